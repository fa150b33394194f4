#include "coast/s57_structure.hpp"

#include <cctype>
#include <cstdlib>
#include <iterator>
#include <optional>

#include "coast/ogr_source.hpp"

namespace shoal::coast {

const char* to_string(StructureKind k) noexcept {
    switch (k) {
    case StructureKind::none: return "";
    case StructureKind::breakwater: return "breakwater";
    case StructureKind::groyne: return "groyne";
    case StructureKind::mole: return "mole";
    case StructureKind::pier: return "pier";
    case StructureKind::promenade_pier: return "promenade pier";
    case StructureKind::wharf: return "wharf";
    case StructureKind::training_wall: return "training wall";
    case StructureKind::rip_rap: return "rip rap";
    case StructureKind::revetment: return "revetment";
    case StructureKind::sea_wall: return "sea wall";
    case StructureKind::landing_steps: return "landing steps";
    case StructureKind::ramp: return "ramp";
    case StructureKind::slipway: return "slipway";
    case StructureKind::fender: return "fender";
    case StructureKind::solid_face_wharf: return "solid face wharf";
    case StructureKind::open_face_wharf: return "open face wharf";
    case StructureKind::log_ramp: return "log ramp";
    case StructureKind::shoreline_construction: return "structure";
    case StructureKind::pontoon: return "pontoon";
    case StructureKind::hulk: return "hulk";
    case StructureKind::dolphin: return "dolphin";
    case StructureKind::deviation_dolphin: return "deviation dolphin";
    case StructureKind::bollard: return "bollard";
    case StructureKind::tie_up_wall: return "tie-up wall";
    case StructureKind::post_or_pile: return "post or pile";
    case StructureKind::chain_wire_cable: return "chain/wire/cable";
    case StructureKind::mooring_buoy: return "mooring buoy";
    case StructureKind::mooring_facility: return "mooring facility";
    }
    return "?";
}

namespace s57 {

namespace {

/// The values of an S-57 category attribute, 1..n, in order.
struct Category {
    StructureKind first;  ///< the kind of value 1; value v is first + (v - 1)
    long count;
    StructureKind unknown;
};

std::optional<Category> category_of(const std::string& object_class) {
    if (object_class == "SLCONS") return Category{StructureKind::breakwater, 17, StructureKind::shoreline_construction};
    if (object_class == "MORFAC") return Category{StructureKind::dolphin, 7, StructureKind::mooring_facility};
    return std::nullopt;
}

StructureKind kind_of_value(const Category& c, long v) {
    return v >= 1 && v <= c.count ? static_cast<StructureKind>(static_cast<long>(c.first) + v - 1) : c.unknown;
}

std::string trimmed(std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.erase(0, 1);
    return s;
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

}  // namespace

bool is_structure_class(const std::string& name) {
    const std::string n = ogr::upper(name);
    return n == "SLCONS" || n == "PONTON" || n == "HULKES" || n == "MORFAC";
}

int field_index(const OGRFeatureDefn& defn, const std::string& name) {
    for (int i = 0; i < defn.GetFieldCount(); ++i)
        if (ogr::upper(defn.GetFieldDefn(i)->GetNameRef()) == name) return i;
    return -1;
}

StructureFields structure_fields(const std::string& object_class, const OGRFeatureDefn& defn) {
    StructureFields f;
    f.object_class = ogr::upper(object_class);
    if (f.object_class == "SLCONS") f.category = field_index(defn, "CATSLC");
    if (f.object_class == "MORFAC") f.category = field_index(defn, "CATMOR");
    f.objnam = field_index(defn, "OBJNAM");
    f.name = field_index(defn, "NAME");
    return f;
}

StructureKind structure_kind(const StructureFields& fields, const OGRFeature& f) {
    if (fields.object_class == "PONTON") return StructureKind::pontoon;
    if (fields.object_class == "HULKES") return StructureKind::hulk;
    const std::optional<Category> cat = category_of(fields.object_class);
    if (!cat) return StructureKind::none;
    const int index = fields.category;
    if (index < 0 || !f.IsFieldSetAndNotNull(index)) return cat->unknown;
    const OGRFieldType type = f.GetFieldDefnRef(index)->GetType();
    if (type == OFTInteger || type == OFTInteger64) return kind_of_value(*cat, static_cast<long>(f.GetFieldAsInteger64(index)));
    if (type == OFTIntegerList || type == OFTInteger64List) {
        int n = 0;
        const GIntBig* values = f.GetFieldAsInteger64List(index, &n);
        return n > 0 ? kind_of_value(*cat, static_cast<long>(values[0])) : cat->unknown;
    }
    std::string text = f.GetFieldAsString(index);  // a StringList reads as "(2:4,6)"
    if (const auto colon = text.find(':'); !text.empty() && text.front() == '(' && colon != std::string::npos)
        text = text.substr(colon + 1);
    text = trimmed(text.substr(0, text.find_first_of(",)")));
    if (text.empty()) return cat->unknown;
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (end && *end == '\0') return kind_of_value(*cat, v);
    const std::string name = lower(text);
    for (long v2 = 1; v2 <= cat->count; ++v2)
        if (name == to_string(kind_of_value(*cat, v2))) return kind_of_value(*cat, v2);
    return cat->unknown;
}

std::string feature_name(const StructureFields& fields, const OGRFeature& f) {
    for (const int i : {fields.objnam, fields.name})
        if (i >= 0 && f.IsFieldSetAndNotNull(i))
            if (std::string s = f.GetFieldAsString(i); !s.empty()) return s;
    return "";
}

}  // namespace s57

}  // namespace shoal::coast
