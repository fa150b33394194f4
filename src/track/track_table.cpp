// Rows of fixes into tracks, one per vessel (track/track_table.hpp).
#include <shoal/track/track_table.hpp>

#include <cmath>
#include <functional>
#include <unordered_map>

#include <shoal/track/csv_reader.hpp>
#include <shoal/track/row_rules.hpp>

#include "util/parse_util.hpp"

namespace shoal::track {

namespace {

constexpr std::size_t absent = static_cast<std::size_t>(-1);

struct SvHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const noexcept { return std::hash<std::string_view>{}(s); }
};

/// An id of 1 to 18 decimal digits without a leading zero (an MMSI) as its number; such ids
/// and only they are looked up by number, so "0123" and "123" stay two vessels.
std::optional<std::uint64_t> integer_id(std::string_view id) noexcept {
    if (id.empty() || id.size() > 18 || (id[0] == '0' && id.size() > 1)) return std::nullopt;
    std::uint64_t v = 0;
    for (const char c : id) {
        if (c < '0' || c > '9') return std::nullopt;
        v = v * 10 + static_cast<std::uint64_t>(c - '0');
    }
    return v;
}

/// Track indexes by integer id: open addressing with linear probing (a daily export has a few
/// thousand vessels, and rows interleaved across them defeat the last-id shortcut).
class IntegerIndex {
public:
    /// The index of `key`, or `absent_index` (then `insert` it).
    std::size_t find(std::uint64_t key) const noexcept {
        if (m_slots.empty()) return absent_index;
        for (std::size_t i = slot_of(key);; i = (i + 1) & (m_slots.size() - 1)) {
            const Slot& s = m_slots[i];
            if (s.index == absent_index) return absent_index;
            if (s.key == key) return s.index;
        }
    }
    void insert(std::uint64_t key, std::size_t index) {
        if ((m_count + 1) * 2 > m_slots.size()) grow();
        place(key, index);
        ++m_count;
    }
    static constexpr std::size_t absent_index = static_cast<std::size_t>(-1);

private:
    struct Slot {
        std::uint64_t key = 0;
        std::size_t index = absent_index;
    };
    std::size_t slot_of(std::uint64_t key) const noexcept {
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 32) & (m_slots.size() - 1);
    }
    void place(std::uint64_t key, std::size_t index) noexcept {
        std::size_t i = slot_of(key);
        while (m_slots[i].index != absent_index) i = (i + 1) & (m_slots.size() - 1);
        m_slots[i] = {key, index};
    }
    void grow() {
        std::vector<Slot> old(std::max<std::size_t>(64, m_slots.size() * 2));
        old.swap(m_slots);
        for (const Slot& s : old)
            if (s.index != absent_index) place(s.key, s.index);
    }
    std::vector<Slot> m_slots;
    std::size_t m_count = 0;
};

}  // namespace

struct TrackTable::Index {
    std::unordered_map<std::string, std::size_t, SvHash, std::equal_to<>> text;  ///< ids that are not integer_id()s
    IntegerIndex integer;
    std::string last_id, last_exercise;
    std::string key;                ///< (exercise, id) as one text, for the lookup
    std::size_t last_track = absent;  ///< the last track met by text (last_id, last_exercise)
    std::uint64_t last_integer = 0;
    std::size_t last_integer_track = absent;  ///< the last track met by number (last_integer)
};

TrackTable::TrackTable(std::vector<PackedTrack>& tracks, std::string file, bool has_id, bool by_exercise)
    : m_tracks(tracks), m_file(std::move(file)), m_has_id(has_id), m_by_exercise(by_exercise), m_index(std::make_unique<Index>()) {}

TrackTable::~TrackTable() = default;

std::size_t TrackTable::track_for(std::string_view id, std::string_view exercise) {
    Index& x = *m_index;
    if (!m_by_exercise) exercise = {};
    if (x.last_track != absent && id == x.last_id && exercise == x.last_exercise) return x.last_track;
    // With an exercise column the key is (exercise, id), as text: no integer shortcut.
    std::optional<std::uint64_t> mmsi;
    if (!m_by_exercise) {
        mmsi = integer_id(id);
        if (mmsi && x.last_integer_track != absent && *mmsi == x.last_integer) return x.last_integer_track;
    } else {
        x.key.assign(exercise).push_back('\0');
        x.key.append(id);
        id = x.key;
    }
    std::size_t idx = absent;
    if (mmsi) {
        idx = x.integer.find(*mmsi);
    } else if (auto it = x.text.find(id); it != x.text.end()) {
        idx = it->second;
    }
    if (idx == absent) {
        idx = m_tracks.size();
        PackedTrack& t = m_tracks.emplace_back();
        t.id = !m_has_id ? detail::file_stem(m_file) : to_utf8(!m_by_exercise ? id : id.substr(exercise.size() + 1));
        t.file = m_file;
        t.exercise = to_utf8(exercise);
        if (mmsi) x.integer.insert(*mmsi, idx);
        else x.text.emplace(std::string(id), idx);
    }
    if (mmsi) {  // the last track by number (no text to copy)
        x.last_integer = *mmsi;
        x.last_integer_track = idx;
        x.last_track = absent;
        return idx;
    }
    x.last_id.assign(!m_by_exercise ? id : id.substr(exercise.size() + 1));
    x.last_exercise.assign(exercise);
    x.last_track = idx;
    x.last_integer_track = absent;
    return idx;
}

void offer_name(PackedTrack& t, std::string_view name) {
    if (t.name.empty() && !name.empty()) t.name = to_utf8(name);
}

void offer_dims(PackedTrack& t, const std::optional<hull::Dimensions>& dims, const char* source) {
    if (t.dims || !dims) return;
    t.dims = dims;
    t.dims_source = source;
}

void offer_draught(PackedTrack& t, double draught_m) {
    if (!std::isnan(t.draught_m) || !usable_draught(draught_m)) return;
    t.draught_m = draught_m;
    t.draught_source = draught_source;
}

void offer_ship_type(PackedTrack& t, double ship_type) {
    if (t.ship_type >= 0) return;
    if (const int v = ship_type_number(ship_type); v >= 0) {
        t.ship_type = v;
        t.ship_type_source = ship_type_source;
    }
}

}  // namespace shoal::track
