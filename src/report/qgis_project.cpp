#include "report/qgis_project.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "detail/qgis_styles.hpp"
#include <shoal/report/report.hpp>
#include <shoal/util/error.hpp>

namespace shoal::report {

namespace {

std::string escape(std::string_view s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string srs_xml(int epsg) {
    OGRSpatialReference s;
    s.importFromEPSG(epsg);
    char* proj4 = nullptr;
    s.exportToProj4(&proj4);
    std::string p4 = proj4 ? proj4 : "";
    CPLFree(proj4);
    const char* name = s.GetName();
    return "<spatialrefsys><proj4>" + escape(p4) + "</proj4><srid>" + std::to_string(epsg) + "</srid><authid>EPSG:" + std::to_string(epsg) +
           "</authid><description>" + escape(name ? name : "") + "</description><geographicflag>" + (s.IsGeographic() ? "true" : "false") +
           "</geographicflag></spatialrefsys>";
}

/// The <maplayer> of one layer: the style's root attributes and elements, wrapped.
std::string map_layer(const std::string& name, const std::string& geometry, const std::string& source) {
    const std::string qml(layer_style(name));
    const std::size_t open = qml.find("<qgis ");
    const std::size_t open_end = qml.find('>', open);
    const std::size_t close = qml.rfind("</qgis>");
    if (open == std::string::npos || open_end == std::string::npos || close == std::string::npos)
        throw LibraryError("the QGIS style of layer " + name + " is not a QGIS style");
    std::string attrs = qml.substr(open + 6, open_end - open - 6);
    // The style's own version attribute is the style's, not the layer's.
    if (std::size_t v = attrs.find("version=\""); v != std::string::npos) attrs.erase(v, attrs.find('"', v + 9) + 1 - v);
    return "    <maplayer type=\"vector\" geometry=\"" + geometry + "\" " + attrs + ">\n      <id>shoal_" + name + "</id>\n      <datasource>" +
           escape(source) + "</datasource>\n      <layername>" + name + "</layername>\n      <srs>" + srs_xml(4326) +
           "</srs>\n      <provider encoding=\"UTF-8\">ogr</provider>\n" + qml.substr(open_end + 1, close - open_end - 1) + "    </maplayer>\n";
}

const char* geometry_of(OGRLayer& l) {
    switch (wkbFlatten(l.GetGeomType())) {
        case wkbPoint: case wkbMultiPoint: return "Point";
        case wkbLineString: case wkbMultiLineString: return "Line";
        default: return "Polygon";
    }
}

}  // namespace

void ProjectView::add(const ProjectView& o) {
    x0 = std::min(x0, o.x0), y0 = std::min(y0, o.y0), x1 = std::max(x1, o.x1), y1 = std::max(y1, o.y1);
    if (!std::isnan(o.first_fix_s)) first_fix_s = std::isnan(first_fix_s) ? o.first_fix_s : std::min(first_fix_s, o.first_fix_s);
    if (!std::isnan(o.last_fix_s)) last_fix_s = std::isnan(last_fix_s) ? o.last_fix_s : std::max(last_fix_s, o.last_fix_s);
}

ProjectView project_view(const audit::AuditResult& r) {
    ProjectView v;
    for (const auto& t : r.tracks)
        for (const auto& line : t.summary.lines)
            for (const auto& p : line) {
                v.x0 = std::min(v.x0, p.lon), v.y0 = std::min(v.y0, p.lat);
                v.x1 = std::max(v.x1, p.lon), v.y1 = std::max(v.y1, p.lat);
            }
    v.first_fix_s = r.first_fix_s;
    v.last_fix_s = r.last_fix_s;
    return v;
}

std::string qgis_project_xml(GDALDataset& ds, const std::string& file_name, const ProjectView& view) {
    // Top of the map first (QGIS's layer tree order).
    std::vector<std::pair<std::string, std::string>> layers;  // name, geometry
    for (const char* name : {"breaches", "events", "encounters", "hulls", "poses", "tracks", "coast"})
        if (OGRLayer* l = ds.GetLayerByName(name)) layers.emplace_back(name, geometry_of(*l));

    // The run's extent (its tracks), and the UTM zone of its centre.
    const double x0 = view.x0, y0 = view.y0, x1 = view.x1, y1 = view.y1;
    const bool have_extent = x0 <= x1 && y0 <= y1;
    const double lon_c = have_extent ? (x0 + x1) / 2 : 0, lat_c = have_extent ? (y0 + y1) / 2 : 0;
    const int zone = std::clamp(static_cast<int>(std::floor((lon_c + 180) / 6)) + 1, 1, 60);
    const int epsg = (lat_c >= 0 ? 32600 : 32700) + zone;

    std::string x = "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n<qgis projectname=\"shoal report\" version=\"3.22.16-Białowieża\">\n";
    x += "  <title>shoal report " + escape(file_name) + "</title>\n";
    x += "  <projectCrs>" + srs_xml(epsg) + "</projectCrs>\n";
    x += "  <layer-tree-group>\n";
    for (const auto& [name, geom] : layers)
        x += "    <layer-tree-layer id=\"shoal_" + name + "\" name=\"" + name + "\" providerKey=\"ogr\" checked=\"Qt::Checked\" expanded=\"" +
             (name == "coast" ? "0" : "1") + "\" source=\"" + escape("./" + file_name + "|layername=" + name) + "\"/>\n";
    x += "  </layer-tree-group>\n  <projectlayers>\n";
    for (const auto& [name, geom] : layers) x += map_layer(name, geom, "./" + file_name + "|layername=" + name);
    x += "  </projectlayers>\n  <layerorder>\n";
    for (const auto& [name, geom] : layers) x += "    <layer id=\"shoal_" + name + "\"/>\n";
    x += "  </layerorder>\n";
    x += "  <properties><Paths><Absolute type=\"bool\">false</Absolute></Paths>"
         "<SpatialRefSys><ProjectionsEnabled type=\"int\">1</ProjectionsEnabled></SpatialRefSys></properties>\n";
    if (have_extent) {
        // The tracks' box in the project CRS (its edges sampled: a box in lon/lat is curved in UTM), plus 5 %.
        OGRSpatialReference wgs, utm;
        wgs.importFromEPSG(4326);
        wgs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        utm.importFromEPSG(epsg);
        utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&wgs, &utm));
        if (!ct) throw LibraryError("no transformation from EPSG:4326 to EPSG:" + std::to_string(epsg));
        double e0 = INFINITY, n0 = INFINITY, e1 = -INFINITY, n1 = -INFINITY;
        for (int i = 0; i <= 10; ++i)
            for (int j = 0; j <= 10; ++j) {
                if (i != 0 && i != 10 && j != 0 && j != 10) continue;
                double e = x0 + (x1 - x0) * i / 10, n = y0 + (y1 - y0) * j / 10;
                if (!ct->Transform(1, &e, &n)) continue;
                e0 = std::min(e0, e), n0 = std::min(n0, n), e1 = std::max(e1, e), n1 = std::max(n1, n);
            }
        const double pad = std::max({(e1 - e0) * 0.05, (n1 - n0) * 0.05, 500.0});
        char box[256];
        std::snprintf(box, sizeof box, "xmin=\"%.1f\" ymin=\"%.1f\" xmax=\"%.1f\" ymax=\"%.1f\"", e0 - pad, n0 - pad, e1 + pad, n1 + pad);
        char ext[256];
        std::snprintf(ext, sizeof ext, "<extent><xmin>%.1f</xmin><ymin>%.1f</ymin><xmax>%.1f</xmax><ymax>%.1f</ymax></extent>", e0 - pad, n0 - pad,
                      e1 + pad, n1 + pad);
        x += "  <mapcanvas name=\"theMapCanvas\" annotationsVisible=\"1\"><units>meters</units>" + std::string(ext) +
             "<rotation>0</rotation><destinationsrs>" + srs_xml(epsg) + "</destinationsrs><rendermaptile>0</rendermaptile></mapcanvas>\n";
        x += "  <ProjectViewSettings UseProjectScales=\"0\" rotation=\"0\"><Scales/><DefaultViewExtent " + std::string(box) + ">" +
             srs_xml(epsg) + "</DefaultViewExtent></ProjectViewSettings>\n";
    }
    if (std::isfinite(view.first_fix_s) && std::isfinite(view.last_fix_s)) {
        // Frames of a minute for a run of up to two hours, five minutes up to a day, else an hour.
        const double span = view.last_fix_s - view.first_fix_s;
        const char* step = span <= 7200 ? "timeStep=\"1\" timeStepUnit=\"min\"" : span <= 86400 ? "timeStep=\"5\" timeStepUnit=\"min\"" : "timeStep=\"1\" timeStepUnit=\"h\"";
        x += "  <ProjectTimeSettings " + std::string(step) + " cumulativeTemporalRange=\"0\" frameRate=\"1\"><TemporalRange><start>" +
             iso_time(view.first_fix_s) + "</start><end>" + iso_time(view.last_fix_s) + "</end></TemporalRange></ProjectTimeSettings>\n";
    }
    x += "</qgis>\n";
    return x;
}

namespace {

void put16(std::string& s, unsigned v) {
    s += static_cast<char>(v & 0xff);
    s += static_cast<char>((v >> 8) & 0xff);
}
void put32(std::string& s, unsigned long v) {
    put16(s, static_cast<unsigned>(v & 0xffff));
    put16(s, static_cast<unsigned>((v >> 16) & 0xffff));
}

}  // namespace

std::string zip_one(const std::string& name, const std::string& content) {
    // Raw deflate (window bits -15), as a zip member holds it.
    z_stream z{};
    if (deflateInit2(&z, Z_BEST_COMPRESSION, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) throw LibraryError("zlib deflateInit2 failed");
    std::string packed(deflateBound(&z, static_cast<uLong>(content.size())), '\0');
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(content.data()));
    z.avail_in = static_cast<uInt>(content.size());
    z.next_out = reinterpret_cast<Bytef*>(packed.data());
    z.avail_out = static_cast<uInt>(packed.size());
    const int rc = deflate(&z, Z_FINISH);
    packed.resize(z.total_out);
    deflateEnd(&z);
    if (rc != Z_STREAM_END) throw LibraryError("zlib deflate failed");
    const unsigned long crc = crc32(0L, reinterpret_cast<const Bytef*>(content.data()), static_cast<uInt>(content.size()));
    constexpr unsigned dos_time = 0, dos_date = (0u << 9) | (1u << 5) | 1u;  // 1980-01-01 00:00
    std::string out;
    auto header = [&](bool central) {
        put32(out, central ? 0x02014b50 : 0x04034b50);
        if (central) put16(out, 20);  // made by
        put16(out, 20);               // version needed
        put16(out, 0x0800);           // flags: UTF-8 name
        put16(out, 8);                // deflate
        put16(out, dos_time);
        put16(out, dos_date);
        put32(out, crc);
        put32(out, packed.size());
        put32(out, content.size());
        put16(out, static_cast<unsigned>(name.size()));
        put16(out, 0);  // extra
        if (central) {
            put16(out, 0);  // comment
            put16(out, 0);  // disk
            put16(out, 0);  // internal attributes
            put32(out, 0);  // external attributes
            put32(out, 0);  // offset of the local header
        }
        out += name;
    };
    header(false);
    out += packed;
    const std::size_t central_at = out.size();
    header(true);
    const std::size_t central_size = out.size() - central_at;
    put32(out, 0x06054b50);
    put16(out, 0);
    put16(out, 0);
    put16(out, 1);
    put16(out, 1);
    put32(out, central_size);
    put32(out, central_at);
    put16(out, 0);
    return out;
}

void add_qgis_project(GDALDataset& ds, const std::string& file_name, const ProjectView& view) {
    const std::string qgz = zip_one("shoal.qgs", qgis_project_xml(ds, file_name, view));
    static const char hex[] = "0123456789abcdef";
    std::string h;
    h.reserve(qgz.size() * 2);
    for (unsigned char c : qgz) {
        h += hex[c >> 4];
        h += hex[c & 15];
    }
    for (const std::string& sql : {std::string("CREATE TABLE qgis_projects(name TEXT PRIMARY KEY, metadata BLOB, content BLOB)"),
                                  "INSERT INTO qgis_projects VALUES ('" + std::string(qgis_project_name) +
                                      "', '{\"last_modified_time\": \"2000-01-01T00:00:00\", \"last_modified_user\": \"shoal\" }', '" + h + "')"}) {
        CPLErrorReset();
        OGRLayer* res = ds.ExecuteSQL(sql.c_str(), nullptr, nullptr);
        if (res) ds.ReleaseResultSet(res);
        if (CPLGetLastErrorType() == CE_Failure) throw LibraryError("writing the QGIS project into the GeoPackage: " + std::string(CPLGetLastErrorMsg()));
    }
}

}  // namespace shoal::report
