#include <shoal/report/read_fingerprints.hpp>

#include <cstdio>
#include <initializer_list>
#define XXH_INLINE_ALL
#include <xxhash.h>
#include <shoal/grid/coast_grid.hpp>

namespace shoal::report {

namespace {

/// Text of numbers to the last bit, for the fingerprints of inputs read from a stream.
std::string bits(std::initializer_list<double> values) {
    std::string out;
    char num[40];
    for (const double v : values) {
        std::snprintf(num, sizeof num, "%a;", v);
        out += num;
    }
    return out;
}
std::string text_fingerprint(const std::string& key) { return grid::fingerprint_hex(XXH3_64bits(key.data(), key.size())); }


}  // namespace

std::string roles_fingerprint(const audit::Roles& roles) {
    std::string key = std::string(audit::to_string(roles.default_role)) + '\n';
    for (const auto& e : roles.entries) key += e.track + '\0' + e.exercise + '\0' + audit::to_string(e.role) + '\n';
    return text_fingerprint(key);
}

/// The ship as read (name, contour, A,B,C,D, draught): for a ship file read from a stream.
std::string hull_fingerprint(const hull::Hull& h) {
    const hull::Dimensions d = h.dimensions();
    std::string key = h.name() + '\0' + bits({d.a, d.b, d.c, d.d, h.draught()});
    for (const geo::XY& p : h.contour()) key += bits({p.x, p.y});
    return text_fingerprint(key);
}

/// The vessels as read (every field of every vessel): for vessels tables read from a stream.
std::string vessels_fingerprint(const std::map<std::string, track::VesselInfo>& vessels) {
    std::string key;
    for (const auto& [id, v] : vessels) {
        key += id + '\0' + v.name + '\0' + v.source + '\0' + v.dims_source + '\0' + v.draught_source + '\0' + v.ship_type_source + '\0';
        if (v.dims) key += bits({v.dims->a, v.dims->b, v.dims->c, v.dims->d});
        key += bits({v.draught_m, static_cast<double>(v.ship_type)}) + '\n';
    }
    return text_fingerprint(key);
}

}  // namespace shoal::report
