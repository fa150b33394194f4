#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <filesystem>
#include <variant>

#include "util/gdal_support.hpp"
#include "report/qgis/qgis_styles.hpp"
#include "report/qgis/chart_layer.hpp"
#include "report/gpkg_output.hpp"
#include "report/part_order.hpp"
#include "report/qgis/qgis_project.hpp"
#include <shoal/report/report_fields.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/report/gpkg_report.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal::report {

namespace {

using fields::Field;

OGRFieldType ogr_type(fields::Type t) {
    switch (t) {
        case fields::Type::text: return OFTString;
        case fields::Type::integer: return OFTInteger64;
        case fields::Type::real: return OFTReal;
        case fields::Type::boolean: return OFTInteger;
        case fields::Type::datetime: return OFTDateTime;
    }
    return OFTString;
}

/// A layer (or, with wkbNone, a table without geometry) with the fields of `table` that are
/// present in this run, in the table's order.
template <class Row>
OGRLayer& make_layer(GDALDataset& ds, const char* name, OGRwkbGeometryType type, const std::vector<Field<Row>>& table,
                     const audit::AuditResult& r) {
    OGRSpatialReference wgs84;
    wgs84.importFromEPSG(4326);
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    OGRLayer* l = ds.CreateLayer(name, type == wkbNone ? nullptr : &wgs84, type, nullptr);
    if (!l) throw LibraryError(std::string("creating layer ") + name + ": " + CPLGetLastErrorMsg());
    for (const auto& f : table) {
        if (f.present && !f.present(r)) continue;
        OGRFieldDefn d(f.name, ogr_type(f.type));
        if (f.type == fields::Type::boolean) d.SetSubType(OFSTBoolean);
        if (l->CreateField(&d) != OGRERR_NONE)
            throw LibraryError(std::string("creating GeoPackage field ") + name + "." + f.name + ": " + CPLGetLastErrorMsg());
    }
    return *l;
}

/// Writes one feature: the fields of `table` for `row`, and `geometry` (may be null).
template <class Row>
void put(OGRLayer& layer, const std::vector<Field<Row>>& table, const Row& row, const audit::AuditResult& r, const OGRGeometry* geometry) {
    OGRFeature f(layer.GetLayerDefn());
    int i = 0;
    for (const auto& field : table) {
        if (field.present && !field.present(r)) continue;
        std::visit(
            [&](const auto& v) {
                using V = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<V, std::monostate>) f.SetFieldNull(i);
                else if constexpr (std::is_same_v<V, std::string>) f.SetField(i, v.c_str());
                else if constexpr (std::is_same_v<V, std::int64_t>) f.SetField(i, static_cast<GIntBig>(v));
                else if constexpr (std::is_same_v<V, bool>) f.SetField(i, v ? 1 : 0);
                else f.SetField(i, v);
            },
            fields::value_of(field, row));
        ++i;
    }
    if (geometry) f.SetGeometry(geometry);
    if (layer.CreateFeature(&f) != OGRERR_NONE)
        throw LibraryError(std::string("writing a feature to layer ") + layer.GetName() + ": " + CPLGetLastErrorMsg());
}

OGRPoint point(geo::LonLat p) {
    using fields::round_to, fields::coordinate_decimals;
    return OGRPoint(round_to(p.lon, coordinate_decimals), round_to(p.lat, coordinate_decimals));
}

void fill_tracks(OGRLayer& tracks, const audit::AuditResult& r) {
    for (const auto& t : fields::track_rows(r)) {
        OGRMultiLineString ml;
        for (const auto& piece : t.track.lines) {
            OGRLineString ls;
            for (const auto& p : piece) ls.addPoint(p.lon, p.lat);
            if (ls.getNumPoints() == 1) ls.addPoint(piece[0].lon, piece[0].lat);
            ml.addGeometry(&ls);
        }
        put(tracks, fields::track_fields(), t, r, &ml);
    }
}

void fill_hulls(OGRLayer& hulls, const audit::AuditResult& r) {
    for (const auto& h : fields::hull_rows(r)) {
        OGRLinearRing ring;
        for (const auto& p : h.ring) ring.addPoint(p.lon, p.lat);
        OGRPolygon poly;
        poly.addRing(&ring);
        put(hulls, fields::hull_fields(), h, r, &poly);
    }
}

void fill_poses(OGRLayer& poses, const audit::AuditResult& r) {
    for (const auto& t : r.tracks)
        for (const auto& p : t.poses) {
            OGRLinearRing ring;
            for (const auto& q : p.hull) ring.addPoint(q.lon, q.lat);
            OGRPolygon poly;
            poly.addRing(&ring);
            put(poses, fields::pose_fields(), fields::PoseRow{t.summary, p}, r, &poly);
        }
}

void fill_coast(OGRLayer& coast, const audit::AuditResult& r, const coast::Coastline& chart) {
    for (const ChartFeature& c : chart_features_near(r, chart)) {
        OGRMultiPolygon mp;
        for (const auto& rings : c.polygons) {
            OGRPolygon poly;
            for (const auto& ring : rings) {
                OGRLinearRing lr;
                for (const auto& q : ring) lr.addPoint(q.lon, q.lat);
                poly.addRing(&lr);
            }
            mp.addGeometry(&poly);
        }
        put(coast, fields::coast_fields(), fields::coast_row(c), r, &mp);
    }
}

bool with_chart(const RunInfo& info) { return info.project && info.chart != nullptr; }

void write_layers(GDALDataset& ds, const audit::AuditResult& r, const RunInfo& info) {
    const GpkgLayers layers = make_gpkg_layers(ds, r, with_chart(info), info.project);
    OGRLayer &events = *layers.events, &tracks = *layers.tracks, &hulls = *layers.hulls, &problems = *layers.problems,
             &run = *layers.run, &summary = *layers.summary;
    OGRLayer *coast = layers.coast, *encounters = layers.encounters, *approaches = layers.approaches;

    if (ds.StartTransaction() != OGRERR_NONE) throw LibraryError("GeoPackage transaction failed");
    for (const auto& t : r.tracks)
        for (const auto& e : t.events) {
            const OGRPoint pt = point(e.point);
            put(events, fields::event_fields(), fields::EventRow{t.summary, e}, r, &pt);
        }
    for (const auto& e : r.encounters.events) {
        const OGRPoint pt = point(e.point);
        put(*encounters, fields::encounter_fields(), fields::EncounterRow{r, e}, r, &pt);
    }
    if (layers.breaches)
        for (const auto& b : r.assessment.breaches) {
            const OGRPoint pt = point({b.lon, b.lat});
            put(*layers.breaches, fields::breach_fields(), fields::BreachRow{r, b}, r, &pt);
        }
    fill_tracks(tracks, r);
    fill_hulls(hulls, r);
    if (layers.poses) fill_poses(*layers.poses, r);
    if (coast) fill_coast(*coast, r, *info.chart);
    if (layers.learned)
        for (const auto& p : r.places) {
            const OGRPoint pt = point(p.position);
            put(*layers.learned, fields::learned_fields(), fields::LearnedRow{p}, r, &pt);
        }
    for (const auto& p : fields::problem_rows(r)) put(problems, fields::problem_fields(), p, r, nullptr);
    if (approaches)
        for (const auto& a : r.encounters.approaches) put(*approaches, fields::approach_fields(), fields::ApproachRow{r, a}, r, nullptr);
    if (layers.scores)
        for (const auto& s : r.assessment.scores) put(*layers.scores, fields::score_fields(), fields::ScoreRow{r, s}, r, nullptr);
    put(run, fields::run_fields(), fields::RunRow{r, info}, r, nullptr);
    put(summary, fields::summary_fields(), fields::RunRow{r, info}, r, nullptr);
    if (layers.part) {
        OGRFeature f(layers.part->GetLayerDefn());
        f.SetField(0, part_order(r, true, info.chart_lonlat).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
        if (layers.part->CreateFeature(&f) != OGRERR_NONE) throw LibraryError(std::string("writing the part table: ") + CPLGetLastErrorMsg());
    }
    if (ds.CommitTransaction() != OGRERR_NONE) throw LibraryError("GeoPackage commit failed: " + std::string(CPLGetLastErrorMsg()));
}

/// A layer's geometry as the QGIS project names it.
const char* geometry_of(OGRLayer& l) {
    switch (wkbFlatten(l.GetGeomType())) {
        case wkbPoint: case wkbMultiPoint: return "Point";
        case wkbLineString: case wkbMultiLineString: return "Line";
        default: return "Polygon";
    }
}

}  // namespace

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

GpkgLayers make_gpkg_layers(GDALDataset& ds, const audit::AuditResult& r, bool chart, bool poses) {
    GpkgLayers l;
    l.events = &make_layer(ds, "events", wkbPoint, fields::event_fields(), r);
    l.tracks = &make_layer(ds, "tracks", wkbMultiLineString, fields::track_fields(), r);
    l.hulls = &make_layer(ds, "hulls", wkbPolygon, fields::hull_fields(), r);
    if (poses) l.poses = &make_layer(ds, "poses", wkbPolygon, fields::pose_fields(), r);
    if (chart) l.coast = &make_layer(ds, "coast", wkbMultiPolygon, fields::coast_fields(), r);
    // --world real: the places the run's traffic taught (learned berths, water the chart lacks).
    if (r.world == audit::World::real) l.learned = &make_layer(ds, "learned", wkbPoint, fields::learned_fields(), r);
    // Exercise mode: ship-to-ship encounters, their own layer (hull footprints of both ships
    // go into `hulls` with kind collision / close_quarters).
    if (r.has_encounters) l.encounters = &make_layer(ds, "encounters", wkbPoint, fields::encounter_fields(), r);
    // --assess: one point per breach (at its worst moment), one row per trainee's score.
    if (r.has_assessment) l.breaches = &make_layer(ds, "breaches", wkbPoint, fields::breach_fields(), r);
    l.problems = &make_layer(ds, "problems", wkbNone, fields::problem_fields(), r);
    if (r.has_encounters) l.approaches = &make_layer(ds, "closest_approaches", wkbNone, fields::approach_fields(), r);
    if (r.has_assessment) l.scores = &make_layer(ds, "scores", wkbNone, fields::score_fields(), r);
    l.run = &make_layer(ds, "run", wkbNone, fields::run_fields(), r);
    l.summary = &make_layer(ds, "summary", wkbNone, fields::summary_fields(), r);
    if (r.shard.active()) {
        l.part = ds.CreateLayer("part", nullptr, wkbNone, nullptr);
        OGRFieldDefn d("order", OFTString);
        if (!l.part || l.part->CreateField(&d) != OGRERR_NONE) throw LibraryError(std::string("creating the GeoPackage table part: ") + CPLGetLastErrorMsg());
    }
    return l;
}

const char* name_of(MapLayer which) noexcept {
    switch (which) {
        case MapLayer::tracks: return "tracks";
        case MapLayer::hulls: return "hulls";
        case MapLayer::poses: return "poses";
        case MapLayer::coast: return "coast";
        case MapLayer::learned: return "learned";
    }
    return "";
}

StagedOutput stage_gpkg_with(const std::string& path, const std::function<void(GDALDataset&)>& fill, const ProjectView* view) {
    detail::register_drivers();
    StagedOutput out(path);  // removed (with SQLite's journal) if interrupted or if anything below fails
    if (out.direct())
        throw InputError("cannot write '" + path + "': a GeoPackage must be a regular file (write it elsewhere, or write GeoJSON)");
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
    if (!drv) throw LibraryError("GDAL has no GPKG driver");
    // A fixed "current date" in the GeoPackage's metadata tables: the same run writes the
    // same bytes (whatever --jobs is, and merged from shards).
    CPLSetThreadLocalConfigOption("OGR_CURRENT_DATE", "2000-01-01T00:00:00.000Z");
    GDALDatasetUniquePtr ds(drv->Create(out.temp_path().c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!ds) throw InputError("cannot write '" + path + "': " + CPLGetLastErrorMsg());
    fill(*ds);
    add_layer_styles(*ds);
    if (view) add_qgis_project(*ds, std::filesystem::path(path).filename().string(), *view);
    CPLErrorReset();
    ds.reset();  // GDALClose: flushes and closes the SQLite file
    if (CPLGetLastErrorType() == CE_Failure) throw InputError("cannot write '" + path + "': " + CPLGetLastErrorMsg());
    return out;
}

StagedOutput stage_gpkg(const std::string& path, const audit::AuditResult& result, const RunInfo& info) {
    const ProjectView view = project_view(result, info.chart_lonlat);
    return stage_gpkg_with(path, [&](GDALDataset& ds) { write_layers(ds, result, info); }, info.project ? &view : nullptr);
}

void write_gpkg(const std::string& path, const audit::AuditResult& result, const RunInfo& info) { stage_gpkg(path, result, info).commit(); }

bool is_shoal_gpkg_report(const std::string& path) {
    if (file_head(path, 16) != std::string("SQLite format 3\0", 16)) return false;
    detail::register_drivers();  // merge asks before anything else of GDAL has been used
    const char* drivers[] = {"GPKG", nullptr};
    const CPLErrorStateBackuper keep;  // the last error as it was: this is a question, not a failure
    CPLPushErrorHandler(detail::quiet_error_handler);
    const GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, drivers, nullptr, nullptr));
    CPLPopErrorHandler();
    return ds && ds->GetLayerByName("events") && ds->GetLayerByName("tracks");
}

}  // namespace shoal::report
