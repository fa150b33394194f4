#include "track/gpx_points.hpp"

#include <cpl_vsi.h>
#include <expat.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <memory>
#include <string_view>
#include <strings.h>

#include "util/parse_util.hpp"
#include <shoal/track/time.hpp>

namespace shoal::track::detail {

namespace {

static_assert(sizeof(GpxPoint) == 40, "GpxPoint: 40 bytes a point");

std::uint32_t saturated(XML_Size v) { return v > UINT32_MAX ? UINT32_MAX : static_cast<std::uint32_t>(v); }

struct Scan {
    XML_Parser parser = nullptr;
    GpxPoints out;
    std::size_t trk = 0, rte = 0;  // elements begun so far
    std::size_t depth = 0;         // of the element open now (the root 1)
    std::vector<GpxPoint>* in_point = nullptr;  // the kind of the point open now, its depth:
    std::size_t point_depth = 0;
    bool in_time = false;  // in the open point's own <time>, whose text is
    std::string time_text;
};

/// What is wrong with a point's problem slot taken for `what` (at most 2^29 - 1 of them).
void add_problem(Scan& s, GpxPoint& p, std::string what, bool time) {
    if (s.out.problems.size() >= (1u << 29) - 1) return;
    s.out.problems.push_back(std::move(what));
    p.problem = static_cast<std::uint32_t>(s.out.problems.size()) & 0x1fffffffu;
    p.time_problem = time ? 1 : 0;
}

/// What is wrong with a lat or lon attribute's text ("" when it is a number; `what` is
/// "latitude" or "longitude"); the number in `out`.
std::string gpx_coordinate_problem(const char* text, const char* what, double& out) {
    const std::string_view t = trim(text);
    if (t.empty()) return std::string(what) + " is empty";
    const bool number = parse_double(t, out);
    if (number && std::isfinite(out)) return "";
    return std::string(what) + " " + quoted(t) + (number && !std::isnan(out) ? " is out of range" : " is not a number");
}

void start(void* data, const XML_Char* name, const XML_Char** attrs) {
    Scan& s = *static_cast<Scan*>(data);
    ++s.depth;
    // The point's own <time>, a child of the point (GDAL's driver takes the last of them).
    if (s.in_point && s.depth == s.point_depth + 1 && std::strcmp(name, "time") == 0) {
        s.in_time = true;
        s.time_text.clear();
        return;
    }
    // Names as GDAL's driver compares them: as written, without namespace processing.
    const bool trkpt = std::strcmp(name, "trkpt") == 0, rtept = !trkpt && std::strcmp(name, "rtept") == 0;
    if (std::strcmp(name, "trk") == 0) ++s.trk;
    else if (std::strcmp(name, "rte") == 0) ++s.rte;
    if (!trkpt && !rtept) return;
    GpxPoint p;
    p.line = saturated(XML_GetCurrentLineNumber(s.parser));
    p.column = saturated(XML_GetCurrentColumnNumber(s.parser) + 1);
    // GDAL's driver gives a point the last <trk> (<rte>) begun, closed or not; -1 before any.
    p.parent = static_cast<std::int32_t>(std::min<std::size_t>(trkpt ? s.trk : s.rte, INT32_MAX)) - 1;
    const char* lat = nullptr;
    const char* lon = nullptr;
    for (std::size_t i = 0; attrs[i]; i += 2) {
        if (std::strcmp(attrs[i], "lat") == 0) lat = attrs[i + 1];
        else if (std::strcmp(attrs[i], "lon") == 0) lon = attrs[i + 1];
    }
    std::string problem;
    if (!lat) problem = "no lat attribute";
    else if (!lon) problem = "no lon attribute";
    else {
        problem = gpx_coordinate_problem(lat, "latitude", p.lat);
        if (problem.empty()) problem = gpx_coordinate_problem(lon, "longitude", p.lon);
    }
    if (!problem.empty()) add_problem(s, p, std::move(problem), false);
    std::vector<GpxPoint>& to = trkpt ? s.out.track : s.out.route;
    to.push_back(p);
    s.in_point = &to;
    s.point_depth = s.depth;
}

void text(void* data, const XML_Char* chars, int len) {
    Scan& s = *static_cast<Scan*>(data);
    if (s.in_time && s.time_text.size() < 256) s.time_text.append(chars, static_cast<std::size_t>(std::min(len, 256)));
}

void end(void* data, const XML_Char*) {
    Scan& s = *static_cast<Scan*>(data);
    if (s.in_time && s.depth == s.point_depth + 1) {
        s.in_time = false;
        GpxPoint& p = s.in_point->back();
        std::string_view t = s.time_text;  // (XML's blanks around it: line ends too)
        while (!t.empty() && std::strchr(" \t\r\n", t.front())) t.remove_prefix(1);
        while (!t.empty() && std::strchr(" \t\r\n", t.back())) t.remove_suffix(1);
        // (A later <time> of the point replaces an earlier one, as in GDAL's driver.)
        if (p.time_problem) p.problem = p.time_problem = p.date_alone = 0;
        p.time_s = NAN;
        if (const auto v = parse_iso8601(t)) {
            p.time_s = *v;
        } else if (!t.empty() && !p.problem) {  // (empty: no time, as GDAL has it)
            p.date_alone = parse_date(t) ? 1 : 0;
            add_problem(s, p, "time " + quoted(t) + (p.date_alone ? " is a date without a time of day" : " is not a valid time"), true);
        }
    }
    if (s.in_point && s.depth == s.point_depth) s.in_point = nullptr;
    --s.depth;
}

/// The single-byte encodings GDAL's own expat parser also reads (ogr_expat.cpp's handler):
/// Windows-1252 and ISO-8859-15. (Expat reads UTF-8, UTF-16, ISO-8859-1 and US-ASCII itself.)
int unknown_encoding(void*, const XML_Char* name, XML_Encoding* info) {
    const bool cp1252 = strcasecmp(name, "windows-1252") == 0;
    const bool latin9 = strcasecmp(name, "iso-8859-15") == 0;
    if (!cp1252 && !latin9) return XML_STATUS_ERROR;
    for (int i = 0; i < 256; ++i) info->map[i] = i;
    if (cp1252) {
        static constexpr std::array<int, 32> high{0x20AC, 0x81,   0x201A, 0x192,  0x201E, 0x2026, 0x2020, 0x2021, 0x2C6, 0x2030, 0x160,
                                                  0x2039, 0x152,  0x8D,   0x17D,  0x8F,   0x90,   0x2018, 0x2019, 0x201C, 0x201D, 0x2022,
                                                  0x2013, 0x2014, 0x2DC,  0x2122, 0x161,  0x203A, 0x153,  0x9D,   0x17E,  0x178};
        // (The five bytes Windows-1252 leaves undefined are malformed, as GDAL's parser has them.)
        for (int i = 0; i < 32; ++i) info->map[0x80 + i] = high[static_cast<std::size_t>(i)];
        for (const int undefined : {0x81, 0x8D, 0x8F, 0x90, 0x9D}) info->map[undefined] = -1;
    } else {
        info->map[0xA4] = 0x20AC;
        info->map[0xA6] = 0x160;
        info->map[0xA8] = 0x161;
        info->map[0xB4] = 0x17D;
        info->map[0xB8] = 0x17E;
        info->map[0xBC] = 0x152;
        info->map[0xBD] = 0x153;
        info->map[0xBE] = 0x178;
    }
    info->data = nullptr;
    info->convert = nullptr;
    info->release = nullptr;
    return XML_STATUS_OK;
}

}  // namespace

GpxPoints scan_gpx_points(const std::string& gdal_path) {
    Scan s;
    std::unique_ptr<VSILFILE, int (*)(VSILFILE*)> f(VSIFOpenL(gdal_path.c_str(), "rb"), VSIFCloseL);
    if (!f) return {};
    std::unique_ptr<std::remove_pointer_t<XML_Parser>, void (*)(XML_Parser)> parser(XML_ParserCreate(nullptr), XML_ParserFree);
    if (!parser) return {};
    s.parser = parser.get();
    XML_SetUserData(s.parser, &s);
    XML_SetElementHandler(s.parser, start, end);
    XML_SetCharacterDataHandler(s.parser, text);
    XML_SetUnknownEncodingHandler(s.parser, unknown_encoding, nullptr);
    std::vector<char> buf(1 << 16);
    for (;;) {
        const std::size_t n = VSIFReadL(buf.data(), 1, buf.size(), f.get());
        const bool last = n < buf.size();
        if (XML_Parse(s.parser, buf.data(), static_cast<int>(n), last) != XML_STATUS_OK) {
            // The points before it are where they are: GDAL's parser stops at the same place.
            s.out.error = XML_ErrorString(XML_GetErrorCode(s.parser));
            s.out.error_line = static_cast<std::size_t>(XML_GetCurrentLineNumber(s.parser));
            s.out.error_column = static_cast<std::size_t>(XML_GetCurrentColumnNumber(s.parser)) + 1;
            break;
        }
        if (last) {
            s.out.read = true;
            break;
        }
    }
    // Points that share their line (a GPX written on one line) are told apart by their column.
    for (std::vector<GpxPoint>* v : {&s.out.track, &s.out.route})
        for (std::size_t i = 0; i < v->size(); ++i)
            (*v)[i].shares_line = (i > 0 && (*v)[i - 1].line == (*v)[i].line) || (i + 1 < v->size() && (*v)[i + 1].line == (*v)[i].line) ? 1 : 0;
    return std::move(s.out);
}

}  // namespace shoal::track::detail
