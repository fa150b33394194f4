#include <shoal/grid/grid_file.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <type_traits>
#include <unordered_map>

#include <shoal/util/atomic_file.hpp>
#include <shoal/util/error.hpp>

#include "util/fast_hash.hpp"
#include "util/mapped_file.hpp"

namespace shoal::grid {

namespace fs = std::filesystem;

namespace {

class Writer {
public:
    template <typename T>
    void pod(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        const char* p = reinterpret_cast<const char*>(&v);
        m_bytes.insert(m_bytes.end(), p, p + sizeof(T));
    }
    void str(const std::string& s) {
        pod<std::uint64_t>(s.size());
        m_bytes.insert(m_bytes.end(), s.begin(), s.end());
    }
    void strings(const std::vector<std::string>& v) {
        pod<std::uint64_t>(v.size());
        for (const auto& s : v) str(s);
    }
    template <typename T>
    void vec(const std::vector<T>& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        pod<std::uint64_t>(v.size());
        const char* p = reinterpret_cast<const char*>(v.data());
        m_bytes.insert(m_bytes.end(), p, p + v.size() * sizeof(T));
    }
    std::vector<char>& bytes() { return m_bytes; }

private:
    std::vector<char> m_bytes;
};

class Reader {
public:
    Reader(const char* data, std::size_t size, const std::string& name) : m_p(data), m_end(data + size), m_name(name) {}
    template <typename T>
    T pod() {
        T v;
        need(sizeof(T));
        std::memcpy(&v, m_p, sizeof(T));
        m_p += sizeof(T);
        return v;
    }
    std::string str() {
        const auto n = count(1);
        std::string s(m_p, n);
        m_p += n;
        return s;
    }
    std::vector<std::string> strings() {
        const auto n = count(8);
        std::vector<std::string> v;
        for (std::size_t i = 0; i < n; ++i) v.push_back(str());
        return v;
    }
    template <typename T>
    std::vector<T> vec() {
        const auto n = count(sizeof(T));
        // Each element copied from the bytes as it is made (not zeroed first, then copied). An
        // array at its type's alignment in the file is copied as one block (memmove: a loop of
        // wide moves whatever the build's optimisation, where an element at a time is 3 M
        // instructions of a 1-pose probe of an 11.8 MB grid at -O2); at any other alignment,
        // an element at a time through memcpy.
        std::vector<T> v;
        if (reinterpret_cast<std::uintptr_t>(m_p) % alignof(T) == 0) {
            const T* first = reinterpret_cast<const T*>(m_p);
            v.assign(first, first + n);
        } else {
            v.assign(Elements<T>{m_p}, Elements<T>{m_p + n * sizeof(T)});
        }
        m_p += n * sizeof(T);
        return v;
    }
    bool at_end() const { return m_p == m_end; }
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError("grid file '" + m_name + "' is damaged: " + what + "; rebuild it with shoal import");
    }

private:
    /// The elements of type T stored from `p` on, at any alignment, as a random access iterator.
    template <typename T>
    struct Elements {
        using iterator_category = std::random_access_iterator_tag;
        using value_type = T;
        using difference_type = std::ptrdiff_t;
        using pointer = const T*;
        using reference = T;
        const char* p;
        T operator*() const noexcept {
            T t;
            std::memcpy(&t, p, sizeof(T));
            return t;
        }
        T operator[](difference_type k) const noexcept { return *(*this + k); }
        Elements& operator++() noexcept { p += sizeof(T); return *this; }
        Elements operator++(int) noexcept { Elements o = *this; p += sizeof(T); return o; }
        Elements& operator--() noexcept { p -= sizeof(T); return *this; }
        Elements operator--(int) noexcept { Elements o = *this; p -= sizeof(T); return o; }
        Elements& operator+=(difference_type k) noexcept { p += k * static_cast<difference_type>(sizeof(T)); return *this; }
        Elements& operator-=(difference_type k) noexcept { p -= k * static_cast<difference_type>(sizeof(T)); return *this; }
        friend Elements operator+(Elements a, difference_type k) noexcept { return a += k; }
        friend Elements operator+(difference_type k, Elements a) noexcept { return a += k; }
        friend Elements operator-(Elements a, difference_type k) noexcept { return a -= k; }
        friend difference_type operator-(Elements a, Elements b) noexcept { return (a.p - b.p) / static_cast<difference_type>(sizeof(T)); }
        friend auto operator<=>(Elements a, Elements b) noexcept = default;
    };

    std::size_t count(std::size_t elem) {
        const auto n = pod<std::uint64_t>();
        if (n > static_cast<std::uint64_t>(m_end - m_p) / elem) fail("an array runs past the end of the file");
        return static_cast<std::size_t>(n);
    }
    void need(std::size_t n) {
        if (static_cast<std::size_t>(m_end - m_p) < n) fail("it ends early");
    }
    const char* m_p;
    const char* m_end;
    const std::string& m_name;
};

constexpr std::uint32_t byte_order_mark = 0x01020304u;
constexpr std::size_t header_size = 8 + 4 + 4 + 8 + 8;
/// Longest frame definition a grid file may hold.
constexpr std::size_t max_frame_text = 65536;

/// The payload's first fields, in the order serialize writes them: the grid's parameters and
/// the frame's definition.
struct Head {
    double cell = 0, x0 = 0, y0 = 0;
    std::int32_t nx = 0, ny = 0;
    double fx = 0, fy = 0, slack = 0;
    bool land = false;
    std::string frame;
};

Head read_head(Reader& r) {
    Head h;
    h.cell = r.pod<double>();
    h.x0 = r.pod<double>();
    h.y0 = r.pod<double>();
    h.nx = r.pod<std::int32_t>();
    h.ny = r.pod<std::int32_t>();
    h.fx = r.pod<double>();
    h.fy = r.pod<double>();
    h.slack = r.pod<double>();
    h.land = r.pod<std::uint8_t>() != 0;
    h.frame = r.str();
    // The frame's CRS text goes to GDAL/PROJ, which may look a name up at length: only text does.
    if (h.frame.empty() || h.frame.size() > max_frame_text ||
        std::any_of(h.frame.begin(), h.frame.end(), [](char c) { return (c >= 0 && c < ' ' && c != '\n' && c != '\t') || c == 0x7F; }))
        r.fail("bad frame definition");
    return h;
}


}  // namespace

std::vector<char> GridFile::serialize(const CoastGrid& g) {
    Writer w;
    w.pod(g.m_cell);
    w.pod(g.m_x0);
    w.pod(g.m_y0);
    w.pod<std::int32_t>(g.m_nx);
    w.pod<std::int32_t>(g.m_ny);
    w.pod(g.m_ref_fx);
    w.pod(g.m_ref_fy);
    w.pod(g.m_clip_slack);
    w.pod<std::uint8_t>(g.m_has_land_side ? 1 : 0);
    w.str(g.m_frame.definition());
    const GridSource& s = g.m_source;
    w.strings(s.inputs);
    w.strings(s.layers);
    w.strings(s.layer_option);
    w.str(s.source_crs);
    w.pod(s.fingerprint);
    w.pod(s.input_vertices);
    w.pod(s.polylines);
    w.pod(s.land_polylines);
    w.pod(s.limiting_depth_m);
    w.pod(s.danger_radius_m);
    w.str(s.depth_field);
    w.pod(s.shallow_polylines);
    w.pod(s.danger_polylines);
    w.pod(s.hazard_features);
    w.pod(s.unknown_depth);
    w.pod(s.structure_polylines);
    w.pod(s.structure_features);
    w.vec(g.m_slot);
    w.vec(g.m_seg_offset);
    w.vec(g.m_ref_winding);
    w.vec(g.m_segments);
    w.vec(g.m_seg_info);
    // Per polyline what it bounds: kind | danger << 4, the structure's kind, the charted depth
    // (NaN unknown), and its name as an index into a table of the distinct names ("" first).
    std::vector<std::uint8_t> kinds, structures;
    std::vector<double> depths;
    std::vector<std::string> names{""};
    std::unordered_map<std::string, std::uint32_t> name_index{{"", 0}};
    std::vector<std::uint32_t> name_of;
    for (const coast::Hazard& h : g.m_hazards) {
        kinds.push_back(static_cast<std::uint8_t>(static_cast<unsigned>(h.kind) | static_cast<unsigned>(h.danger) << 4));
        structures.push_back(static_cast<std::uint8_t>(h.structure));
        depths.push_back(h.depth_m);
        const auto [it, added] = name_index.try_emplace(h.name, static_cast<std::uint32_t>(names.size()));
        if (added) names.push_back(h.name);
        name_of.push_back(it->second);
    }
    w.vec(kinds);
    w.vec(structures);
    w.vec(depths);
    w.strings(names);
    w.vec(name_of);
    // Levels of charted depth (the depths themselves follow from the polylines').
    w.vec(g.m_lw_offset);
    w.vec(g.m_lw_level);
    w.vec(g.m_lw_winding);
    w.vec(g.m_land_level);
    const std::vector<char>& payload = w.bytes();

    Writer out;
    for (char c : grid_magic) out.pod(c);
    out.pod(grid_format_version);
    out.pod(byte_order_mark);
    out.pod<std::uint64_t>(payload.size());
    out.pod<std::uint64_t>(util::xxh3_64(payload.data(), payload.size()));
    out.bytes().insert(out.bytes().end(), payload.begin(), payload.end());
    return std::move(out.bytes());
}

void GridFile::save(const CoastGrid& grid, const std::string& path) {
    const std::vector<char> bytes = serialize(grid);
    write_file_atomically(path, std::string_view(bytes.data(), bytes.size()));
}

CoastGrid GridFile::load(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError("'" + path + "': no such file or directory");
    if (fs::is_directory(path, ec)) throw InputError("'" + path + "' is a directory, not a grid file");
    if (const auto st = fs::status(path, ec); !ec && fs::exists(st) && !fs::is_regular_file(st))
        throw InputError("'" + path + "' is not a regular file (a device, a pipe or a FIFO), not a grid file");
    const detail::MappedFile file(path, [&](detail::MappedFile::Failure f, const std::string& reason) {
        return f == detail::MappedFile::Failure::open ? "cannot open grid file '" + path + "': " + reason : "cannot read grid file '" + path + "'";
    });
    return parse(file.bytes(), path);
}

std::string GridFile::frame_definition(const std::string& path) {
    // The header and as much of the payload as its first fields can take (the frame's text at most
    // max_frame_text), read by the same read_head as parse; any shortfall is "".
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes(header_size + 256 + max_frame_text);
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
    std::uint32_t version = 0;
    if (bytes.size() < header_size || std::memcmp(bytes.data(), grid_magic, 8) != 0) return "";
    std::memcpy(&version, bytes.data() + 8, 4);
    if (version != grid_format_version) return "";
    try {
        Reader r(bytes.data() + header_size, bytes.size() - header_size, path);
        return read_head(r).frame;
    } catch (const InputError&) {
        return "";
    }
}

CoastGrid GridFile::parse(const std::vector<char>& bytes, const std::string& name) { return parse(std::span<const char>(bytes), name); }

CoastGrid GridFile::parse(std::span<const char> bytes, const std::string& name) {
    if (bytes.size() < 8 || std::memcmp(bytes.data(), grid_magic, 8) != 0)
        throw InputError("'" + name + "' is not a shoal grid file (no SHOALGRD magic number)");
    Reader h(bytes.data(), bytes.size(), name);
    if (bytes.size() < header_size) h.fail("the header is cut short");
    h.pod<std::uint64_t>();
    const auto version = h.pod<std::uint32_t>();
    const auto bom = h.pod<std::uint32_t>();
    if (bom != byte_order_mark) h.fail("wrong byte order mark");
    if (version != grid_format_version)
        throw InputError("grid file '" + name + "' has format version " + std::to_string(version) + "; this shoal reads version " +
                         std::to_string(grid_format_version) + ": rebuild it with shoal import");
    const auto size = h.pod<std::uint64_t>();
    const auto checksum = h.pod<std::uint64_t>();
    if (size != bytes.size() - header_size)
        h.fail("it is " + std::to_string(bytes.size()) + " bytes long, its header says " + std::to_string(size + header_size) +
               " (cut short?)");
    const char* payload = bytes.data() + header_size;
    if (util::xxh3_64(payload, size) != checksum) h.fail("checksum mismatch");

    Reader r(payload, size, name);
    const Head head = read_head(r);
    CoastGrid g(geo::LocalFrame::from_definition(head.frame));
    g.m_cell = head.cell;
    g.m_x0 = head.x0;
    g.m_y0 = head.y0;
    g.m_nx = head.nx;
    g.m_ny = head.ny;
    g.m_ref_fx = head.fx;
    g.m_ref_fy = head.fy;
    g.m_clip_slack = head.slack;
    g.m_has_land_side = head.land;
    GridSource& s = g.m_source;
    s.inputs = r.strings();
    s.layers = r.strings();
    s.layer_option = r.strings();
    s.source_crs = r.str();
    s.fingerprint = r.pod<std::uint64_t>();
    s.input_vertices = r.pod<std::uint64_t>();
    s.polylines = r.pod<std::uint64_t>();
    s.land_polylines = r.pod<std::uint64_t>();
    s.limiting_depth_m = r.pod<double>();
    s.danger_radius_m = r.pod<double>();
    s.depth_field = r.str();
    s.shallow_polylines = r.pod<std::uint64_t>();
    s.danger_polylines = r.pod<std::uint64_t>();
    s.hazard_features = r.pod<std::uint64_t>();
    s.unknown_depth = r.pod<std::uint64_t>();
    s.structure_polylines = r.pod<std::uint64_t>();
    s.structure_features = r.pod<std::uint64_t>();
    g.m_slot = r.vec<std::uint32_t>();
    g.m_seg_offset = r.vec<std::uint32_t>();
    g.m_ref_winding = r.vec<std::int32_t>();
    g.m_segments = r.vec<Segment>();
    g.m_seg_info = r.vec<std::uint32_t>();
    const auto kinds = r.vec<std::uint8_t>();
    const auto structures = r.vec<std::uint8_t>();
    const auto depths = r.vec<double>();
    auto names = r.strings();
    const auto name_of = r.vec<std::uint32_t>();
    g.m_lw_offset = r.vec<std::uint32_t>();
    g.m_lw_level = r.vec<std::uint16_t>();
    g.m_lw_winding = r.vec<std::int32_t>();
    g.m_land_level = r.vec<std::uint16_t>();
    if (!r.at_end()) r.fail("unexpected bytes after the arrays");
    if (kinds.size() != depths.size() || structures.size() != kinds.size() || name_of.size() != kinds.size())
        r.fail("polyline table sizes");
    for (std::size_t k = 0; k < kinds.size(); ++k) {
        const unsigned kind = kinds[k] & 0x0Fu, danger = kinds[k] >> 4;
        if (kind > static_cast<unsigned>(coast::HazardKind::structure) || danger > static_cast<unsigned>(coast::DangerKind::obstruction) ||
            structures[k] > static_cast<unsigned>(coast::StructureKind::mooring_facility) ||
            (kind == static_cast<unsigned>(coast::HazardKind::structure)) != (structures[k] != 0))
            r.fail("bad polyline kind");
        if (name_of[k] >= names.size()) r.fail("polyline name out of range");
        coast::Hazard hz;
        hz.kind = static_cast<coast::HazardKind>(kind);
        hz.danger = static_cast<coast::DangerKind>(danger);
        hz.structure = static_cast<coast::StructureKind>(structures[k]);
        hz.depth_m = depths[k];
        hz.name = names[name_of[k]];
        g.m_hazards.push_back(std::move(hz));
    }
    {
        std::uint32_t most = 0;  // the greatest polyline index (no branch a segment)
        for (std::uint32_t info : g.m_seg_info) most = std::max(most, info & ~CoastGrid::boundary_bit);
        if (!g.m_seg_info.empty() && most >= kinds.size()) r.fail("segment of a polyline out of range");
    }
    try {
        g.assign_levels();
    } catch (const UsageError&) {
        r.fail("too many levels of charted depth");
    }
    // Consistency: a checksum protects against damage, these against a wrong writer.
    if (!(head.cell > 0) || !std::isfinite(head.cell) || !std::isfinite(head.x0) || !std::isfinite(head.y0) || head.nx <= 0 || head.ny <= 0 ||
        !(head.fx > 0 && head.fx < 1 && head.fy > 0 && head.fy < 1))
        r.fail("bad grid parameters");
    if (static_cast<std::uint64_t>(head.nx) * static_cast<std::uint64_t>(head.ny) != g.m_slot.size()) r.fail("cell array size");
    const std::size_t ncoast = g.m_ref_winding.size();
    if (g.m_seg_offset.size() != ncoast + 1 || g.m_seg_offset.front() != 0 || g.m_seg_offset.back() != g.m_segments.size() ||
        !std::is_sorted(g.m_seg_offset.begin(), g.m_seg_offset.end()) || g.m_seg_info.size() != g.m_segments.size())
        r.fail("segment offsets");
    {
        // A slot is a coast cell's index (below ncoast), land or water: v - ncoast, unsigned,
        // falls below land_slot - ncoast only for the others (one test, no branch, a cell).
        bool bad = false;
        const std::uint32_t n32 = static_cast<std::uint32_t>(std::min<std::size_t>(ncoast, CoastGrid::land_slot));
        for (std::uint32_t v : g.m_slot) bad |= static_cast<std::uint32_t>(v - n32) < CoastGrid::land_slot - n32;
        if (bad) r.fail("cell slot out of range");
    }
    const std::size_t top = g.m_level_depth.size();
    if (top == 0) {
        if (!g.m_lw_offset.empty() || !g.m_lw_level.empty() || !g.m_lw_winding.empty() || !g.m_land_level.empty())
            r.fail("levels of charted depth in a grid without depth areas or dangers");
    } else {
        if (g.m_lw_offset.size() != ncoast + 1 || g.m_lw_offset.front() != 0 || g.m_lw_offset.back() != g.m_lw_level.size() ||
            !std::is_sorted(g.m_lw_offset.begin(), g.m_lw_offset.end()) || g.m_lw_winding.size() != g.m_lw_level.size() ||
            g.m_land_level.size() != g.m_slot.size())
            r.fail("level offsets");
        for (std::uint16_t lv : g.m_lw_level)
            if (lv >= top) r.fail("level out of range");
        for (std::uint16_t lv : g.m_land_level)
            if (lv > top) r.fail("land level out of range");
    }
    if (!g.compute_chunk_boxes()) r.fail("non-finite segment");
    return g;
}

bool looks_like_grid(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return false;
    std::ifstream in(path, std::ios::binary);
    char head[8] = {};
    in.read(head, 8);
    return in.gcount() == 8 && std::memcmp(head, grid_magic, 8) == 0;
}

}  // namespace shoal::grid
