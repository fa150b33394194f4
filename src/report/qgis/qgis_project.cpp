#include "report/qgis/qgis_project.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <cpl_conv.h>
#include <cpl_vsi.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "report/qgis/qgis_styles.hpp"
#include <shoal/report/markup.hpp>
#include <shoal/report/geojson_report.hpp>
#include <shoal/util/error.hpp>

namespace shoal::report {

namespace {

/// The project's text: the one markup escaper, `'` kept (every attribute is in double quotes).
std::string xml_text(std::string_view s) { return markup_text(s, Apostrophe::kept); }

std::string srs_xml(int epsg) {
    OGRSpatialReference s;
    s.importFromEPSG(epsg);
    char* proj4 = nullptr;
    s.exportToProj4(&proj4);
    std::string p4 = proj4 ? proj4 : "";
    CPLFree(proj4);
    const char* name = s.GetName();
    return "<spatialrefsys><proj4>" + xml_text(p4) + "</proj4><srid>" + std::to_string(epsg) + "</srid><authid>EPSG:" + std::to_string(epsg) +
           "</authid><description>" + xml_text(name ? name : "") + "</description><geographicflag>" + (s.IsGeographic() ? "true" : "false") +
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

const char* geometry_of(OGRLayer& l) {
    switch (wkbFlatten(l.GetGeomType())) {
        case wkbPoint: case wkbMultiPoint: return "Point";
        case wkbLineString: case wkbMultiLineString: return "Line";
        default: return "Polygon";
    }
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

std::string qgz_of(const std::string& member, const std::string& qgs) {
    // Through GDAL's zip writer into a file in memory (GDAL stamps no date: the same XML, the same bytes).
    static std::atomic<unsigned> serial{0};
    const std::string zip = "/vsimem/shoal-qgz-" + std::to_string(serial++) + ".qgz";
    void* z = CPLCreateZip(zip.c_str(), nullptr);
    if (!z) throw LibraryError("GDAL cannot create a zip in memory: " + std::string(CPLGetLastErrorMsg()));
    const bool ok = CPLCreateFileInZip(z, member.c_str(), nullptr) == CE_None &&
                    CPLWriteFileInZip(z, qgs.data(), static_cast<int>(qgs.size())) == CE_None && CPLCloseFileInZip(z) == CE_None;
    const bool closed = CPLCloseZip(z) == CE_None;
    vsi_l_offset n = 0;
    GByte* bytes = VSIGetMemFileBuffer(zip.c_str(), &n, FALSE);
    std::string out = ok && closed && bytes ? std::string(reinterpret_cast<const char*>(bytes), static_cast<std::size_t>(n)) : std::string();
    VSIUnlink(zip.c_str());
    if (out.empty()) throw LibraryError("GDAL could not zip the QGIS project: " + std::string(CPLGetLastErrorMsg()));
    return out;
}

bool is_shoal_qgz(const std::string& path, const std::string& member) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;  // a FIFO or a device is never opened
    VSILFILE* f = VSIFOpenL(("/vsizip/{" + path + "}/" + member).c_str(), "rb");
    if (!f) return false;
    std::string head(4096, '\0');
    head.resize(VSIFReadL(head.data(), 1, head.size(), f));
    VSIFCloseL(f);
    return head.find(sidecar_mark) != std::string::npos;
}

void add_qgis_project(GDALDataset& ds, const std::string& file_name, const ProjectView& view) {
    std::vector<ProjectLayer> layers;
    for (const char* name : report_layers_top_first)
        if (OGRLayer* l = ds.GetLayerByName(name)) layers.push_back({name, geometry_of(*l), "./" + file_name + "|layername=" + name});
    const std::string qgz = qgz_of("shoal.qgs", qgis_project_xml(layers, file_name, view));
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
