// A run's fixes shuffled by vessel into partitions on disk (audit/partition.hpp).
#include <shoal/audit/partition.hpp>

#include <unistd.h>
#define XXH_INLINE_ALL
#include <xxhash.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>

#include <shoal/shard/shard.hpp>
#include "track/merge.hpp"
#include <shoal/track/reader.hpp>
#include <shoal/track/time.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>

#include "read_files.hpp"
#include "util/mapped_file.hpp"

namespace shoal::audit {

namespace {

namespace fs = std::filesystem;

// The layout of this build: raw packed fixes and their side values are written as they lie in
// memory, so a file of another build (another layout) is refused, never misread.
constexpr char magic_index[8] = {'S', 'H', 'O', 'A', 'L', 'P', 'I', '1'};
constexpr char magic_part[8] = {'S', 'H', 'O', 'A', 'L', 'P', 'T', '1'};
constexpr char magic_traffic[8] = {'S', 'H', 'O', 'A', 'L', 'T', 'F', '1'};
constexpr std::uint32_t layout = sizeof(track::PackedFix) * 1000 + sizeof(track::FixExtra);

class Writer {
public:
    void raw(const void* p, std::size_t n) { m_out.append(static_cast<const char*>(p), n); }
    void u64(std::uint64_t v) { raw(&v, sizeof v); }
    void f64(double v) { raw(&v, sizeof v); }
    void str(const std::string& s) {
        u64(s.size());
        raw(s.data(), s.size());
    }
    void strs(const std::vector<std::string>& v) {
        u64(v.size());
        for (const auto& s : v) str(s);
    }
    const std::string& bytes() const noexcept { return m_out; }

private:
    std::string m_out;
};

class Reader {
public:
    // Partition files run to hundreds of megabytes a task: mapped, not read into a zeroed string.
    explicit Reader(std::string path)
        : m_file(std::make_unique<detail::MappedFile>(path, [&](detail::MappedFile::Failure, const std::string& reason) {
              return path + ": cannot read (" + reason + ")";
          })),
          m_in(m_file->bytes().data(), m_file->bytes().size()),
          m_path(std::move(path)) {}
    void raw(void* p, std::size_t n) {
        if (n > m_in.size() - m_at) throw InputError(m_path + ": a partition file cut short (was it written by another run, or is the disk full?)");
        std::memcpy(p, m_in.data() + m_at, n);
        m_at += n;
    }
    std::uint64_t u64() {
        std::uint64_t v = 0;
        raw(&v, sizeof v);
        return v;
    }
    double f64() {
        double v = 0;
        raw(&v, sizeof v);
        return v;
    }
    std::size_t count(std::size_t each) {  // a count of items of at least `each` bytes, checked against what is left
        const std::uint64_t n = u64();
        if (each > 0 && n > (m_in.size() - m_at) / each) throw InputError(m_path + ": a partition file cut short or corrupt");
        return static_cast<std::size_t>(n);
    }
    std::string str() {
        const std::size_t n = count(1);
        std::string s(m_in.data() + m_at, n);
        m_at += n;
        return s;
    }
    std::vector<std::string> strs() {
        std::vector<std::string> v(count(8));
        for (auto& s : v) s = str();
        return v;
    }
    void header(const char (&magic)[8]) {
        char m[8];
        raw(m, sizeof m);
        if (std::memcmp(m, magic, sizeof m) != 0 || u64() != layout)
            throw InputError(m_path + ": not a partition file of this shoal (written by another version, or another file)");
    }
    bool done() const noexcept { return m_at == m_in.size(); }
    const std::string& path() const noexcept { return m_path; }

private:
    std::unique_ptr<detail::MappedFile> m_file;
    std::string_view m_in;
    std::size_t m_at = 0;
    std::string m_path;
};

void write_file(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) throw InputError("cannot write '" + path + "' (disk full?)");
}

Reader open_file(const std::string& path) { return Reader(path); }

std::string part_name(unsigned k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "part-%05u.bin", k);
    return buf;
}

void put_report(Writer& w, const track::ReadReport& r) {
    for (std::size_t v : {r.rows, r.skipped, r.duplicates, r.reordered, r.max_messages, r.skips_said}) w.u64(v);
    w.strs(r.messages);
}
track::ReadReport get_report(Reader& in) {
    track::ReadReport r;
    for (std::size_t* v : {&r.rows, &r.skipped, &r.duplicates, &r.reordered, &r.max_messages, &r.skips_said}) *v = in.u64();
    r.messages = in.strs();
    return r;
}

void put_track(Writer& w, const track::PackedTrack& t) {
    for (const std::string* s : {&t.id, &t.name, &t.file, &t.dims_source, &t.draught_source, &t.ship_type_source, &t.exercise, &t.role}) w.str(*s);
    w.u64(t.dims ? 1 : 0);
    if (t.dims)
        for (double v : {t.dims->a, t.dims->b, t.dims->c, t.dims->d}) w.f64(v);
    w.f64(t.draught_m);
    w.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(t.ship_type)));
    w.u64(t.fixes.size());
    for (std::size_t i = 0; i < t.fixes.size(); ++i) w.raw(&t.fixes[i], sizeof(track::PackedFix));
    w.u64(t.extras.size());
    if (!t.extras.empty()) w.raw(t.extras.data(), t.extras.size() * sizeof(track::FixExtra));
}
track::PackedTrack get_track(Reader& in) {
    track::PackedTrack t;
    for (std::string* s : {&t.id, &t.name, &t.file, &t.dims_source, &t.draught_source, &t.ship_type_source, &t.exercise, &t.role}) *s = in.str();
    if (in.u64()) {
        hull::Dimensions d;
        for (double* v : {&d.a, &d.b, &d.c, &d.d}) *v = in.f64();
        t.dims = d;
    }
    t.draught_m = in.f64();
    t.ship_type = static_cast<int>(static_cast<std::int64_t>(in.u64()));
    const std::size_t n = in.count(sizeof(track::PackedFix));
    for (std::size_t i = 0; i < n; ++i) {
        track::PackedFix f;
        in.raw(&f, sizeof f);
        t.fixes.push_back(f);
    }
    t.extras.resize(in.count(sizeof(track::FixExtra)));
    if (!t.extras.empty()) in.raw(t.extras.data(), t.extras.size() * sizeof(track::FixExtra));
    return t;
}

/// What a partition folder's index holds.
struct Index {
    std::string input;
    unsigned count = 0;
    std::string read_key;  ///< the read options that change what is read
    std::vector<FileResult> files;
    std::vector<std::vector<std::string>> ids;  ///< each file's track ids, in file order
};

/// The read options that change what is read, one "field value" line each (field as the
/// library names it; in_terms_of gives the front end's name).
std::string read_key(const track::ReadOptions& o) {
    const auto named = [](const std::string& v) { return v.empty() ? std::string("none") : "'" + v + "'"; };
    return "ReadOptions::date_s " + (o.date_s ? track::format_iso8601(*o.date_s, 0).substr(0, 10) : std::string("none")) +
           "\nReadOptions::hull_from_length_width " + (o.hull_from_length_width ? "on" : "off") + "\nReadOptions::max_messages " +
           std::to_string(o.max_messages) + "\nReadOptions::exercise_column " + named(o.exercise_column) + "\nReadOptions::role_column " +
           named(o.role_column) + "\n";
}

/// The first line in which two read_keys differ, as "FIELD A" and "FIELD B" (empty when equal).
std::pair<std::string, std::string> first_difference(const std::string& a, const std::string& b) {
    std::size_t i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
        const std::size_t ei = std::min(a.find('\n', i), a.size()), ej = std::min(b.find('\n', j), b.size());
        if (a.compare(i, ei - i, b, j, ej - j) != 0) return {a.substr(i, ei - i), b.substr(j, ej - j)};
        i = ei + 1;
        j = ej + 1;
    }
    return {};
}

Index read_index(const std::string& dir) {
    Reader in = open_file((fs::path(dir) / "index.bin").string());
    in.header(magic_index);
    Index x;
    x.input = in.str();
    x.count = static_cast<unsigned>(in.u64());
    x.read_key = in.str();
    x.files.resize(in.count(8));
    x.ids.resize(x.files.size());
    for (std::size_t k = 0; k < x.files.size(); ++k) {
        FileResult& f = x.files[k];
        f.file = in.str();
        f.format = in.str();
        f.error = in.str();
        f.tracks = in.u64();
        f.read = get_report(in);
        f.size = static_cast<long long>(static_cast<std::int64_t>(in.u64()));
        f.fingerprint = in.str();
        x.ids[k] = in.strs();
    }
    if (!in.done()) throw InputError(in.path() + ": a partition index with more than it should hold");
    return x;
}

}  // namespace

PartitionSummary write_partitions(const std::string& dir, const std::string& input, const track::ReadOptions& options, unsigned count,
                                  unsigned jobs, const std::function<std::pair<long long, std::string>(const FileResult&)>& fingerprint) {
    if (count == 0) throw UsageError("write_partitions: the count of partitions must be at least 1");
    std::error_code ec;
    if (fs::symlink_status(dir, ec).type() != fs::file_type::not_found)
        throw InputError("'" + dir + "' exists: partitions are written to a new folder, nothing replaced");
    const std::vector<std::string> files = track::expand_inputs({input});
    std::vector<track::PackedTrackFile> read;
    std::vector<FileResult> results;
    read_track_files(files, options, jobs, read, results,
                     [&](std::size_t k) { std::tie(results[k].size, results[k].fingerprint) = fingerprint(results[k]); });
    PartitionSummary summary;
    Writer index;
    index.raw(magic_index, sizeof magic_index);
    index.u64(layout);
    index.str(input);
    index.u64(count);
    index.str(read_key(options));
    index.u64(files.size());
    std::vector<std::vector<std::pair<std::size_t, std::size_t>>> where(count);  // (file, track) in each partition
    for (std::size_t k = 0; k < files.size(); ++k) {
        const FileResult& f = results[k];
        index.str(f.file);
        index.str(f.format);
        index.str(f.error);
        index.u64(f.tracks);
        put_report(index, f.read);
        index.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(f.size)));
        index.str(f.fingerprint);
        index.u64(read[k].tracks.size());
        for (std::size_t i = 0; i < read[k].tracks.size(); ++i) {
            const track::PackedTrack& t = read[k].tracks[i];
            index.str(t.id);
            where[shard_of(shard_key(t.id, std::nullopt), count)].push_back({k, i});
            summary.fixes += t.size();
        }
        summary.tracks += read[k].tracks.size();
        if (f.size > 0) summary.bytes_read += static_cast<std::size_t>(f.size);
    }
    summary.files = files.size();
    const fs::path target(dir);
    const fs::path temp = target.parent_path() / (".tmp-" + target.filename().string() + "-" + std::to_string(::getpid()));
    fs::remove_all(temp, ec);
    if (!fs::create_directory(temp, ec)) throw InputError("cannot create the folder '" + temp.string() + "' (" + ec.message() + ")");
    try {
        write_file((temp / "index.bin").string(), index.bytes());
        for (unsigned p = 0; p < count; ++p) {
            Writer w;
            w.raw(magic_part, sizeof magic_part);
            w.u64(layout);
            w.u64(where[p].size());
            for (const auto& [k, i] : where[p]) {
                w.u64(k);
                w.u64(i);
                put_track(w, read[k].tracks[i]);
                read[k].tracks[i].release_fixes();
            }
            write_file((temp / part_name(p)).string(), w.bytes());
        }
        fs::rename(temp, target, ec);  // onto a folder that appeared meanwhile: refused (not empty) or replaced only if empty
        if (ec) throw InputError("cannot put the partitions in place at '" + dir + "' (" + ec.message() + ")");
    } catch (...) {
        fs::remove_all(temp, ec);
        throw;
    }
    return summary;
}

ReadResult read_partition(const std::vector<std::string>& dirs, const std::vector<std::string>& inputs, const track::ReadOptions& options,
                          Shard shard, std::vector<std::size_t>& positions, std::vector<std::string>* all_ids) {
    if (!shard.active()) throw UsageError("read_partition needs a shard I/N");
    if (dirs.size() != inputs.size())
        throw UsageError("partitions of " + std::to_string(dirs.size()) + " inputs given for a run of " + std::to_string(inputs.size()) +
                         " (one partition folder per TRACK input, in order)");
    ReadResult result;
    // 1. Every input's index: the run's files, and every track's position among the run's
    // (one vessel met in several files takes the position of its first track, as one run merges them).
    std::vector<Index> index;
    std::set<std::string> files_seen;
    std::map<std::string, std::size_t> vessel_position;
    std::vector<std::vector<std::vector<std::size_t>>> position_of;  // [input][file][track]; SIZE_MAX: merged into an earlier one
    std::size_t next = 0;
    for (std::size_t d = 0; d < dirs.size(); ++d) {
        index.push_back(read_index(dirs[d]));
        const Index& x = index.back();
        if (x.input != inputs[d])
            throw InputError(dirs[d] + ": the partitions of '" + x.input + "', not of '" + inputs[d] + "' (input " + std::to_string(d + 1) + " of the run)");
        if (x.count != shard.count)
            throw InputError(dirs[d] + ": written in " + std::to_string(x.count) + " partitions, not " + std::to_string(shard.count));
        // The files were read when the partitions were written: with this run's read options, or
        // the report would name options its fixes were not read with.
        if (const auto [theirs, ours] = first_difference(x.read_key, read_key(options)); !theirs.empty())
            throw InputError(dirs[d] + ": the partitions were read with " + theirs + ", this run asks " + ours +
                             ": give the read options the partitions were written with (or write them again)");
        position_of.emplace_back();
        for (std::size_t k = 0; k < x.files.size(); ++k) {
            if (!files_seen.insert(x.files[k].file).second)
                throw InputError("'" + x.files[k].file + "' is in two inputs of the run: give each file once");
            result.files.push_back(x.files[k]);
            std::vector<std::size_t>& pos = position_of.back().emplace_back();
            for (const std::string& id : x.ids[k]) {
                if (all_ids) all_ids->push_back(id);
                if (!track::is_vessel_id(id)) {
                    pos.push_back(next++);
                    continue;
                }
                const auto [it, fresh] = vessel_position.try_emplace(id, next);
                pos.push_back(fresh ? next++ : SIZE_MAX);
            }
        }
    }
    // 2. This partition's tracks of every input, in the run's order (input, file, track).
    struct Loaded {
        std::size_t input, file, track;
        track::PackedTrack t;
    };
    std::vector<Loaded> loaded;
    for (std::size_t d = 0; d < dirs.size(); ++d) {
        Reader in = open_file((fs::path(dirs[d]) / part_name(shard.index)).string());
        in.header(magic_part);
        const std::size_t n = in.count(16);
        for (std::size_t j = 0; j < n; ++j) {
            Loaded l{d, 0, 0, {}};
            l.file = static_cast<std::size_t>(in.u64());
            l.track = static_cast<std::size_t>(in.u64());
            if (l.file >= position_of[d].size() || l.track >= position_of[d][l.file].size())
                throw InputError(in.path() + ": a track the index does not list (a partition of another run?)");
            l.t = get_track(in);
            loaded.push_back(std::move(l));
        }
        if (!in.done()) throw InputError(in.path() + ": a partition file with more than it should hold");
    }
    std::sort(loaded.begin(), loaded.end(),
              [](const Loaded& a, const Loaded& b) { return std::tie(a.input, a.file, a.track) < std::tie(b.input, b.file, b.track); });
    for (auto& l : loaded) {
        const std::size_t p = position_of[l.input][l.file][l.track];
        if (p != SIZE_MAX) positions.push_back(p);  // merge_same_vessels keeps the first track of a vessel, in place
        result.tracks.push_back(std::move(l.t));
    }
    for (std::string& m : track::merge_same_vessels(result.tracks, {})) result.warnings.push_back(std::move(m));
    if (positions.size() != result.tracks.size())
        throw InputError(dirs.front() + ": partition " + std::to_string(shard.index) + " holds a vessel's tracks apart from another partition (partitions of different runs?)");
    return result;
}

std::string traffic_key(const std::vector<std::string>& dirs, std::uint64_t grid_fingerprint, const std::string& hull_label) {
    Writer w;
    for (const std::string& dir : dirs) w.str(track::read_file((fs::path(dir) / "index.bin").string()));
    w.u64(grid_fingerprint);
    w.str(hull_label);
    const std::string& bytes = w.bytes();
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(XXH3_64bits(bytes.data(), bytes.size())));
    return hex;
}

void write_traffic(const std::string& path, const std::vector<TrackResult>& traffic, Shard shard, const std::string& key) {
    Writer w;
    w.raw(magic_traffic, sizeof magic_traffic);
    w.u64(layout);
    w.u64(shard.index);
    w.u64(shard.count);
    w.str(key);
    w.u64(traffic.size());
    for (const TrackResult& r : traffic) {
        w.str(r.summary.id);
        w.u64(r.stays.size());
        for (const Stay& s : r.stays) {
            w.u64(s.first);
            w.u64(s.last);
            for (double v : {s.start_s, s.end_s, s.local.x, s.local.y}) w.f64(v);
            w.u64((s.moored ? 1u : 0u) | (s.aground ? 2u : 0u));
            w.u64(s.visit);
        }
        w.u64(r.over_land.size());
        for (const geo::XY& p : r.over_land) {
            w.f64(p.x);
            w.f64(p.y);
        }
    }
    // Only a traffic file shoal wrote is replaced: any other file there (a report, a partition's
    // index, the user's own) is left as it is.
    std::error_code ec;
    if (fs::exists(path, ec)) {
        char head[sizeof magic_traffic] = {};
        std::ifstream old(path, std::ios::binary);
        old.read(head, sizeof head);
        if (!fs::is_regular_file(path, ec) || old.gcount() != static_cast<std::streamsize>(sizeof head) ||
            std::memcmp(head, magic_traffic, sizeof head) != 0)
            throw InputError("'" + path + "' exists and is not a partition's traffic file that shoal wrote: not replaced (move it away, or choose another path for the traffic)");
    }
    StagedOutput out(path);
    out.write(w.bytes());
    out.commit();
}

std::vector<TrackResult> read_traffic(const std::vector<std::string>& paths, Shard shard, const std::string& key) {
    if (paths.size() != shard.count)
        throw InputError("the traffic of " + std::to_string(paths.size()) + " partitions given, for a run of " + std::to_string(shard.count) +
                         ": every partition's is needed");
    std::vector<TrackResult> out;
    for (std::size_t p = 0; p < paths.size(); ++p) {
        Reader in = open_file(paths[p]);
        in.header(magic_traffic);
        const std::uint64_t index = in.u64(), count = in.u64();
        if (index != p || count != shard.count)
            throw InputError(paths[p] + ": the traffic of partition " + std::to_string(index) + "/" + std::to_string(count) + ", not " +
                             std::to_string(p) + "/" + std::to_string(shard.count));
        if (in.str() != key)
            throw InputError(paths[p] + ": the traffic of other partitions, another grid or another ship than this run's (made under another "
                             "run's partitions: make every partition's traffic again from this run's partitions, grid and ship)");
        const std::size_t n = in.count(24);
        for (std::size_t k = 0; k < n; ++k) {
            TrackResult r;
            r.summary.id = in.str();
            r.stays.resize(in.count(64));
            for (Stay& s : r.stays) {
                s.first = in.u64();
                s.last = in.u64();
                for (double* v : {&s.start_s, &s.end_s, &s.local.x, &s.local.y}) *v = in.f64();
                const std::uint64_t flags = in.u64();
                s.moored = flags & 1u;
                s.aground = flags & 2u;
                s.visit = in.u64();
            }
            r.over_land.resize(in.count(16));
            for (geo::XY& q : r.over_land) {
                q.x = in.f64();
                q.y = in.f64();
            }
            if (p != shard.index) out.push_back(std::move(r));  // this partition's own: from its sweep
        }
        if (!in.done()) throw InputError(paths[p] + ": a traffic file with more than it should hold");
    }
    return out;
}

}  // namespace shoal::audit
