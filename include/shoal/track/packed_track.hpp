#pragma once
/// Tracks held compactly while a batch is read, so that memory stays bounded for big AIS
/// exports: 32 bytes per fix instead of sizeof(Fix), in storage that grows in chunks (no
/// doubling, no reallocation). Exact: every value unpacks to the same double it was packed
/// from. Values as AIS exports write them (positions with up to 7 decimals, heading, COG and
/// SOG with up to 2, line numbers under 2^32) fit in the 32 bytes; any other fix keeps its
/// values in a side table of its track.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <shoal/hull/hull.hpp>
#include <shoal/track/track.hpp>

namespace shoal::track {

/// One fix in 32 bytes (see the file comment).
struct PackedFix {
    double time_s = NAN;
    std::int32_t lat_e7 = 0, lon_e7 = 0;    ///< degrees x 1e7
    std::uint32_t line = 0;
    std::uint32_t extra = 0;                ///< 0, or 1 + index of the exact values in the track's side table
    std::uint16_t heading_c = 0, cog_c = 0, sog_c = 0;  ///< hundredths; `none` for NAN
    std::uint8_t nav_status = nav_status_unknown;       ///< AIS navigational status (kept in the padding)
    static constexpr std::uint16_t none = 0xFFFF;
};
static_assert(sizeof(PackedFix) == 32);

/// The fixes of one track: chunks of 4, 8, ... 256 fixes, then 256 each, so a track never
/// holds more than 256 unused slots (or half its size when small) and nothing is copied as it grows.
class PackedFixes {
public:
    PackedFixes() = default;
    PackedFixes(PackedFixes&& o) noexcept { *this = std::move(o); }
    PackedFixes& operator=(PackedFixes&& o) noexcept {
        if (this == &o) return *this;
        m_chunks = std::move(o.m_chunks);
        m_size = std::exchange(o.m_size, 0);
        m_capacity = std::exchange(o.m_capacity, 0);
        m_next = std::exchange(o.m_next, nullptr);
        m_end = std::exchange(o.m_end, nullptr);
        o.m_chunks.clear();
        return *this;
    }
    std::size_t size() const noexcept { return m_size; }
    bool empty() const noexcept { return m_size == 0; }
    PackedFix& operator[](std::size_t i) noexcept;
    const PackedFix& operator[](std::size_t i) const noexcept;
    void push_back(const PackedFix& f) {
        if (m_next == m_end) return push_back_slow(f);
        *m_next++ = f;
        ++m_size;
    }
    /// Keeps the first `n` fixes (n <= size()); the storage stays.
    void truncate(std::size_t n) noexcept {
        m_size = n < m_size ? n : m_size;
        m_next = m_end = nullptr;
    }
    /// Frees everything.
    void clear() noexcept;
    /// Bytes allocated for fixes.
    std::size_t capacity_bytes() const noexcept;

private:
    static constexpr std::size_t first_chunk = 4, max_chunk = 256, growing_chunks = 7;  // 4 .. 256
    static std::size_t chunk_size(std::size_t k) noexcept { return k < growing_chunks ? first_chunk << k : max_chunk; }
    void push_back_slow(const PackedFix& f);
    std::vector<std::unique_ptr<PackedFix[]>> m_chunks;
    std::size_t m_size = 0, m_capacity = 0;
    PackedFix* m_next = nullptr;  ///< where fix m_size goes, while it is in the last chunk
    PackedFix* m_end = nullptr;   ///< the last chunk's end
};

/// The values of a fix that do not fit in PackedFix.
struct FixExtra {
    double lat = NAN, lon = NAN, heading_deg = NAN, cog_deg = NAN, sog_kn = NAN;
    std::size_t line = 0;
};

/// A Track whose fixes are packed; unpack() gives back the Track (with heading_used_deg and
/// heading_source not yet resolved).
struct PackedTrack {
    std::string id, name, file;
    std::optional<hull::Dimensions> dims;
    double draught_m = NAN;
    std::string dims_source, draught_source;  ///< as Track's
    int ship_type = -1;                       ///< as Track's
    std::string ship_type_source;
    std::string exercise, role;               ///< as Track's
    PackedFixes fixes;
    std::vector<FixExtra> extras;

    std::size_t size() const noexcept { return fixes.size(); }
    void push_back(const Fix& f) { fixes.push_back(pack(f)); }
    /// The fix at `i`, unpacked.
    Fix fix(std::size_t i) const;
    /// Replaces fix `i` (its time may change; the order is the caller's concern).
    void set(std::size_t i, const Fix& f) { fixes[i] = pack(f); }
    /// Every fix unpacked into a Track; id, name and so on copied. The packed fixes stay.
    Track unpack() const;
    /// Frees the fixes (after unpack(), to keep memory bounded while a batch is swept).
    void release_fixes() noexcept;
    /// The same track, packed (the fixes are moved out of `t`).
    static PackedTrack pack(Track&& t);

private:
    PackedFix pack(const Fix& f);
};

/// The same as normalise(Track&, ReadReport&) on a packed track: sorts the fixes by time
/// (stable), drops exact duplicates in time, keeping the first and filling its missing
/// heading, COG and SOG from the repeats; counts and messages in `report`.
void normalise(PackedTrack& track, ReadReport& report);
/// normalise() of every track of `tracks`, in runs of tracks on up to `threads` threads when
/// they hold many fixes: the same tracks, counts and messages (in track order, within the
/// report's limit) as one after another.
void normalise(std::vector<PackedTrack>& tracks, ReadReport& report, unsigned threads);

}  // namespace shoal::track
