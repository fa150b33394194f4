#pragma once
/// The fuzzed entry points, shared by the libFuzzer targets (fuzz_*.cpp, built with clang by
/// scripts/fuzz.sh) and by tests/fuzz_replay_test.cpp, which runs every saved input through
/// them in the normal build. Each function takes arbitrary bytes and must return normally:
/// an InputError (or UsageError) is the expected answer to bad input; anything else (a crash,
/// a sanitizer report, another exception, a broken invariant) is a bug.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include <shoal/exercise/assessment.hpp>
#include <shoal/exercise/exercise.hpp>
#include <shoal/audit/partition.hpp>
#include <shoal/check/detector.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/io/pose_csv.hpp>
#include <shoal/grid/grid_builder.hpp>
#include <shoal/picture/debrief.hpp>
#include <shoal/picture/debrief_record.hpp>
#include <shoal/merge/merge_parts.hpp>
#include <shoal/picture/plot.hpp>
#include <shoal/track/ais.hpp>
#include <shoal/track/csv_reader.hpp>
#include <shoal/track/nmea_reader.hpp>
#include <shoal/track/ogr_reader.hpp>
#include <shoal/track/packed_track.hpp>
#include <shoal/track/reader.hpp>
#include <shoal/track/vessels_table.hpp>
#include <shoal/track/track.hpp>
#include <shoal/util/error.hpp>
#include "util/input_file.hpp"
#include "track/stream_readers.hpp"

namespace shoal::fuzz {

/// A broken invariant: report it and abort (libFuzzer then saves the input).
[[noreturn]] inline void broken(const char* target, const std::string& what) {
    std::fprintf(stderr, "fuzz %s: invariant broken: %s\n", target, what.c_str());
    std::abort();
}

/// Messages quote bad input in short pieces: a 10 MB line must not make a 10 MB message.
inline constexpr std::size_t max_message = 4096;
inline void bounded(const char* target, std::string_view message) {
    if (message.size() > max_message) broken(target, "a message of " + std::to_string(message.size()) + " bytes");
}

/// What every reader promises about the tracks it returns.
inline void check_tracks(const char* target, track::TrackFile& file) {
    for (track::Track& t : file.tracks) {
        for (std::size_t i = 0; i < t.fixes.size(); ++i) {
            const track::Fix& f = t.fixes[i];
            if (!std::isfinite(f.time_s)) broken(target, "fix time is not finite");
            if (!(std::fabs(f.position.lat) <= 90.0) || !(std::fabs(f.position.lon) <= 180.0))
                broken(target, "fix position out of range");
            if (i > 0 && !(t.fixes[i - 1].time_s < f.time_s)) broken(target, "fixes not strictly increasing in time");
            if (!std::isnan(f.heading_deg) && !(f.heading_deg >= 0.0 && f.heading_deg < 360.0)) broken(target, "heading out of range");
            if (!std::isnan(f.cog_deg) && !(f.cog_deg >= 0.0 && f.cog_deg < 360.0)) broken(target, "cog out of range");
            if (!std::isnan(f.sog_kn) && !(f.sog_kn >= 0.0)) broken(target, "sog out of range");
        }
        track::resolve_headings(t);
        for (const track::Fix& f : t.fixes)
            if (!(f.heading_used_deg >= 0.0 && f.heading_used_deg < 360.0)) broken(target, "resolved heading out of [0, 360)");
    }
    // + one note each for the file: "no date", AIS "types not read", AIS reports without a time,
    // and the own ship's join (or its AIVDO of several MMSIs).
    if (file.report.messages.size() > file.report.max_messages + 4)
        broken(target, "more messages kept than the limit");
    for (const std::string& m : file.report.messages) bounded(target, m);
}

/// The first byte chooses options; the rest is the file's text.
inline track::ReadOptions options_from(std::uint8_t flags) {
    track::ReadOptions o;
    if (flags & 1) o.date_s = 1.7e9;
    o.max_messages = flags & 2 ? 0 : 10;
    return o;
}

/// A CSV record as the splitter gives it: its line and fields.
struct Record {
    std::size_t line = 0;
    std::vector<std::string> fields;
    friend bool operator==(const Record&, const Record&) = default;
};

/// The records of `text` split at once.
inline std::vector<Record> records_whole(std::string_view text) {
    std::vector<Record> out;
    track::CsvSplitter split(text);
    std::vector<std::string_view> fields;
    while (split.next(fields)) out.push_back({split.line(), {fields.begin(), fields.end()}});
    return out;
}

/// The records of `text` fed to the splitter in blocks of `block` bytes, as read_csv_packed
/// reads a file (the first block extended to hold the first line; a long record read again
/// with as much more as the buffer holds).
inline std::vector<Record> records_in_blocks(std::string_view text, std::size_t block) {
    std::vector<Record> out;
    std::string buf;
    std::size_t pos = 0;
    auto read_more = [&](std::size_t want) {
        const std::size_t n = std::min(want, text.size() - pos);
        buf.append(text.substr(pos, n));
        pos += n;
        return pos == text.size();
    };
    bool eof = read_more(block);
    while (!eof && !track::CsvSplitter::holds_first_line(buf)) eof = read_more(block);
    track::CsvSplitter split(buf, eof);
    std::vector<std::string_view> fields;
    for (;;) {
        while (split.next(fields)) out.push_back({split.line(), {fields.begin(), fields.end()}});
        if (eof) break;
        buf.erase(0, split.consumed());
        eof = read_more(std::max(block, buf.size()));
        split.more(buf, eof);
    }
    return out;
}

/// Packing a fix and unpacking it gives back the same values (NaN as NaN).
inline void check_packing(const char* target, const std::uint8_t* data, std::size_t size) {
    track::PackedTrack packed;
    std::vector<track::Fix> fixes;
    auto same = [](double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0; };
    for (std::size_t at = 0; at + 48 <= size && fixes.size() < 64; at += 48) {
        double v[6];
        std::memcpy(v, data + at, sizeof v);
        track::Fix f;
        f.time_s = v[0];
        f.position = {v[1], v[2]};
        f.heading_deg = v[3];
        f.cog_deg = v[4];
        f.sog_kn = v[5];
        f.line = at;
        fixes.push_back(f);
        packed.push_back(f);
        // Values as exports write them, which pack without the side table.
        f.position = {std::round(v[1]) / 1e7, std::round(v[2]) / 1e7};
        f.heading_deg = std::round(v[3]) / 100.0;
        fixes.push_back(f);
        packed.push_back(f);
    }
    if (packed.size() != fixes.size()) broken(target, "packed size");
    const track::Track t = packed.unpack();
    for (std::size_t i = 0; i < fixes.size(); ++i) {
        const track::Fix& a = fixes[i];
        const track::Fix& b = t.fixes[i];
        if (!same(a.time_s, b.time_s) || !same(a.position.lat, b.position.lat) || !same(a.position.lon, b.position.lon) ||
            !same(a.heading_deg, b.heading_deg) || !same(a.cog_deg, b.cog_deg) || !same(a.sog_kn, b.sog_kn) || a.line != b.line)
            broken(target, "a packed fix does not unpack to the same values");
    }
}

/// CSV tracks: every dialect the reader detects (separator, header layout, decimal comma,
/// quoting, BOM, CRLF, Latin-1), the format sniffing that sends a file there, reading in
/// blocks (the same records as at once, wherever the blocks end) and packed fixes.
inline void csv_tracks(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return;
    const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
    (void)track::sniff_format(text, "fuzz.csv");
    const std::vector<Record> whole = records_whole(text);
    std::size_t last_line = 0;
    for (const Record& r : whole) {
        if (r.line <= last_line) broken("csv_tracks", "record lines do not increase");
        last_line = r.line;
        if (r.fields.empty()) broken("csv_tracks", "a record without fields");
    }
    if (records_in_blocks(text, 1 + (data[0] >> 2)) != whole) broken("csv_tracks", "records differ when read in blocks");
    check_packing("csv_tracks", data, size);
    (void)track::to_utf8(text);
    try {
        track::TrackFile f = track::read_csv_text(text, "fuzz.csv", options_from(data[0]));
        check_tracks("csv_tracks", f);
    } catch (const InputError& e) {
        bounded("csv_tracks", e.what());
    }
}

/// NMEA 0183 logs.
inline void nmea(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return;
    const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
    (void)track::holds_nmea_sentence(text);
    try {
        track::TrackFile f = track::read_nmea_text(text, "fuzz.nmea", options_from(data[0]));
        if (f.tracks.empty() || f.tracks.front().id != "fuzz")
            broken("nmea", "an NMEA log gives the own ship's track first");
        check_tracks("nmea", f);
    } catch (const InputError& e) {
        bounded("nmea", e.what());
    }
}

/// GeoJSON tracks (Points with times, LineStrings with a times array, any nesting nlohmann
/// accepts).
inline void geojson_tracks(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return;
    const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        track::TrackFile f = track::read_geojson_text(text, "fuzz.geojson", options_from(data[0]));
        check_tracks("geojson_tracks", f);
    } catch (const InputError& e) {
        bounded("geojson_tracks", e.what());
    }
}

/// `!AIVDM,...*hh` with the checksum computed.
inline std::string aivdm_sentence(const std::string& body) {
    unsigned sum = 0;
    for (const char c : body) sum ^= static_cast<unsigned char>(c);
    const char hex[] = "0123456789ABCDEF";
    return "!" + body + '*' + hex[sum >> 4] + hex[sum & 15];
}

/// AIS sentences: the line decoder and the NMEA reader's tracks of them. When the first byte's
/// bit 2 is set, the rest is a payload (each byte's low 6 bits armoured) in well-formed
/// sentences (two fragments when bit 6 is set, a tag block with a time when bit 7 is), so that
/// the fuzzer reaches the message decoding behind the checksum.
inline void aivdm(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return;
    std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    if (data[0] & 4) {
        std::string payload;
        for (std::size_t i = 1; i < size && payload.size() < 200; ++i) {
            const int v = data[i] & 63;
            payload += static_cast<char>(v < 40 ? v + 48 : v + 56);
        }
        const std::string fill = std::to_string((data[0] >> 3) % 6);
        const std::string tag = data[0] & 128 ? "\\c:1700000000*5F\\" : "";
        if (data[0] & 64) {
            const std::size_t half = payload.size() / 2;
            text = tag + aivdm_sentence("AIVDM,2,1,3,A," + payload.substr(0, half) + ",0") + "\n" +
                   aivdm_sentence("AIVDM,2,2,3,A," + payload.substr(half) + "," + fill) + "\n";
        } else {
            text = tag + aivdm_sentence("AIVDM,1,1,,B," + payload + "," + fill) + "\n";
        }
        text += "$GPZDA,120000,15,08,2014,00,00*40\n" + text;  // the same after a clock
    }
    std::vector<std::string> problems;
    for (const track::ais::Decoded& d : track::ais::decode_lines(text, &problems)) {
        const track::ais::Message& m = d.message;
        if (m.position && !(std::fabs(m.position->lon) <= 180.0 && std::fabs(m.position->lat) <= 90.0))
            broken("aivdm", "a position off the globe");
        if (!std::isnan(m.sog_kn) && !(m.sog_kn >= 0.0 && m.sog_kn < 102.3)) broken("aivdm", "sog out of range");
        if (!std::isnan(m.cog_deg) && !(m.cog_deg >= 0.0 && m.cog_deg < 360.0)) broken("aivdm", "cog out of range");
        if (!std::isnan(m.heading_deg) && !(m.heading_deg >= 0.0 && m.heading_deg < 360.0)) broken("aivdm", "heading out of range");
        if (m.dims && !(m.dims->a > 0 && m.dims->b > 0 && m.dims->c > 0 && m.dims->d > 0)) broken("aivdm", "a dimension <= 0");
        if (!std::isnan(m.draught_m) && !(m.draught_m > 0.0)) broken("aivdm", "draught <= 0");
        if (m.name.size() > 20) broken("aivdm", "a name of more than 20 characters");
        if (d.line == 0) broken("aivdm", "a message without its line");
    }
    for (const std::string& p : problems) bounded("aivdm", p);
    try {
        track::TrackFile f = track::read_nmea_text(text, "fuzz.nmea", options_from(data[0]));
        if (f.tracks.empty() || f.tracks.front().id != "fuzz") broken("aivdm", "an NMEA log gives the own ship's track first");
        check_tracks("aivdm", f);
    } catch (const InputError& e) {
        bounded("aivdm", e.what());
    }
}

/// Ship files (and the --dims text, which is just as hostile).
inline void ship(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const hull::Hull h = hull::Hull::parse(text, "fuzz.json");
        if (h.contour().size() < 3) broken("ship", "a hull with fewer than 3 points");
        if (!std::isfinite(h.radius()) || !(h.radius() > 0)) broken("ship", "hull radius not finite and > 0");
        const auto placed = h.placed({1000.0, -2000.0}, 37.5);
        for (const auto p : placed)
            if (!std::isfinite(p.x) || !std::isfinite(p.y)) broken("ship", "placed hull point not finite");
    } catch (const InputError& e) {
        bounded("ship", e.what());
    }
    if (size < 200) {
        try {
            (void)hull::Hull::from_dims_string(std::string(text));
        } catch (const InputError& e) {
            bounded("ship", e.what());
        }
    }
}

/// GPX tracks, as OGR's GPX driver reads them (tracks, routes, waypoints; times, names),
/// from a /vsimem/ file: the reader shoal uses for a GPX file or a GPX on a pipe.
inline void gpx_tracks(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return;
    const shoal::detail::MemoryFile memory(std::string(reinterpret_cast<const char*>(data) + 1, size - 1), ".gpx");
    try {
        track::TrackFile f = track::detail::read_gpx_at(memory.path(), "fuzz.gpx", options_from(data[0]));
        check_tracks("gpx_tracks", f);
    } catch (const InputError& e) {
        bounded("gpx_tracks", e.what());
    }
}

/// Vessels tables (track::read_vessels, then merge_vessels of the table into itself read
/// again): every vessel kept has an id, plausible dimensions and a draught in range; every
/// warning is short and names the file; the table merged with itself disagrees about nothing.
inline void vessels(const std::uint8_t* data, std::size_t size) {
    const shoal::detail::MemoryFile memory(std::string(reinterpret_cast<const char*>(data), size), ".csv");
    try {
        std::vector<std::string> warnings;
        auto table = track::read_vessels(memory.path(), &warnings);
        if (warnings.size() > 11) broken("vessels", "more warnings than the first ten and a count");
        for (const std::string& w : warnings) {
            bounded("vessels", w);
            if (w.rfind(memory.path(), 0) != 0) broken("vessels", "a warning that does not name the file");
        }
        for (const auto& [id, v] : table) {
            if (id.empty()) broken("vessels", "a vessel without an id");
            if (v.dims && !(v.dims->a > 0 && v.dims->b > 0 && v.dims->c > 0 && v.dims->d > 0 && hull::Hull::plausible(*v.dims)))
                broken("vessels", "dimensions kept that no ship has");
            if (!std::isnan(v.draught_m) && !(v.draught_m > 0 && v.draught_m <= track::max_draught_m)) broken("vessels", "draught out of range");
        }
        std::map<std::string, track::VesselInfo> all;
        const std::size_t n = table.size();
        track::merge_vessels(all, std::move(table), "a", &warnings);
        track::merge_vessels(all, track::read_vessels(memory.path()), "b", &warnings);
        if (all.size() != n) broken("vessels", "the same table merged twice gives other vessels");
        if (warnings.size() > 11) broken("vessels", "the same table disagrees with itself");
    } catch (const InputError& e) {
        bounded("vessels", e.what());
    }
}

/// Zip files read as folders (detail::zip_members, and the central directory read by
/// zip_entry_names for the members GDAL does not list): no more names than entries fit in the
/// bytes; every member a /vsizip/ path of the file; every note short and naming the file.
inline void zip_members(const std::uint8_t* data, std::size_t size) {
    const shoal::detail::MemoryFile memory(std::string(reinterpret_cast<const char*>(data), size), ".zip");
    const std::vector<std::string> names = shoal::detail::zip_entry_names(memory.path());
    if (names.size() > size / 46 + 1) broken("zip_members", "more names than central directory entries fit in the file");
    std::vector<std::string> notes;
    for (const std::string& m : shoal::detail::zip_members(memory.path(), &notes))
        if (m.rfind("/vsizip/", 0) != 0) broken("zip_members", "a member that is not a /vsizip/ path");
    if (notes.size() > 11) broken("zip_members", "more notes than the first ten and a count");
    for (const std::string& n : notes) {
        bounded("zip_members", n);
        if (n.rfind(memory.path(), 0) != 0) broken("zip_members", "a note that does not name the file");
    }
}

inline constexpr std::size_t grid_header_size = 8 + 4 + 4 + 8 + 8;

/// Grid cache files. When the first byte is odd, the rest gets a correct payload size and
/// checksum written into its header before parsing, so the fuzzer reaches the payload's
/// checks (a checksum guards against damage, not against a wrong writer); when even, the
/// bytes are parsed as they are. A grid that loads must also work: cells queried, poses
/// checked, and a save/load round trip giving the same bytes.
inline void grid_cache(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return;
    std::vector<char> bytes(reinterpret_cast<const char*>(data) + 1, reinterpret_cast<const char*>(data) + size);
    if ((data[0] & 1) && bytes.size() >= grid_header_size) {
        const std::uint64_t payload = bytes.size() - grid_header_size;
        const std::uint64_t sum = XXH3_64bits(bytes.data() + grid_header_size, payload);
        std::memcpy(bytes.data() + 16, &payload, 8);
        std::memcpy(bytes.data() + 24, &sum, 8);
    }
    try {
        const grid::CoastGrid g = grid::GridFile::parse(bytes, "fuzz.shoalgrid");
        (void)g.land_cell_count();
        (void)g.memory_bytes();
        const geo::Box e = g.extent();
        const geo::XY probes[] = {{(e.minx + e.maxx) / 2, (e.miny + e.maxy) / 2},
                                  {e.minx, e.miny},
                                  {e.maxx, e.maxy},
                                  {e.minx + g.cell_size() * 0.5, e.miny + g.cell_size() * 1.5},
                                  {e.minx - 100.0, e.maxy + 100.0}};
        for (const geo::XY p : probes) (void)g.is_land(p);
        if (data[0] & 2) {
            const hull::Hull h = hull::Hull::from_dimensions({20, 5, 3, 3});
            const check::Detector det(g, h);
            for (const geo::XY p : probes) {
                check::LocalPose pose;
                pose.position = p;
                (void)det.check(pose, {g.cell_size() * 3, true});
            }
        }
        // Saving normalises (a flag byte becomes 0 or 1); after that a round trip is exact.
        const std::vector<char> saved = grid::GridFile::serialize(g);
        if (grid::GridFile::serialize(grid::GridFile::parse(saved, "fuzz-saved.shoalgrid")) != saved)
            broken("grid_cache", "a saved grid does not load and save to the same bytes");
    } catch (const InputError& e) {
        bounded("grid_cache", e.what());
    } catch (const UsageError& e) {
        bounded("grid_cache", e.what());
    }
}

/// Exercise files (`check --roles`: audit::Roles::parse): an entry read has a track id and
/// its role can be looked up; messages are short.
inline void roles(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const audit::Roles r = audit::Roles::parse(text, "fuzz.json");
        for (const auto& e : r.entries) {
            if (e.track.empty()) broken("roles", "an entry without a track");
            (void)r.role_of(e.exercise, e.track);  // the lookup, under the sanitizers
        }
    } catch (const InputError& e) {
        bounded("roles", e.what());
    }
}

/// Assessment files (audit::Assessment::parse, check --assess): every criterion kept has a
/// unique non-empty id, a finite limit and penalty >= 0, and an area (a closed ring of at
/// least 4 points on the globe) exactly when its kind takes one.
inline void assessment(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const audit::Assessment a = audit::Assessment::parse(text, "fuzz.json");
        if (a.criteria.empty()) broken("assessment", "no criteria, no error");
        std::vector<std::string> ids;
        for (const audit::Criterion& c : a.criteria) {
            if (c.id.empty()) broken("assessment", "a criterion without an id");
            ids.push_back(c.id);
            if (!(std::isfinite(c.limit) && c.limit >= 0) || !(std::isfinite(c.penalty) && c.penalty >= 0))
                broken("assessment", "a limit or penalty that is not a finite number >= 0");
            const bool area = c.kind == audit::CriterionKind::speed_limit || c.kind == audit::CriterionKind::no_entry;
            if (area != !c.area.empty()) broken("assessment", "an area where the kind takes none, or none where it needs one");
            if (area && (c.area.size() < 4 || !(c.area.front() == c.area.back()))) broken("assessment", "an area that is not a closed ring");
            for (const geo::LonLat& p : c.area)
                if (!(std::fabs(p.lon) <= 180.0) || !(std::fabs(p.lat) <= 90.0)) broken("assessment", "an area corner off the globe");
        }
        std::sort(ids.begin(), ids.end());
        if (std::adjacent_find(ids.begin(), ids.end()) != ids.end()) broken("assessment", "two criteria with one id");
        (void)a.watch_clearance_m();
    } catch (const InputError& e) {
        bounded("assessment", e.what());
    }
}

/// The poses of `shoal probe` (io::parse_pose_csv): every pose kept is on the globe with a
/// finite heading and its line; at most a few messages, each short.
inline void poses(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const io::PoseFile f = io::parse_pose_csv(text, "fuzz.csv");
        for (const io::PoseRow& p : f.poses) {
            if (!(std::fabs(p.lat) <= 90.0) || !(std::fabs(p.lon) <= 180.0)) broken("poses", "a pose off the globe");
            if (!std::isfinite(p.heading_deg)) broken("poses", "a heading that is not finite");
            if (p.line == 0) broken("poses", "a pose without its line");
        }
        if (f.errors.size() > f.skipped) broken("poses", "more messages than bad rows");
        for (const std::string& m : f.errors) bounded("poses", m);
    } catch (const InputError& e) {
        bounded("poses", e.what());
    }
}

/// Shards' reports merged (`shoal merge`: report::merge_geojson), from /vsimem/ files as the
/// merge reads files: the input is the parts one after another, separated by a NUL byte (which
/// JSON text never holds), at most four. A merge gives a JSON text or a short InputError.
inline void merge_parts(const std::uint8_t* data, std::size_t size) {
    const std::string_view all(reinterpret_cast<const char*>(data), size);
    std::vector<std::unique_ptr<shoal::detail::MemoryFile>> files;
    std::vector<std::string> paths;
    for (std::size_t from = 0; from <= all.size() && files.size() < 4;) {
        const std::size_t nul = std::min(all.find('\0', from), all.size());
        files.push_back(std::make_unique<shoal::detail::MemoryFile>(std::string(all.substr(from, nul - from)), ".geojson"));
        paths.push_back(files.back()->path());
        from = nul + 1;
    }
    try {
        const std::string merged = report::merge_geojson(paths);
        if (!nlohmann::json::accept(merged)) broken("merge_parts", "a merged report that is not JSON");
    } catch (const InputError& e) {
        bounded("merge_parts", e.what());
    }
}

/// A small grid for drawing: an island of 2 km off (0 N, 0 E), built once.
inline const grid::CoastGrid& drawing_grid() {
    static const grid::CoastGrid g = [] {
        const shoal::detail::MemoryFile island(
            R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":{"type":"Polygon",)"
            R"("coordinates":[[[0,0],[0.02,0],[0.02,0.02],[0,0.02],[0,0]]]}}]})",
            ".geojson");
        grid::BuildRequest r;
        r.cell_m = 1000;
        return grid::build_grid({island.path()}, r, nullptr);
    }();
    return g;
}

/// A shard's debrief record (`merge --debrief/--plot`: report::parse_debrief_record, then
/// join_debrief_records and the debrief's pages and the picture drawn from it, as merge
/// does): a record, or a short InputError; the pages and the picture of whatever it holds are
/// drawn without a crash, a hang or a sanitizer report.
inline void debrief_record(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        report::DebriefRecord rec = report::parse_debrief_record(bytes, "fuzz.debrief.cbor");
        const report::RunInfo info = rec.info;
        std::vector<report::DebriefRecord> records;
        records.push_back(std::move(rec));
        const audit::AuditResult run = report::join_debrief_records(std::move(records), {0}, {true});
        const grid::CoastGrid& g = drawing_grid();
        for (const report::DebriefPage& page : report::debrief_pages(run))
            if (report::debrief_html(run, g, info, page).find("</html>") == std::string::npos) broken("debrief_record", "a page cut short");
        if (report::plot_svg(run, g).find("</svg>") == std::string::npos) broken("debrief_record", "a picture cut short");
    } catch (const InputError& e) {
        bounded("debrief_record", e.what());
    }
}

/// The files of `check --partitions` and of `--traffic-only`, read back as a partition's audit
/// reads them (audit::read_partition of a one-partition folder, read_traffic). The input is
/// three bodies: [u16 n][n bytes of the index's body][u16 m][m bytes of partition 0's body][the
/// traffic's body]; each file gets shoal's header (its magic and this build's layout; the index
/// the input's name, the traffic the partitions' key) so the bodies are what is fuzzed. Seeds:
/// the files of a real run, headers cut off. A partition read holds a position for each track;
/// anything else is an InputError under 4 KB.
inline void partitions(const std::uint8_t* data, std::size_t size) {
    std::string_view in(reinterpret_cast<const char*>(data), size);
    const auto take = [&in]() {
        if (in.size() < 2) return std::string();
        const std::size_t n = std::min<std::size_t>(static_cast<unsigned char>(in[0]) | static_cast<std::size_t>(static_cast<unsigned char>(in[1])) << 8, in.size() - 2);
        std::string body(in.substr(2, n));
        in.remove_prefix(2 + n);
        return body;
    };
    const std::string index_body = take(), part_body = take(), traffic_body(in);
    const std::uint64_t layout = sizeof(track::PackedFix) * 1000 + sizeof(track::FixExtra);
    const auto u64 = [](std::uint64_t v) { return std::string(reinterpret_cast<const char*>(&v), sizeof v); };
    const auto str = [&](const std::string& v) { return u64(v.size()) + v; };
    // A folder of this process's own, removed at exit.
    struct Folder {
        std::filesystem::path path = std::filesystem::temp_directory_path() / ("shoal-fuzz-partitions-" + std::to_string(::getpid()));
        Folder() { std::filesystem::create_directories(path / "in"); }
        ~Folder() {
            std::error_code ec;
            std::filesystem::remove_all(path, ec);
        }
    };
    static const Folder folder;
    const std::filesystem::path dir = folder.path / "in";
    const auto put = [](const std::filesystem::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; };
    put(dir / "index.bin", std::string("SHOALPI1", 8) + u64(layout) + str("fuzz.csv") + index_body);
    put(dir / "part-00000.bin", std::string("SHOALPT1", 8) + u64(layout) + part_body);
    try {
        std::vector<std::size_t> positions;
        std::vector<std::string> ids;
        const audit::ReadResult r = audit::read_partition({dir.string()}, {"fuzz.csv"}, {}, audit::Shard{0, 1}, positions, &ids);
        if (positions.size() != r.tracks.size()) broken("partitions", "a track without its position");
        for (const std::size_t p : positions)
            if (p >= ids.size()) broken("partitions", "a position beyond the run's tracks");
        for (const std::string& w : r.warnings) bounded("partitions", w);
    } catch (const InputError& e) {
        bounded("partitions", e.what());
    }
    try {
        const std::string key = audit::traffic_key({dir.string()}, 0, "fuzz");
        const std::filesystem::path traffic = dir.parent_path() / "traffic.bin";
        put(traffic, std::string("SHOALTF1", 8) + u64(layout) + u64(0) + u64(1) + str(key) + traffic_body);
        (void)audit::read_traffic({traffic.string()}, audit::Shard{0, 1}, key);
    } catch (const InputError& e) {
        bounded("partitions", e.what());
    }
}

}  // namespace shoal::fuzz
