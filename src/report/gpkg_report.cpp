#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "detail/qgis_styles.hpp"
#include <shoal/report/report.hpp>
#include <shoal/util/atomic_file.hpp>
#include <shoal/util/error.hpp>

namespace shoal::report {

namespace fs = std::filesystem;

namespace {

void add_field(OGRLayer& layer, const char* name, OGRFieldType type, OGRFieldSubType subtype = OFSTNone) {
    OGRFieldDefn f(name, type);
    f.SetSubType(subtype);
    if (layer.CreateField(&f) != OGRERR_NONE)
        throw LibraryError(std::string("creating GeoPackage field ") + name + ": " + CPLGetLastErrorMsg());
}

OGRLayer& make_layer(GDALDataset& ds, const char* name, OGRwkbGeometryType type, OGRSpatialReference& srs) {
    OGRLayer* l = ds.CreateLayer(name, &srs, type, nullptr);
    if (!l) throw LibraryError(std::string("creating GeoPackage layer ") + name + ": " + CPLGetLastErrorMsg());
    return *l;
}

void put(OGRLayer& layer, OGRFeature& f) {
    if (layer.CreateFeature(&f) != OGRERR_NONE)
        throw LibraryError(std::string("writing a feature to layer ") + layer.GetName() + ": " + CPLGetLastErrorMsg());
}

double finite_or_null(OGRFeature& f, const char* field, double v) {
    if (std::isfinite(v)) f.SetField(field, v);
    else f.SetFieldNull(f.GetFieldIndex(field));
    return v;
}

void write_layers(GDALDataset& ds, const audit::AuditResult& r) {
    OGRSpatialReference wgs84;
    wgs84.importFromEPSG(4326);
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);

    OGRLayer& events = make_layer(ds, "events", wkbPoint, wgs84);
    for (const char* s : {"track", "name", "kind", "hit"}) add_field(events, s, OFTString);
    add_field(events, "charted_depth_m", OFTReal);
    add_field(events, "danger", OFTString);
    for (const char* s : {"start", "end"}) add_field(events, s, OFTString);
    for (const char* s : {"duration_s", "min_clearance_m", "penetration_m", "ship_lat", "ship_lon", "heading"}) add_field(events, s, OFTReal);
    add_field(events, "heading_source", OFTString);
    add_field(events, "orientation", OFTString);
    add_field(events, "speed_kn", OFTReal);
    add_field(events, "speed_source", OFTString);
    add_field(events, "stopped_before", OFTInteger, OFSTBoolean);
    add_field(events, "stopped_after_s", OFTReal);
    add_field(events, "reference_inside_m", OFTReal);
    add_field(events, "nav_status", OFTInteger);
    add_field(events, "nav_status_text", OFTString);
    add_field(events, "reported_aground", OFTInteger, OFSTBoolean);
    for (const char* s : {"unseen_after", "area", "area_name", "structure"}) add_field(events, s, OFTString);
    add_field(events, "fix_index", OFTInteger64);
    add_field(events, "fix_line", OFTInteger64);
    add_field(events, "file", OFTString);
    add_field(events, "hull", OFTString);
    add_field(events, "label", OFTString);

    OGRLayer& tracks = make_layer(ds, "tracks", wkbMultiLineString, wgs84);
    for (const char* s : {"track", "name", "file", "hull"}) add_field(tracks, s, OFTString);
    for (const char* s : {"fixes", "skipped_rows", "uncovered_fixes", "segments", "groundings", "alongside",
                          "contacts_at_start", "expected_contacts", "close_passes", "wild_fixes", "jumps", "unknown_heading_fixes"})
        add_field(tracks, s, OFTInteger64);
    add_field(tracks, "min_clearance_m", OFTReal);
    add_field(tracks, "distance_km", OFTReal);
    add_field(tracks, "start", OFTString);
    add_field(tracks, "end", OFTString);

    OGRLayer& hulls = make_layer(ds, "hulls", wkbPolygon, wgs84);
    for (const char* s : {"track", "kind", "hit", "start", "label"}) add_field(hulls, s, OFTString);

    // Exercise mode: ship-to-ship encounters, their own layer (hull footprints of both ships
    // go into `hulls` with kind collision / close_quarters).
    OGRLayer* encounters = nullptr;
    if (r.has_encounters) {
        encounters = &make_layer(ds, "encounters", wkbPoint, wgs84);
        for (const char* f : {"track", "other_track", "kind", "start", "end"}) add_field(*encounters, f, OFTString);
        for (const char* f : {"duration_s", "min_clearance_m", "distance_m", "ship_lat", "ship_lon", "heading", "other_lat",
                              "other_lon", "other_heading"})
            add_field(*encounters, f, OFTReal);
        add_field(*encounters, "label", OFTString);
    }

    std::map<std::string, std::size_t> skipped_by_file;
    for (const auto& f : r.files) skipped_by_file[f.file] = f.read.skipped;

    if (ds.StartTransaction() != OGRERR_NONE) throw LibraryError("GeoPackage transaction failed");
    for (const auto& t : r.tracks) {
        const auto& s = t.summary;
        OGRFeature tf(tracks.GetLayerDefn());
        tf.SetField("track", s.id.c_str());
        tf.SetField("name", s.name.c_str());
        tf.SetField("file", s.file.c_str());
        tf.SetField("hull", s.hull.c_str());
        tf.SetField("fixes", static_cast<GIntBig>(s.fixes));
        tf.SetField("skipped_rows", static_cast<GIntBig>(skipped_by_file[s.file]));
        tf.SetField("uncovered_fixes", static_cast<GIntBig>(s.uncovered_fixes));
        tf.SetField("segments", static_cast<GIntBig>(s.segments));
        tf.SetField("groundings", static_cast<GIntBig>(s.groundings));
        tf.SetField("close_passes", static_cast<GIntBig>(s.close_passes));
        tf.SetField("alongside", static_cast<GIntBig>(s.alongside));
        tf.SetField("contacts_at_start", static_cast<GIntBig>(s.contacts_at_start));
        tf.SetField("expected_contacts", static_cast<GIntBig>(s.expected_contacts));
        tf.SetField("wild_fixes", static_cast<GIntBig>(s.wild_fixes.size()));
        tf.SetField("jumps", static_cast<GIntBig>(s.jumps));
        tf.SetField("unknown_heading_fixes", static_cast<GIntBig>(s.unknown_heading_fixes));
        finite_or_null(tf, "min_clearance_m", s.min_clearance_m);
        tf.SetField("distance_km", s.distance_m / 1000);
        tf.SetField("start", iso_time(s.start_s).c_str());
        tf.SetField("end", iso_time(s.end_s).c_str());
        OGRMultiLineString ml;
        for (const auto& piece : s.lines) {
            OGRLineString ls;
            for (const auto& p : piece) ls.addPoint(p.lon, p.lat);
            if (ls.getNumPoints() == 1) ls.addPoint(piece[0].lon, piece[0].lat);
            ml.addGeometry(&ls);
        }
        tf.SetGeometry(&ml);
        put(tracks, tf);

        for (const auto& e : t.events) {
            OGRFeature ef(events.GetLayerDefn());
            const std::string label = event_label(e);
            ef.SetField("track", s.id.c_str());
            ef.SetField("name", s.name.c_str());
            ef.SetField("kind", audit::to_string(e.kind));
            ef.SetField("hit", coast::to_string(e.hit));
            finite_or_null(ef, "charted_depth_m", e.hit != coast::HazardKind::land ? e.charted_depth_m : NAN);
            ef.SetField("danger", coast::to_string(e.danger));
            ef.SetField("start", iso_time(e.start_s).c_str());
            ef.SetField("end", iso_time(e.end_s).c_str());
            ef.SetField("duration_s", e.end_s - e.start_s);
            finite_or_null(ef, "min_clearance_m", e.min_clearance_m);
            const bool contact = audit::is_contact(e.kind);
            if (contact) ef.SetField("penetration_m", e.penetration_m);
            else ef.SetFieldNull(ef.GetFieldIndex("penetration_m"));
            ef.SetField("ship_lat", e.ship.lat);
            ef.SetField("ship_lon", e.ship.lon);
            finite_or_null(ef, "heading", e.heading_deg);
            ef.SetField("heading_source", track::to_string(e.heading_source));
            ef.SetField("orientation", e.orientation_unknown ? "unknown (hull circle)" : "hull");
            finite_or_null(ef, "speed_kn", e.speed_kn);
            ef.SetField("speed_source", track::to_string(e.speed_source));
            if (contact) {
                ef.SetField("stopped_before", e.stopped_before ? 1 : 0);
                finite_or_null(ef, "stopped_after_s", e.stopped_after_s);
                finite_or_null(ef, "reference_inside_m", e.reference_inside_m);
            } else {
                for (const char* f : {"stopped_before", "stopped_after_s", "reference_inside_m"}) ef.SetFieldNull(ef.GetFieldIndex(f));
            }
            if (e.nav_status != track::nav_status_unknown) ef.SetField("nav_status", e.nav_status);
            else ef.SetFieldNull(ef.GetFieldIndex("nav_status"));
            ef.SetField("nav_status_text", track::nav_status_text(e.nav_status));
            ef.SetField("reported_aground", e.reported_aground ? 1 : 0);
            ef.SetField("unseen_after", e.unseen_after.c_str());
            ef.SetField("area", e.area_kind.c_str());
            ef.SetField("area_name", e.area_name.c_str());
            ef.SetField("structure", e.structure.c_str());
            ef.SetField("fix_index", static_cast<GIntBig>(e.fix_index));
            ef.SetField("fix_line", static_cast<GIntBig>(e.fix_line));
            ef.SetField("file", s.file.c_str());
            ef.SetField("hull", s.hull.c_str());
            ef.SetField("label", label.c_str());
            OGRPoint pt(e.point.lon, e.point.lat);
            ef.SetGeometry(&pt);
            put(events, ef);

            OGRFeature hf(hulls.GetLayerDefn());
            hf.SetField("track", s.id.c_str());
            hf.SetField("kind", audit::to_string(e.kind));
            hf.SetField("hit", coast::to_string(e.hit));
            hf.SetField("start", iso_time(e.start_s).c_str());
            hf.SetField("label", label.c_str());
            OGRLinearRing ring;
            for (const auto& p : e.hull) ring.addPoint(p.lon, p.lat);
            OGRPolygon poly;
            poly.addRing(&ring);
            hf.SetGeometry(&poly);
            put(hulls, hf);
        }
    }
    for (const auto& e : r.encounters.events) {
        const std::string a = r.tracks.at(e.a.track).summary.id, b = r.tracks.at(e.b.track).summary.id;
        const std::string label = std::string(e.kind == audit::EncounterKind::collision ? "collision " : "close quarters ") +
                                  iso_time(e.start_s).substr(11);
        OGRFeature f(encounters->GetLayerDefn());
        f.SetField("track", a.c_str());
        f.SetField("other_track", b.c_str());
        f.SetField("kind", audit::to_string(e.kind));
        f.SetField("start", iso_time(e.start_s).c_str());
        f.SetField("end", iso_time(e.end_s).c_str());
        f.SetField("duration_s", e.end_s - e.start_s);
        f.SetField("min_clearance_m", e.min_clearance_m);
        f.SetField("distance_m", e.distance_m);
        f.SetField("ship_lat", e.a.position.lat);
        f.SetField("ship_lon", e.a.position.lon);
        f.SetField("heading", e.a.heading_deg);
        f.SetField("other_lat", e.b.position.lat);
        f.SetField("other_lon", e.b.position.lon);
        f.SetField("other_heading", e.b.heading_deg);
        f.SetField("label", label.c_str());
        OGRPoint pt(e.point.lon, e.point.lat);
        f.SetGeometry(&pt);
        put(*encounters, f);
        for (const audit::ShipAt* ship : {&e.a, &e.b}) {
            OGRFeature hf(hulls.GetLayerDefn());
            hf.SetField("track", r.tracks.at(ship->track).summary.id.c_str());
            hf.SetField("kind", audit::to_string(e.kind));
            hf.SetField("start", iso_time(e.start_s).c_str());
            hf.SetField("label", label.c_str());
            OGRLinearRing ring;
            for (const auto& p : ship->hull) ring.addPoint(p.lon, p.lat);
            OGRPolygon poly;
            poly.addRing(&ring);
            hf.SetGeometry(&poly);
            put(hulls, hf);
        }
    }
    if (ds.CommitTransaction() != OGRERR_NONE) throw LibraryError("GeoPackage commit failed: " + std::string(CPLGetLastErrorMsg()));
}

}  // namespace

void write_gpkg(const std::string& path, const audit::AuditResult& result, const RunInfo& /*info*/) {
    GDALAllRegister();
    const fs::path target(path);
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw InputError("cannot write '" + path + "': folder '" + dir.string() + "' does not exist");
    if (fs::is_directory(target, ec)) throw InputError("cannot write '" + path + "': it is a directory");
    if (const auto st = fs::status(target, ec); fs::exists(st) && !fs::is_regular_file(st))
        throw InputError("cannot write '" + path + "': a GeoPackage must be a regular file (write it elsewhere, or use --format geojson)");
    std::random_device rd;
    std::string name(1, '.');  // appended, not "." + string: GCC 12 -O3 warns falsely (-Wrestrict) on that
    name += target.stem().string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(rd()) + ".gpkg";
    const fs::path tmp = dir / name;
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
    if (!drv) throw LibraryError("GDAL has no GPKG driver");
    // A fixed "current date" in the GeoPackage's metadata tables: the same run writes the
    // same bytes (whatever --jobs is).
    CPLSetThreadLocalConfigOption("OGR_CURRENT_DATE", "2000-01-01T00:00:00.000Z");
    const TempFileInProgress listed(tmp.string());  // removed (with SQLite's journal) if interrupted
    try {
        GDALDatasetUniquePtr ds(drv->Create(tmp.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        if (!ds) throw InputError("cannot write '" + path + "': " + CPLGetLastErrorMsg());
        write_layers(*ds, result);
        add_layer_styles(*ds);
        CPLErrorReset();
        ds.reset();  // GDALClose: flushes and closes the SQLite file
        if (CPLGetLastErrorType() == CE_Failure) throw InputError("cannot write '" + path + "': " + CPLGetLastErrorMsg());
    } catch (...) {
        fs::remove(tmp, ec);
        throw;
    }
    fs::rename(tmp, target, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw InputError("cannot write '" + path + "': " + ec.message());
    }
}

}  // namespace shoal::report
