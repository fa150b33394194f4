#include "report/qgis/qgis_project.hpp"

#include <iconv.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "geo/transverse_mercator.hpp"
#include "report/qgis/qgis_styles.hpp"
#include "util/input_file.hpp"
#include <shoal/report/markup.hpp>
#include <shoal/report/geojson_report.hpp>
#include <shoal/util/error.hpp>

namespace shoal::report {

namespace {

/// The project's text: the one markup escaper, `'` kept (every attribute is in double quotes).
std::string xml_text(std::string_view s) { return markup_text(s, Apostrophe::kept); }

/// The project's coordinate systems: WGS 84 (EPSG:4326) and its UTM zones (EPSG:326zz north,
/// 327zz south), each as GDAL's OSR describes it from PROJ's database (its PROJ.4 text and
/// name; report_test QgisProject.SpatialReferencesAreWhatOsrSaysOfTheirEpsgCodes), without
/// opening the database: the zone and the hemisphere say it all.
std::string srs_xml(int epsg) {
    const bool geographic = epsg == 4326;
    const int zone = epsg % 100;
    const bool south = epsg / 100 == 327;
    if (!geographic && (zone < 1 || zone > 60 || (epsg / 100 != 326 && !south)))
        throw LibraryError("the QGIS project's CRS EPSG:" + std::to_string(epsg) + " is neither WGS 84 nor one of its UTM zones");
    const std::string z = std::to_string(zone);
    const std::string proj4 =
        geographic ? "+proj=longlat +datum=WGS84 +no_defs" : "+proj=utm +zone=" + z + (south ? " +south" : "") + " +datum=WGS84 +units=m +no_defs";
    const std::string name = geographic ? "WGS 84" : "WGS 84 / UTM zone " + z + (south ? "S" : "N");
    return "<spatialrefsys><proj4>" + xml_text(proj4) + "</proj4><srid>" + std::to_string(epsg) + "</srid><authid>EPSG:" + std::to_string(epsg) +
           "</authid><description>" + xml_text(name) + "</description><geographicflag>" + (geographic ? "true" : "false") +
           "</geographicflag></spatialrefsys>";
}

/// The <maplayer> of one layer: the style's root attributes and elements, wrapped.
std::string map_layer(const ProjectLayer& layer, const std::string& id) {
    const std::string& name = layer.name;
    const std::string qml(layer_style(name));
    const std::size_t open = qml.find("<qgis ");
    const std::size_t open_end = qml.find('>', open);
    const std::size_t close = qml.rfind("</qgis>");
    if (open == std::string::npos || open_end == std::string::npos || close == std::string::npos)
        throw LibraryError("the QGIS style of layer " + name + " is not a QGIS style");
    std::string attrs = qml.substr(open + 6, open_end - open - 6);
    // The style's own version attribute is the style's, not the layer's.
    if (std::size_t v = attrs.find("version=\""); v != std::string::npos) attrs.erase(v, attrs.find('"', v + 9) + 1 - v);
    return "    <maplayer type=\"vector\" geometry=\"" + layer.geometry + "\" " + attrs + ">\n      <id>" + xml_text(id) + "</id>\n      <datasource>" +
           xml_text(layer.source) + "</datasource>\n      <layername>" + name + "</layername>\n      <srs>" + srs_xml(4326) +
           "</srs>\n      <provider encoding=\"UTF-8\">ogr</provider>\n" + qml.substr(open_end + 1, close - open_end - 1) + "    </maplayer>\n";
}

}  // namespace

void ProjectView::add(const ProjectView& o) {
    std::vector<std::string> all = exercises;
    all.insert(all.end(), o.exercises.begin(), o.exercises.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    exercises = std::move(all);
    x0 = std::min(x0, o.x0), y0 = std::min(y0, o.y0), x1 = std::max(x1, o.x1), y1 = std::max(y1, o.y1);
    if (!o.chart.empty()) chart.extend(o.chart);
    if (!std::isnan(o.first_fix_s)) first_fix_s = std::isnan(first_fix_s) ? o.first_fix_s : std::min(first_fix_s, o.first_fix_s);
    if (!std::isnan(o.last_fix_s)) last_fix_s = std::isnan(last_fix_s) ? o.last_fix_s : std::max(last_fix_s, o.last_fix_s);
}

ProjectView project_view(const audit::AuditResult& r, const geo::Box& chart) {
    ProjectView v;
    v.chart = chart;
    for (const auto& t : r.tracks)
        for (const auto& line : t.summary.lines)
            for (const auto& p : line) {
                v.x0 = std::min(v.x0, p.lon), v.y0 = std::min(v.y0, p.lat);
                v.x1 = std::max(v.x1, p.lon), v.y1 = std::max(v.y1, p.lat);
            }
    v.first_fix_s = r.first_fix_s;
    v.last_fix_s = r.last_fix_s;
    if (r.has_encounters) {
        for (const auto& t : r.tracks) v.exercises.push_back(t.summary.exercise);
        std::sort(v.exercises.begin(), v.exercises.end());
        v.exercises.erase(std::unique(v.exercises.begin(), v.exercises.end()), v.exercises.end());
    }
    return v;
}

std::string qgis_project_xml(const std::vector<ProjectLayer>& layers, const std::string& report_name, const ProjectView& view) {
    // The chart's extent (the tracks' when no chart box is known: a track far outside the
    // chart, a fix at 0,0 or a vessel across the sea, would put the map elsewhere), and the UTM
    // zone of its centre; a chart wider than four zones in EPSG:4326.
    const bool chart = !view.chart.empty();
    const double x0 = chart ? view.chart.minx : view.x0, y0 = chart ? view.chart.miny : view.y0;
    const double x1 = chart ? view.chart.maxx : view.x1, y1 = chart ? view.chart.maxy : view.y1;
    const bool have_extent = x0 <= x1 && y0 <= y1;
    const double lon_c = have_extent ? (x0 + x1) / 2 : 0, lat_c = have_extent ? (y0 + y1) / 2 : 0;
    const int zone = std::clamp(static_cast<int>(std::floor((lon_c + 180) / 6)) + 1, 1, 60);
    const bool geographic = have_extent && (x1 - x0 > 24 || std::max(std::fabs(y0), std::fabs(y1)) > 84);
    const int epsg = geographic ? 4326 : (lat_c >= 0 ? 32600 : 32700) + zone;

    std::string x = "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n" + std::string(sidecar_mark) +
                    "\n<qgis projectname=\"shoal report\" version=\"3.22.16-Białowieża\">\n";
    x += "  <title>shoal report " + xml_text(report_name) + "</title>\n";
    x += "  <projectCrs>" + srs_xml(epsg) + "</projectCrs>\n";
    // Exercise mode: the layers with an `exercise` field once per exercise, filtered to it.
    std::vector<ProjectLayer> shown;  // every map layer, top first, its id in `name`'s place below
    std::vector<std::string> ids;
    std::string tree;
    auto tree_layer = [&](const ProjectLayer& l, const std::string& id, const char* indent) {
        tree += std::string(indent) + "<layer-tree-layer id=\"" + id + "\" name=\"" + l.name + "\" providerKey=\"ogr\" checked=\"Qt::Checked\" expanded=\"" +
                (l.name == "coast" ? "0" : "1") + "\" source=\"" + xml_text(l.source) + "\"/>\n";
        shown.push_back(l);
        ids.push_back(id);
    };
    const auto per_exercise = [&](const ProjectLayer& l) {
        return !view.exercises.empty() && l.filterable && std::find_if(std::begin(exercise_layers), std::end(exercise_layers),
                                                        [&](const char* n) { return l.name == n; }) != std::end(exercise_layers);
    };
    if (!view.exercises.empty()) {
        tree += "    <layer-tree-group name=\"exercises\" checked=\"Qt::Checked\" expanded=\"1\" mutually-exclusive=\"1\" mutually-exclusive-child=\"0\">\n";
        for (std::size_t k = 0; k < view.exercises.size(); ++k) {
            const std::string& e = view.exercises[k];
            tree += "      <layer-tree-group name=\"" + xml_text("exercise " + (e.empty() ? std::string("run") : e)) + "\" checked=\"" +
                    (k == 0 ? "Qt::Checked" : "Qt::Unchecked") + "\" expanded=\"" + (k == 0 ? "1" : "0") + "\">\n";
            std::string quoted;  // an SQL string literal: ' doubled
            for (const char c : e) quoted += c == '\'' ? std::string("''") : std::string(1, c);
            for (const ProjectLayer& l : layers)
                if (per_exercise(l))
                    tree_layer({l.name, l.geometry, l.source + "|subset=\"exercise\" = '" + quoted + "'", true}, "shoal_" + l.name + "_" + std::to_string(k + 1),
                               "        ");
            tree += "      </layer-tree-group>\n";
        }
        tree += "    </layer-tree-group>\n";
    }
    for (const ProjectLayer& l : layers)
        if (!per_exercise(l)) tree_layer(l, "shoal_" + l.name, "    ");
    x += "  <layer-tree-group>\n" + tree + "  </layer-tree-group>\n  <projectlayers>\n";
    for (std::size_t k = 0; k < shown.size(); ++k) x += map_layer(shown[k], ids[k]);
    x += "  </projectlayers>\n  <layerorder>\n";
    for (const std::string& id : ids) x += "    <layer id=\"" + id + "\"/>\n";
    x += "  </layerorder>\n";
    x += "  <properties><Paths><Absolute type=\"bool\">false</Absolute></Paths>"
         "<SpatialRefSys><ProjectionsEnabled type=\"int\">1</ProjectionsEnabled></SpatialRefSys></properties>\n";
    if (have_extent) {
        // The box in the project CRS (its edges sampled: a box in lon/lat is curved in UTM), plus 5 %.
        // The UTM zone as PROJ computes EPSG's (bit for bit: geo_test TransverseMercator.Utm*);
        // in EPSG:4326, the degrees as they are.
        const std::optional<geo::TransverseMercator> utm =
            geographic ? std::nullopt : std::optional<geo::TransverseMercator>(geo::TransverseMercator::utm(zone, lat_c < 0));
        double e0 = INFINITY, n0 = INFINITY, e1 = -INFINITY, n1 = -INFINITY;
        for (int i = 0; i <= 10; ++i)
            for (int j = 0; j <= 10; ++j) {
                if (i != 0 && i != 10 && j != 0 && j != 10) continue;
                double e = x0 + (x1 - x0) * i / 10, n = y0 + (y1 - y0) * j / 10;
                if (utm && !utm->forward(e, n, e, n)) continue;
                e0 = std::min(e0, e), n0 = std::min(n0, n), e1 = std::max(e1, e), n1 = std::max(n1, n);
            }
        const double pad = std::max({(e1 - e0) * 0.05, (n1 - n0) * 0.05, geographic ? 0.005 : 500.0});
        const int digits = geographic ? 6 : 1;
        if (geographic) {  // degrees: padded no further than the world
            e0 = std::max(e0 - pad, -180.0) + pad, e1 = std::min(e1 + pad, 180.0) - pad;
            n0 = std::max(n0 - pad, -90.0) + pad, n1 = std::min(n1 + pad, 90.0) - pad;
        }
        char box[256];
        std::snprintf(box, sizeof box, "xmin=\"%.*f\" ymin=\"%.*f\" xmax=\"%.*f\" ymax=\"%.*f\"", digits, e0 - pad, digits, n0 - pad, digits, e1 + pad,
                      digits, n1 + pad);
        char ext[256];
        std::snprintf(ext, sizeof ext, "<extent><xmin>%.*f</xmin><ymin>%.*f</ymin><xmax>%.*f</xmax><ymax>%.*f</ymax></extent>", digits, e0 - pad,
                      digits, n0 - pad, digits, e1 + pad, digits, n1 + pad);
        x += "  <mapcanvas name=\"theMapCanvas\" annotationsVisible=\"1\"><units>" + std::string(geographic ? "degrees" : "meters") + "</units>" + std::string(ext) +
             "<rotation>0</rotation><destinationsrs>" + srs_xml(epsg) + "</destinationsrs><rendermaptile>0</rendermaptile></mapcanvas>\n";
        x += "  <ProjectViewSettings UseProjectScales=\"0\" rotation=\"0\"><Scales/><DefaultViewExtent " + std::string(box) + ">" +
             srs_xml(epsg) + "</DefaultViewExtent></ProjectViewSettings>\n";
    }
    if (std::isfinite(view.first_fix_s) && std::isfinite(view.last_fix_s)) {
        // Frames of a minute for a run of up to two hours, five minutes up to a day, else an hour.
        const double span = view.last_fix_s - view.first_fix_s;
        // In exercise mode (a pose at every fix) frames of a second: a frame then holds one pose
        // of each ship whose fixes are a second or more apart at whole seconds (a pose holds from
        // its fix until the next, the end not included), not a trail of the minute's poses.
        const char* step = !view.exercises.empty() ? "timeStep=\"1\" timeStepUnit=\"s\""
                           : span <= 7200         ? "timeStep=\"1\" timeStepUnit=\"min\""
                           : span <= 86400        ? "timeStep=\"5\" timeStepUnit=\"min\""
                                                  : "timeStep=\"1\" timeStepUnit=\"h\"";
        x += "  <ProjectTimeSettings " + std::string(step) + " cumulativeTemporalRange=\"0\" frameRate=\"1\"><TemporalRange><start>" +
             iso_time(view.first_fix_s) + "</start><end>" + iso_time(view.last_fix_s) + "</end></TemporalRange></ProjectTimeSettings>\n";
    }
    x += "</qgis>\n";
    return x;
}

namespace {

void put16(std::string& out, unsigned v) {
    out += static_cast<char>(v & 0xff);
    out += static_cast<char>((v >> 8) & 0xff);
}
void put32(std::string& out, std::uint32_t v) {
    put16(out, v & 0xffff);
    put16(out, v >> 16);
}

/// `utf8` in code page 437, as GDAL's CPLRecode (UTF-8 to CP437, through iconv) makes a zip
/// member's name: a byte that cannot be converted is skipped (and with it, byte by byte, a
/// character that has no place in CP437); anything else ends the conversion.
std::string cp437_of(const std::string& utf8) {
    iconv_t cd = ::iconv_open("CP437", "UTF-8");
    if (cd == reinterpret_cast<iconv_t>(-1)) throw LibraryError("this system's iconv has no CP437, for the QGIS project's member name '" + utf8 + "'");
    std::string out(std::max<std::size_t>(32768, utf8.size() + 1), '\0');
    char* in = const_cast<char*>(utf8.data());
    std::size_t in_left = utf8.size();
    char* dst = out.data();
    std::size_t dst_left = out.size();
    while (in_left > 0) {
        if (::iconv(cd, &in, &in_left, &dst, &dst_left) != static_cast<std::size_t>(-1)) continue;
        if (errno == EILSEQ) {
            --in_left;
            ++in;
        } else if (errno == E2BIG) {
            const auto used = static_cast<std::size_t>(dst - out.data());
            out.resize(out.size() * 2);
            dst = out.data() + used;
            dst_left = out.size() - used;
        } else {
            break;
        }
    }
    ::iconv_close(cd);
    out.resize(static_cast<std::size_t>(dst - out.data()));
    return out;
}

/// The name of `member` in the zip and its extra field, as GDAL's zip writer makes them: a name
/// that is not ASCII in CP437, its UTF-8 in an Info-ZIP Unicode Path field (0x7075).
std::pair<std::string, std::string> member_name_and_unicode_field(const std::string& member) {
    const bool ascii = std::all_of(member.begin(), member.end(), [](char c) { return static_cast<unsigned char>(c) < 0x80; });
    if (ascii) return {member, ""};
    std::string name = cp437_of(member);
    std::string extra;
    const std::size_t data = 1 + 4 + member.size();
    if (4 + data <= 0xffff) {  // else GDAL leaves the field out
        put16(extra, 0x7075);
        put16(extra, static_cast<unsigned>(data));
        extra += '\1';
        put32(extra, static_cast<std::uint32_t>(::crc32(0, reinterpret_cast<const Bytef*>(name.data()), static_cast<uInt>(name.size()))));
        extra += member;
    }
    return {std::move(name), std::move(extra)};
}

/// The local header of a member called `name` up to its data, as GDAL's zip writer
/// (cpl_minizip_zip.cpp, ZIP64 on) writes it: version 4.5, no date, the name's extra field
/// `unicode`, then an empty ZIP64 field; its checksum and sizes (bytes 14-25) left 0.
std::string local_header(const std::string& name, const std::string& unicode) {
    std::string h;
    put32(h, 0x04034b50);
    put16(h, 45);  // version needed: ZIP64
    put16(h, 0);   // flags
    put16(h, 8);   // deflated
    put16(h, 0);   // time
    put16(h, 0);   // date
    put32(h, 0), put32(h, 0), put32(h, 0);
    put16(h, static_cast<unsigned>(name.size()));
    put16(h, static_cast<unsigned>(unicode.size() + 20));
    h += name;
    h += unicode;
    put16(h, 1);  // ZIP64 extended information, its sizes 0
    put16(h, 16);
    h.append(16, '\0');
    return h;
}

}  // namespace

std::string qgz_of(const std::string& member, const std::string& qgs) {
    // The bytes GDAL's CPLCreateZip, CPLCreateFileInZip and CPLWriteFileInZip wrote for the
    // project (report_test QgisProject.TheQgzIsTheZipGdalWrites), deflated by zlib as GDAL
    // has it do (level 6, raw, a 32 KiB window, memory level 8), without loading GDAL.
    if (qgs.size() >= 0xffffffffu || member.size() > 0xffff) throw LibraryError("the QGIS project is too big for its zip");
    const auto [name, unicode] = member_name_and_unicode_field(member);
    if (name.size() > 0xffff || unicode.size() + 20 > 0xffff) throw LibraryError("the QGIS project's name is too long for its zip");
    z_stream z{};
    if (::deflateInit2(&z, Z_DEFAULT_COMPRESSION, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        throw LibraryError("zlib cannot deflate the QGIS project");
    std::string data(::deflateBound(&z, static_cast<uLong>(qgs.size())), '\0');
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(qgs.data()));
    z.avail_in = static_cast<uInt>(qgs.size());
    z.next_out = reinterpret_cast<Bytef*>(data.data());
    z.avail_out = static_cast<uInt>(data.size());
    const int rc = ::deflate(&z, Z_FINISH);
    data.resize(z.total_out);
    ::deflateEnd(&z);
    if (rc != Z_STREAM_END) throw LibraryError("zlib could not deflate the QGIS project");
    std::string sizes;
    put32(sizes, static_cast<std::uint32_t>(::crc32(0, reinterpret_cast<const Bytef*>(qgs.data()), static_cast<uInt>(qgs.size()))));
    put32(sizes, static_cast<std::uint32_t>(data.size()));
    put32(sizes, static_cast<std::uint32_t>(qgs.size()));
    std::string out = local_header(name, unicode);
    out.replace(14, 12, sizes);
    out += data;
    // The central directory, its one entry, and its end.
    const auto directory_at = static_cast<std::uint32_t>(out.size());
    put32(out, 0x02014b50);
    put16(out, 45);  // made by
    put16(out, 45);  // needed
    put16(out, 0), put16(out, 8), put16(out, 0), put16(out, 0);  // flags, deflated, time, date
    out += sizes;
    put16(out, static_cast<unsigned>(name.size()));
    put16(out, static_cast<unsigned>(unicode.size()));
    put16(out, 0), put16(out, 0), put16(out, 0);  // comment, disk, internal attributes
    put32(out, 0), put32(out, 0);                 // external attributes, the local header's offset
    out += name;
    out += unicode;
    const auto directory_size = static_cast<std::uint32_t>(out.size() - directory_at);
    put32(out, 0x06054b50);
    put16(out, 0), put16(out, 0), put16(out, 1), put16(out, 1);
    put32(out, directory_size), put32(out, directory_at);
    put16(out, 0);
    return out;
}

bool is_shoal_qgz(const std::string& path, const std::string& member) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;  // a FIFO or a device is never opened
    // The member found by its name in the zip's directory, as GDAL's /vsizip/ finds it: as
    // written, or in CP437 as shoal writes a name that is not ASCII.
    std::string cp437;
    try {
        cp437 = member_name_and_unicode_field(member).first;
    } catch (const LibraryError&) {  // no CP437 in this system's iconv: the name as it is
    }
    const std::vector<detail::ZipEntry> entries = detail::zip_directory(path);
    const auto entry = std::find_if(entries.begin(), entries.end(), [&](const detail::ZipEntry& e) {
        return e.name == member || (!cp437.empty() && e.name == cp437);
    });
    if (entry == entries.end() || (entry->method != 0 && entry->method != 8)) return false;
    // Its local header, which must be the entry's (its name and method, as zip readers check:
    // a directory entry pointing at another member is no such member).
    const std::string local = detail::read_at(path, entry->local_header, 30 + entry->name.size());
    const auto u16 = [&](std::size_t at) {
        return static_cast<std::uint64_t>(static_cast<unsigned char>(local[at])) | static_cast<std::uint64_t>(static_cast<unsigned char>(local[at + 1])) << 8;
    };
    if (local.size() != 30 + entry->name.size() || local.compare(0, 4, std::string_view("PK\x03\x04", 4)) != 0 || u16(8) != entry->method ||
        u16(26) != entry->name.size() || local.compare(30, std::string::npos, entry->name) != 0)
        return false;
    const std::uint64_t data_at = entry->local_header + 30 + u16(26) + u16(28);
    // The project's first 4 KiB (the mark is on its second line), from at most 64 KiB of its
    // packed bytes (4 KiB of XML deflate to far less), read at once.
    constexpr std::size_t head = 4096, most_packed = 64 * 1024;
    std::string text;
    if (entry->method == 0) {
        text = detail::read_at(path, data_at, static_cast<std::size_t>(std::min<std::uint64_t>(head, entry->packed)));
    } else {
        std::string packed = detail::read_at(path, data_at, static_cast<std::size_t>(std::min<std::uint64_t>(most_packed, entry->packed)));
        z_stream z{};
        if (::inflateInit2(&z, -MAX_WBITS) != Z_OK) return false;
        text.assign(head, '\0');
        z.next_in = reinterpret_cast<Bytef*>(packed.data());
        z.avail_in = static_cast<uInt>(packed.size());
        z.next_out = reinterpret_cast<Bytef*>(text.data());
        z.avail_out = static_cast<uInt>(text.size());
        int rc = Z_OK;
        while (rc == Z_OK && z.avail_in > 0 && z.avail_out > 0) rc = ::inflate(&z, Z_NO_FLUSH);
        text.resize(text.size() - z.avail_out);
        ::inflateEnd(&z);
    }
    return text.find(sidecar_mark) != std::string::npos;
}

}  // namespace shoal::report
