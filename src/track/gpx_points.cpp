#include "track/gpx_points.hpp"

#include <cpl_vsi.h>
#include <expat.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string_view>

#include "util/parse_util.hpp"

namespace shoal::track::detail {

namespace {

struct Scan {
    XML_Parser parser = nullptr;
    GpxPoints out;
    std::size_t trk = 0, rte = 0;  // elements begun so far
};

void start(void* data, const XML_Char* name, const XML_Char** attrs) {
    Scan& s = *static_cast<Scan*>(data);
    // Names as GDAL's driver compares them: as written, without namespace processing.
    const bool trkpt = std::strcmp(name, "trkpt") == 0, rtept = !trkpt && std::strcmp(name, "rtept") == 0;
    if (std::strcmp(name, "trk") == 0) ++s.trk;
    if (std::strcmp(name, "rte") == 0) ++s.rte;
    if (!trkpt && !rtept) return;
    GpxPoint p;
    p.line = static_cast<std::size_t>(XML_GetCurrentLineNumber(s.parser));
    p.parent = trkpt ? (s.trk > 0 ? s.trk - 1 : 0) : (s.rte > 0 ? s.rte - 1 : 0);
    const char* lat = nullptr;
    const char* lon = nullptr;
    for (std::size_t i = 0; attrs[i]; i += 2) {
        if (std::strcmp(attrs[i], "lat") == 0) lat = attrs[i + 1];
        else if (std::strcmp(attrs[i], "lon") == 0) lon = attrs[i + 1];
    }
    if (!lat) p.problem = "no lat attribute";
    else if (!lon) p.problem = "no lon attribute";
    else {
        p.problem = gpx_coordinate_problem(lat, "latitude", p.lat);
        if (p.problem.empty()) p.problem = gpx_coordinate_problem(lon, "longitude", p.lon);
    }
    (trkpt ? s.out.track : s.out.route).push_back(std::move(p));
}

}  // namespace

std::string gpx_coordinate_problem(const char* text, const char* what, double& out) {
    const std::string_view t = trim(text);
    if (t.empty()) return std::string(what) + " is empty";
    const bool number = parse_double(t, out);
    if (number && std::isfinite(out)) return "";
    std::string shown(t.substr(0, 40));
    if (t.size() > 40) shown += "...";
    return std::string(what) + " '" + shown + (number ? "' is out of range" : "' is not a number");
}

GpxPoints scan_gpx_points(const std::string& gdal_path) {
    Scan s;
    std::unique_ptr<VSILFILE, int (*)(VSILFILE*)> f(VSIFOpenL(gdal_path.c_str(), "rb"), VSIFCloseL);
    if (!f) return {};
    std::unique_ptr<std::remove_pointer_t<XML_Parser>, void (*)(XML_Parser)> parser(XML_ParserCreate(nullptr), XML_ParserFree);
    if (!parser) return {};
    s.parser = parser.get();
    XML_SetUserData(s.parser, &s);
    XML_SetStartElementHandler(s.parser, start);
    std::vector<char> buf(1 << 16);
    for (;;) {
        const std::size_t n = VSIFReadL(buf.data(), 1, buf.size(), f.get());
        const bool last = n < buf.size();
        if (XML_Parse(s.parser, buf.data(), static_cast<int>(n), last) != XML_STATUS_OK) return {};
        if (last) break;
    }
    s.out.read = true;
    return std::move(s.out);
}

}  // namespace shoal::track::detail
