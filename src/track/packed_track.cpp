#include <shoal/track/packed_track.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "util/parallel.hpp"

namespace shoal::track {

namespace {

/// `v` as an integer multiple of 1/scale when that reads back as exactly `v`.
template <typename Int>
bool scaled(double v, double scale, Int lo, Int hi, Int& out) noexcept {
    // The nearest integer to v * scale by adding and taking away 1.5 * 2^52 (exact below 2^51;
    // which one of two equally near is taken does not matter: neither passes the test below).
    const double x = v * scale;
    if (!(x >= static_cast<double>(lo) - 1 && x <= static_cast<double>(hi) + 1)) return false;  // NaN and infinities too
    constexpr double magic = 6755399441055744.0;
    const double s = (x + magic) - magic;  // IEEE arithmetic: not folded (no -ffast-math)
    if (!(s >= static_cast<double>(lo) && s <= static_cast<double>(hi))) return false;
    if (s / scale != v || (s == 0.0 && std::signbit(v))) return false;  // -0.0 stays exact too
    out = static_cast<Int>(s);
    return true;
}

/// Heading, COG and SOG in hundredths (`PackedFix::none` for NAN); false when not exact.
bool hundredths(double v, std::uint16_t& out) noexcept {
    if (std::isnan(v)) {
        out = PackedFix::none;
        return true;
    }
    return scaled<std::uint16_t>(v, 100.0, 0, PackedFix::none - 1, out);
}

double from_hundredths(std::uint16_t c) noexcept { return c == PackedFix::none ? NAN : c / 100.0; }

}  // namespace

// ---------------------------------------------------------------------------------------------

PackedFix& PackedFixes::operator[](std::size_t i) noexcept {
    return const_cast<PackedFix&>(static_cast<const PackedFixes&>(*this)[i]);
}

const PackedFix& PackedFixes::operator[](std::size_t i) const noexcept {
    constexpr std::size_t growing_total = first_chunk * ((std::size_t{1} << growing_chunks) - 1);  // 508
    if (i < growing_total) {
        const std::size_t k = static_cast<std::size_t>(std::bit_width(i / first_chunk + 1)) - 1;
        return m_chunks[k][i - first_chunk * ((std::size_t{1} << k) - 1)];
    }
    const std::size_t j = i - growing_total;
    return m_chunks[growing_chunks + j / max_chunk][j % max_chunk];
}

void PackedFixes::push_back_slow(const PackedFix& f) {
    if (m_size == m_capacity) {  // a new chunk, filled from its start
        const std::size_t n = chunk_size(m_chunks.size());
        m_chunks.push_back(std::make_unique_for_overwrite<PackedFix[]>(n));
        m_capacity += n;
        m_next = m_chunks.back().get();
        m_end = m_next + n;
        *m_next++ = f;
        ++m_size;
        return;
    }
    (*this)[m_size++] = f;  // after truncate(): until the next chunk
}

void PackedFixes::clear() noexcept {
    m_chunks.clear();
    m_chunks.shrink_to_fit();
    m_size = m_capacity = 0;
    m_next = m_end = nullptr;
}

std::size_t PackedFixes::capacity_bytes() const noexcept { return m_capacity * sizeof(PackedFix); }

// ---------------------------------------------------------------------------------------------

PackedFix PackedTrack::pack(const Fix& f) {
    PackedFix p;
    p.time_s = f.time_s;
    p.nav_status = f.nav_status;
    const bool fits = scaled<std::int32_t>(f.position.lat, 1e7, -900000000, 900000000, p.lat_e7) &&
                      scaled<std::int32_t>(f.position.lon, 1e7, -1800000000, 1800000000, p.lon_e7) &&
                      hundredths(f.heading_deg, p.heading_c) && hundredths(f.cog_deg, p.cog_c) &&
                      hundredths(f.sog_kn, p.sog_c) && f.line <= std::numeric_limits<std::uint32_t>::max();
    if (fits) {
        p.line = static_cast<std::uint32_t>(f.line);
        return p;
    }
    extras.push_back({f.position.lat, f.position.lon, f.heading_deg, f.cog_deg, f.sog_kn, f.line});
    p.extra = static_cast<std::uint32_t>(extras.size());
    return p;
}

Fix PackedTrack::fix(std::size_t i) const {
    const PackedFix& p = fixes[i];
    Fix f;
    f.time_s = p.time_s;
    f.nav_status = p.nav_status;
    if (p.extra) {
        const FixExtra& e = extras[p.extra - 1];
        f.position = {e.lon, e.lat};
        f.heading_deg = e.heading_deg;
        f.cog_deg = e.cog_deg;
        f.sog_kn = e.sog_kn;
        f.line = e.line;
        return f;
    }
    f.position = {p.lon_e7 / 1e7, p.lat_e7 / 1e7};
    f.heading_deg = from_hundredths(p.heading_c);
    f.cog_deg = from_hundredths(p.cog_c);
    f.sog_kn = from_hundredths(p.sog_c);
    f.line = p.line;
    return f;
}

Track PackedTrack::unpack() const {
    Track t;
    t.id = id;
    t.name = name;
    t.file = file;
    t.dims = dims;
    t.draught_m = draught_m;
    t.dims_source = dims_source;
    t.draught_source = draught_source;
    t.ship_type = ship_type;
    t.ship_type_source = ship_type_source;
    t.exercise = exercise;
    t.role = role;
    t.fixes.reserve(fixes.size());
    for (std::size_t i = 0; i < fixes.size(); ++i) t.fixes.push_back(fix(i));
    return t;
}

void PackedTrack::release_fixes() noexcept {
    fixes.clear();
    extras.clear();
    extras.shrink_to_fit();
}

PackedTrack PackedTrack::pack(Track&& t) {
    PackedTrack p;
    p.id = std::move(t.id);
    p.name = std::move(t.name);
    p.file = std::move(t.file);
    p.dims = t.dims;
    p.draught_m = t.draught_m;
    p.dims_source = t.dims_source;
    p.draught_source = t.draught_source;
    p.ship_type = t.ship_type;
    p.ship_type_source = t.ship_type_source;
    p.exercise = std::move(t.exercise);
    p.role = std::move(t.role);
    for (const Fix& f : t.fixes) p.push_back(f);
    t.fixes.clear();
    t.fixes.shrink_to_fit();
    return p;
}

void normalise(PackedTrack& track, ReadReport& report) {
    const std::size_t n = track.size();
    bool plain = true;  // every time finite, in order
    for (std::size_t i = 0; i < n && plain; ++i)
        plain = std::isfinite(track.fixes[i].time_s) && (i == 0 || !(track.fixes[i].time_s < track.fixes[i - 1].time_s));
    if (!plain) {
        // Out of order (rare in real exports): normalise this one track unpacked, then pack it again.
        Track t = track.unpack();
        normalise(t, report);
        track.release_fixes();
        for (const Fix& f : t.fixes) track.push_back(f);
        return;
    }
    // In order: drop repeated times in place, as normalise(Track&) does.
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (kept > 0 && track.fixes[i].time_s == track.fixes[kept - 1].time_s) {
            Fix k = track.fix(kept - 1);
            const Fix r = track.fix(i);
            if (std::isnan(k.heading_deg)) k.heading_deg = r.heading_deg;
            if (std::isnan(k.cog_deg)) k.cog_deg = r.cog_deg;
            if (std::isnan(k.sog_kn)) k.sog_kn = r.sog_kn;
            track.set(kept - 1, k);
            ++report.duplicates;
            continue;
        }
        if (kept != i) track.fixes[kept] = track.fixes[i];
        ++kept;
    }
    track.fixes.truncate(kept);
}

void normalise(std::vector<PackedTrack>& tracks, ReadReport& report, unsigned threads) {
    std::vector<std::size_t> fixes;
    std::size_t all = 0;
    for (const PackedTrack& t : tracks) {
        fixes.push_back(t.size());
        all += t.size();
    }
    constexpr std::size_t worth_a_thread = 65536;  // fixes: fewer are normalised sooner than a thread starts
    const std::size_t runs = std::clamp<std::size_t>(std::min<std::size_t>(threads, all / worth_a_thread), 1, std::max<std::size_t>(1, tracks.size()));
    if (runs == 1) {
        for (PackedTrack& t : tracks) normalise(t, report);
        return;
    }
    const std::vector<std::size_t> start = shoal::detail::weighted_runs(fixes, runs);
    std::vector<ReadReport> found(runs);
    for (ReadReport& f : found) f.max_messages = report.max_messages;
    shoal::detail::parallel_blocks(runs, static_cast<unsigned>(runs), [&](std::size_t b, unsigned) {
        for (std::size_t k = start[b]; k < start[b + 1]; ++k) normalise(tracks[k], found[b]);
    });
    // Each run's report as its rows would have come one after another: its first messages
    // (each run kept as many as the report can) kept while the report has room.
    for (const ReadReport& f : found) {
        report.duplicates += f.duplicates;
        report.reordered += f.reordered;
        for (const std::string& m : f.messages) report.skip(m);
        report.skipped += f.skipped - f.messages.size();
    }
}

}  // namespace shoal::track
