// The GeoJSON and the GeoPackage report carry the same layers, fields and values: both are
// written from one result and read back independently (OGR for the features and layers,
// nlohmann::json for the GeoJSON's "shoal" member), then compared field by field. The GeoJSON
// matches its schema (Debian's python3-jsonschema), the schema and the user guide name every
// field of the report.

#include <gtest/gtest.h>

#include <ctime>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "report/geojson_output.hpp"
#include <shoal/report/report_fields.hpp>
#include "test_support.hpp"
#include <shoal/audit/audit.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/report/geojson_report.hpp>
#include <shoal/report/gpkg_report.hpp>

namespace shoal::report {
namespace {

using json = nlohmann::json;

/// SHOAL_TEST_DATA is SOURCE/tests/data/.
std::string source_root() { return std::filesystem::path(SHOAL_TEST_DATA).parent_path().parent_path().parent_path().string(); }

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::vector<geo::LonLat> ring_at(geo::LonLat c) {
    return {{c.lon - 1e-4, c.lat - 1e-4}, {c.lon + 1e-4, c.lat - 1e-4}, {c.lon + 1e-4, c.lat + 1e-4}, {c.lon - 1e-4, c.lat - 1e-4}};
}

/// A result with every kind of value the report holds: all event kinds, hazards and dangers,
/// unknown heading and speed, clearance beyond the search limit, an encounter, an approach,
/// every kind of problem; numbers with more decimals than the report keeps.
audit::AuditResult hand_result() {
    using audit::EventKind;
    audit::AuditResult r;
    const double t0 = 1714557600.123456;
    for (int k = 0; k < 2; ++k) {
        audit::TrackResult t;
        auto& s = t.summary;
        s.id = k == 0 ? "244123456" : "235000111";
        s.name = k == 0 ? "Nordic Star" : "";
        s.file = k == 0 ? "a.csv" : "b.csv";
        s.hull = k == 0 ? "--dims" : "AIS dimensions 10,5,2,2";
        s.fixes = 120 + static_cast<std::size_t>(k);
        s.uncovered_fixes = 3;
        s.segments = 2;
        s.gaps = 1;
        s.poses = 4567;
        s.jumps = 1;
        s.unknown_heading_fixes = 7;
        s.min_clearance_m = k == 0 ? 0.0 : INFINITY;
        s.distance_m = 12345.6789 + k;
        s.start_s = t0;
        s.end_s = t0 + 3600.5;
        s.lines = {{{-1.3, 50.7}, {-1.29876543, 50.70123456}}, {{-1.28, 50.71}}};
        if (k == 0) s.wild_fixes.push_back({17, t0 + 10, {-1.2, 50.8}, 999, "jump of 5.2 km in 10 s (1011 kn) and back"});
        const EventKind kinds[] = {EventKind::grounding, EventKind::close_pass, EventKind::expected_contact, EventKind::contact_at_start,
                                   EventKind::alongside};
        int i = 0;
        for (EventKind kind : kinds) {
            audit::Event e;
            e.kind = kind;
            e.start_s = t0 + 60.0 * i + 0.0004;
            e.end_s = e.start_s + 12.34567;
            e.min_clearance_m = kind == EventKind::close_pass ? 12.34567 : 0.0;
            e.penetration_m = 1.23456;
            e.point = {-1.312345678, 50.712345678 + 0.001 * i};
            e.ship = {-1.31234561, 50.71234561 + 0.001 * i};
            e.heading_deg = i == 1 ? NAN : 123.456;
            e.orientation_unknown = i == 1;
            e.heading_source = i == 1 ? track::HeadingSource::none : track::HeadingSource::cog;
            e.fix_index = static_cast<std::size_t>(10 + i);
            e.fix_line = static_cast<std::size_t>(12 + i);
            e.hull = ring_at(e.ship);
            e.hit = i == 0 ? coast::HazardKind::shallow : i == 2 ? coast::HazardKind::danger : coast::HazardKind::land;
            e.charted_depth_m = i == 0 ? 3.4567 : i == 2 ? NAN : 9.0;
            e.danger = i == 2 ? coast::DangerKind::wreck : coast::DangerKind::none;
            e.speed_kn = i == 1 ? NAN : 7.891;
            e.speed_source = i == 1 ? track::SpeedSource::none : track::SpeedSource::sog;
            e.stopped_before = i == 4;
            e.stopped_after_s = i == 0 ? 45.678 : NAN;
            e.reference_inside_m = -2.3456;
            e.nav_status = i == 0 ? std::uint8_t{0} : i == 4 ? std::uint8_t{5} : track::nav_status_unknown;
            e.reported_aground = i == 0;
            if (kind == EventKind::contact_at_start) e.unseen_after = "gap";
            if (kind == EventKind::expected_contact) {
                e.area_kind = "berth";
                e.area_name = "Pier 3";
                e.structure = "pier";
            }
            t.events.push_back(e);
            ++i;
        }
        s.groundings = 1;
        s.close_passes = 1;
        s.alongside = 1;
        s.contacts_at_start = 1;
        s.expected_contacts = 1;
        r.tracks.push_back(std::move(t));
    }
    r.files.push_back({"a.csv", "csv", {}, "", 1});
    r.files.back().read.skipped = 3;
    r.files.back().read.messages = {"a.csv line 5: latitude 91 out of range; row skipped"};
    r.files.push_back({"b.csv", "csv", {}, "", 1});
    r.files.push_back({"c.nmea", "nmea", {}, "'c.nmea': cannot be read", 0});
    r.errors.push_back({"b.csv", "235000999", "too few fixes"});
    r.fixes = 241;
    r.poses = 9134;
    r.skipped_rows = 3;
    r.uncovered_fixes = 6;
    r.groundings = r.close_passes = r.alongside = r.contacts_at_start = r.expected_contacts = 2;
    r.wild_fixes = 1;
    r.jumps = 2;
    r.unknown_heading_fixes = 14;
    r.first_fix_s = t0;
    r.last_fix_s = t0 + 3600.5;
    r.has_encounters = true;
    audit::Encounter enc;
    enc.kind = audit::EncounterKind::collision;
    enc.start_s = t0 + 100.25;
    enc.end_s = t0 + 130.125;
    enc.distance_m = 23.45678;
    enc.point = {-1.305555555, 50.705555555};
    enc.a = {0, {-1.3055, 50.7055}, 10.25, 4, ring_at({-1.3055, 50.7055})};
    enc.b = {1, {-1.3056, 50.7056}, 190.06, 5, ring_at({-1.3056, 50.7056})};
    r.encounters.events.push_back(enc);
    r.encounters.approaches.push_back({0, 1, t0 + 100.25, 0.0, 23.45678, {-1.3055, 50.7055}, {-1.3056, 50.7056}});
    r.collisions = 1;
    // Its COLREG situation: a crossing, the first ship giving way and altering course.
    audit::ColregEncounter c;
    c.a = 0;
    c.b = 1;
    c.start_s = t0 + 20.5;
    c.end_s = t0 + 400.25;
    c.at_start.situation = audit::Situation::crossing;
    c.at_start.give_way = audit::Party::a;
    c.at_start.stand_on = audit::Party::b;
    c.at_start.bearing_of_b_deg = 45.04;
    c.at_start.bearing_of_a_deg = 315.06;
    c.cpa_start = {12.345, 80.25};
    c.closest_m = 23.45678;
    c.closest_s = t0 + 100.25;
    c.action_a = {true, false, t0 + 60};
    r.situations.push_back(c);
    r.exercises = 1;
    for (auto& t : r.tracks) t.summary.exercise = "run";
    r.tracks.back().summary.role = audit::Role::target;
    return r;
}

RunInfo hand_info() {
    RunInfo info;
    info.coast = "coast.shp";
    info.frame = "transverse Mercator at -1.3";
    info.cell_m = 500;
    info.limiting_depth_m = 5.5;
    info.grid_fingerprint = "0123456789abcdef";
    info.ship = "--dims 50,10,5,5";
    info.berths = "berths.geojson";
    info.ship_margin_m = 20;
    return info;
}

/// What OGR read for one field, as JSON: null, or the value in the type of the GeoPackage's field.
json ogr_value(const OGRFeature& f, int i, const OGRFieldDefn& as) {
    if (!f.IsFieldSetAndNotNull(i)) return nullptr;
    switch (as.GetType()) {
        case OFTString: return f.GetFieldAsString(i);
        case OFTInteger64: return f.GetFieldAsInteger64(i);
        case OFTReal: return f.GetFieldAsDouble(i);
        case OFTInteger:
            if (as.GetSubType() == OFSTBoolean) return f.GetFieldAsInteger(i) != 0;
            return f.GetFieldAsInteger(i);
        case OFTDateTime: {
            // A UTC DateTime, as the ISO 8601 text the GeoJSON holds.
            int y, mo, d, h, mi, tz;
            float sec;
            f.GetFieldAsDateTime(i, &y, &mo, &d, &h, &mi, &sec, &tz);
            EXPECT_EQ(tz, 100) << as.GetNameRef() << " is not UTC";
            std::tm tm{};
            tm.tm_year = y - 1900, tm.tm_mon = mo - 1, tm.tm_mday = d, tm.tm_hour = h, tm.tm_min = mi;
            return iso_time(static_cast<double>(timegm(&tm)) + std::round(sec * 1000.0) / 1000.0);
        }
        default: ADD_FAILURE() << "unexpected field type of " << as.GetNameRef(); return nullptr;
    }
}

json json_as(const json& v, const OGRFieldDefn& as) {
    if (v.is_null()) return nullptr;
    if (as.GetType() == OFTReal) return v.get<double>();
    return v;
}

/// Every field of GeoPackage feature `g` equals the same field of the JSON object `j`, and
/// `j` has no other keys except (when `omitted_null`) fields null in `g`.
void expect_same(const OGRFeature& g, const json& j, const std::string& where, bool omitted_null = false) {
    const OGRFeatureDefn& d = *g.GetDefnRef();
    std::set<std::string> keys;
    for (const auto& [k, v] : j.items()) keys.insert(k);
    for (int i = 0; i < d.GetFieldCount(); ++i) {
        const OGRFieldDefn& fd = *d.GetFieldDefn(i);
        const std::string name = fd.GetNameRef();
        const json gv = ogr_value(g, i, fd);
        if (omitted_null && gv.is_null()) {
            EXPECT_FALSE(j.contains(name)) << where << "." << name;
            continue;
        }
        ASSERT_TRUE(j.contains(name)) << where << ": the GeoJSON lacks " << name;
        EXPECT_EQ(json_as(j[name], fd), gv) << where << "." << name;
        keys.erase(name);
    }
    EXPECT_TRUE(keys.empty()) << where << ": the GeoPackage lacks " << (keys.empty() ? "" : *keys.begin());
}

struct Reports {
    test::TempDir dir;
    audit::AuditResult result = hand_result();
    RunInfo info = hand_info();
    std::string geojson_path = dir.file("r.geojson"), gpkg_path = dir.file("r.gpkg");
    GDALDatasetUniquePtr gj, gp;
    json doc;
    Reports() {
        write_geojson(geojson_path, result, info);
        write_gpkg(gpkg_path, result, info);
        GDALAllRegister();
        const char* only_gj[] = {"GeoJSON", nullptr};
        const char* only_gp[] = {"GPKG", nullptr};
        const char* list_contents[] = {"LIST_ALL_TABLES=NO", nullptr};
        const char* as_written[] = {"DATE_AS_STRING=YES", nullptr};  // times compared as the text written
        gj.reset(GDALDataset::Open(geojson_path.c_str(), GDAL_OF_VECTOR, only_gj, as_written));
        gp.reset(GDALDataset::Open(gpkg_path.c_str(), GDAL_OF_VECTOR, only_gp, list_contents));
        doc = json::parse(slurp(geojson_path));
    }
    std::vector<OGRFeatureUniquePtr> features(GDALDataset& ds, const char* layer) {
        std::vector<OGRFeatureUniquePtr> out;
        OGRLayer* l = ds.GetLayerByName(layer);
        if (!l) {
            ADD_FAILURE() << "no layer " << layer;
            return out;
        }
        l->ResetReading();
        while (OGRFeature* f = l->GetNextFeature()) out.emplace_back(f);
        return out;
    }
};

TEST(ReportFields, GeoJsonAndGeoPackageHoldTheSameLayersFieldsAndValues) {
    Reports rep;
    ASSERT_TRUE(rep.gj && rep.gp);
    std::set<std::string> layers;
    for (int i = 0; i < rep.gp->GetLayerCount(); ++i) layers.insert(rep.gp->GetLayer(i)->GetName());
    EXPECT_EQ(layers, (std::set<std::string>{"events", "encounters", "tracks", "hulls", "poses", "problems", "closest_approaches", "run",
                                           "summary", "layer_styles"}));

    // Features: the GeoJSON's Point features are the GeoPackage's events, then its encounters.
    const auto gj_features = rep.features(*rep.gj, rep.gj->GetLayer(0)->GetName());
    const auto events = rep.features(*rep.gp, "events"), encounters = rep.features(*rep.gp, "encounters");
    ASSERT_EQ(events.size(), 10u);
    ASSERT_EQ(encounters.size(), 1u);
    ASSERT_EQ(gj_features.size(), events.size() + encounters.size());
    for (std::size_t k = 0; k < gj_features.size(); ++k) {
        const OGRFeature& a = *gj_features[k];
        const OGRFeature& b = k < events.size() ? *events[k] : *encounters[k - events.size()];
        const std::string where = "feature " + std::to_string(k);
        std::set<std::string> set_in_geojson, in_gpkg;
        for (int i = 0; i < a.GetFieldCount(); ++i)
            if (a.IsFieldSet(i)) set_in_geojson.insert(a.GetFieldDefnRef(i)->GetNameRef());
        for (int i = 0; i < b.GetFieldCount(); ++i) {
            const OGRFieldDefn& fd = *b.GetFieldDefnRef(i);
            in_gpkg.insert(fd.GetNameRef());
            const int ai = a.GetFieldIndex(fd.GetNameRef());
            ASSERT_GE(ai, 0) << where << ": the GeoJSON lacks " << fd.GetNameRef();
            EXPECT_EQ(ogr_value(a, ai, fd), ogr_value(b, i, fd)) << where << "." << fd.GetNameRef();
        }
        EXPECT_EQ(set_in_geojson, in_gpkg) << where;
        const auto* pa = a.GetGeometryRef()->toPoint();
        const auto* pb = b.GetGeometryRef()->toPoint();
        EXPECT_EQ(pa->getX(), pb->getX()) << where;
        EXPECT_EQ(pa->getY(), pb->getY()) << where;
    }

    // The other layers: members of "shoal" in the GeoJSON.
    const json& shoal = rep.doc["shoal"];
    const auto compare_rows = [&](const char* layer, const json& rows, bool omitted_null = false) {
        const auto fs = rep.features(*rep.gp, layer);
        ASSERT_EQ(fs.size(), rows.size()) << layer;
        for (std::size_t k = 0; k < fs.size(); ++k) expect_same(*fs[k], rows[k], std::string(layer) + "[" + std::to_string(k) + "]", omitted_null);
    };
    compare_rows("tracks", shoal["tracks"]);
    compare_rows("problems", shoal["problems"], true);
    compare_rows("closest_approaches", shoal["closest_approaches"]);
    compare_rows("summary", json::array({shoal["summary"]}));
    json run = shoal;
    for (const char* member : {"tracks", "problems", "closest_approaches", "summary"}) run.erase(member);
    compare_rows("run", json::array({run}));
    EXPECT_EQ(shoal["problems"].size(), 4u);

    // Hulls (GeoPackage only): one per event, two per encounter.
    EXPECT_EQ(rep.features(*rep.gp, "hulls").size(), events.size() + 2 * encounters.size());
}

/// The report is written piece by piece (not built as one document): it must still be exactly
/// what nlohmann's dump(1) of the whole document makes, its indentation, separators and empty
/// arrays included. Reading it back and dumping the document again is that answer.
TEST(ReportFields, TheStreamedGeoJsonIsTheDocumentsDump) {
    audit::AuditResult full = hand_result();
    const RunInfo info = hand_info();
    const std::string text = geojson(full, info);
    EXPECT_EQ(nlohmann::ordered_json::parse(text).dump(1) + "\n", text);
    // Text that must be escaped, in the header's rows and in the features (written as text,
    // not as JSON values): quotes, backslashes, control characters, UTF-8.
    audit::AuditResult odd = hand_result();
    ASSERT_FALSE(odd.tracks.empty());
    ASSERT_FALSE(odd.tracks.front().events.empty());
    odd.tracks.front().summary.name = "Tug \"\xc3\x84\"\n\t\\ \x01 \xe2\x98\x83 /";
    odd.tracks.front().summary.id = "id \x7f \"q\"";
    for (auto& e : odd.tracks.front().events) {
        e.hit_name = "Pier \"A\"\r\n\xe2\x82\xac";
        e.area_name = "\\\\server";
    }
    const std::string escaped = geojson(odd, info);
    EXPECT_EQ(nlohmann::ordered_json::parse(escaped).dump(1) + "\n", escaped);
    EXPECT_NE(escaped.find("Pier \\\"A\\\"\\r\\n\xe2\x82\xac"), std::string::npos);
    // The same with nothing to list: empty arrays are written [] as dump writes them.
    audit::AuditResult empty;
    const std::string none = geojson(empty, info);
    EXPECT_EQ(nlohmann::ordered_json::parse(none).dump(1) + "\n", none);
    EXPECT_NE(none.find("\"features\": []"), std::string::npos);
    // Many events: more than one piece of a mebibyte, the file the same as the text.
    audit::AuditResult many = hand_result();
    for (int k = 0; k < 12; ++k) many.tracks.push_back(many.tracks.front());
    for (auto& t : many.tracks) {
        const std::vector<audit::Event> one = t.events;
        for (int k = 0; k < 100; ++k) t.events.insert(t.events.end(), one.begin(), one.end());
    }
    const std::string big = geojson(many, info);
    ASSERT_GT(big.size(), std::size_t{3} << 19) << "more than one piece of a mebibyte";
    EXPECT_EQ(nlohmann::ordered_json::parse(big).dump(1) + "\n", big);
    // The features are made a block of 512 at a time on threads: any number writes the same,
    // the events in their order (each told apart here by its start).
    std::vector<std::string> order;
    for (auto& t : many.tracks)
        for (auto& e : t.events) {
            e.start_s = 1.7e9 + static_cast<double>(order.size());
            e.end_s = e.start_s + 10;
            order.push_back(iso_time(e.start_s));
        }
    ASSERT_GT(order.size(), 3u * 512u) << "several blocks";
    const std::string told = geojson(many, info);
    const auto doc = nlohmann::ordered_json::parse(told);
    ASSERT_GE(doc["features"].size(), order.size()) << "the events first, then the encounters'";
    for (std::size_t k = 0; k < order.size(); ++k) ASSERT_EQ(doc["features"][k]["properties"]["start"], order[k]) << k;
    for (const unsigned jobs : {1u, 3u}) {
        RunInfo on = info;
        on.jobs = jobs;
        EXPECT_TRUE(geojson(many, on) == told) << jobs << " threads";
    }
    test::TempDir dir;
    write_geojson(dir.file("big.geojson"), many, info);
    EXPECT_TRUE(slurp(dir.file("big.geojson")) == told) << "the file is the text";
}

/// The layer files' coordinates: glibc's printf "%.7f" (an independent formatter) with its
/// trailing zeros dropped, one kept after the point; the text reads back as printf's rounding.
TEST(ReportFields, LayerCoordinatesAreWhatPrintfWritesWithoutTrailingZeros) {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> lon(-180, 180), small(-1e-6, 1e-6);
    std::vector<double> values{0.0, -0.0, 1e-9, -1e-9, 5e-8, -5e-8, 1.5e-7, 179.99999995, -179.99999995, 24.0, 60.5, 24.525563, 1e300, -1e300};
    for (int i = 0; i < 200000; ++i) values.push_back(lon(rng));
    for (int i = 0; i < 20000; ++i) values.push_back(small(rng));
    for (int i = 0; i < 20000; ++i) values.push_back(std::round(lon(rng) * 1e7) / 1e7);  // decimals of 7 digits, as read
    for (int i = 0; i < 20000; ++i) values.push_back((std::floor(lon(rng) * 1e7) + 0.5) / 1e7);  // halfway, near enough
    for (int j = -46080; j < 46080; j += 7) values.push_back((2 * j + 1) / 256.0);  // exactly halfway: ties to even, as printf
    for (double big : {3.99999999e8, 4e8, 4.00000001e8, 123456789.12345675, 1e9 + 0.00000005, -7e8})
        values.push_back(big);  // either side of the fast path's limit
    std::size_t shortened = 0;
    for (const double v : values) {
        char buf[512];
        std::snprintf(buf, sizeof buf, "%.7f", v);
        std::string expected = buf;
        while (expected.back() == '0') expected.pop_back();
        if (expected.back() == '.') expected += '0';
        shortened += expected.size() < std::strlen(buf);
        std::string got;
        append_coordinate(got, v);
        ASSERT_EQ(got, expected) << "the double " << v;
        EXPECT_EQ(std::strtod(got.c_str(), nullptr), std::strtod(buf, nullptr)) << got;
    }
    EXPECT_GT(shortened, 20000u);
    std::string nan;
    append_coordinate(nan, NAN);
    append_coordinate(nan, INFINITY);
    EXPECT_EQ(nan, "nullnull");
}

/// round_to's powers of ten are pow's, and it rounds as with them: every decimals a field
/// may ask for, on random values.
TEST(ReportFields, RoundingTakesPowersOfTenExactly) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (int d = -3; d <= 25; ++d) {
        const volatile double exponent = d;  // pow at run time, not folded by the compiler
        const double k = std::pow(10.0, exponent);
        for (int i = 0; i < 2000; ++i) {
            const double v = unit(rng) * std::pow(10.0, i % 12 - 4);
            ASSERT_EQ(fields::round_to(v, d), std::round(v * k) / k) << v << " to " << d << " decimals";
        }
    }
}

/// The positions a PositionWriter puts are those append_coordinate writes one number at a
/// time, with the text between them, over many of its buffers' flushes: ordinary, huge, not
/// finite and negative-zero coordinates, after text already in the string.
TEST(ReportFields, PositionsWrittenTogetherAreEachCoordinateAppended) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> unit(0, 1);
    auto coordinate = [&]() -> double {
        const double u = unit(rng);
        if (u < 0.01) return NAN;
        if (u < 0.02) return -INFINITY;
        if (u < 0.03) return -0.0;
        if (u < 0.05) return (unit(rng) - 0.5) * 1e12;  // beyond the fast path
        if (u < 0.06) return (unit(rng) < 0.5 ? -1 : 1) * (4e8 - unit(rng));
        return 360 * (unit(rng) - 0.5);
    };
    for (int trial = 0; trial < 200; ++trial) {
        std::string got = "head", expected = "head";
        {
            PositionWriter w(got);
            const int n = static_cast<int>(2000 * unit(rng));
            for (int i = 0; i < n; ++i) {
                const geo::LonLat p{coordinate(), coordinate()};
                const char before = "\0,[]"[static_cast<int>(4 * unit(rng))];
                if (unit(rng) < 0.2) {
                    w.put(before);
                    expected += before;
                    continue;
                }
                w.put(before, p);
                if (before) expected += before;
                expected += '[';
                append_coordinate(expected, p.lon);
                expected += ',';
                append_coordinate(expected, p.lat);
                expected += ']';
            }
            w.flush();
        }
        ASSERT_EQ(got, expected) << "trial " << trial;
    }
}

/// The map's label of an event says its kind: a contact is never labelled as a close pass
/// (chart_disagrees was, "close 22:58:03.307Z"), and each kind has its own words.
TEST(ReportFields, EveryEventKindHasItsOwnLabel) {
    using audit::EventKind;
    std::set<std::string> words;
    for (const EventKind k : {EventKind::grounding, EventKind::alongside, EventKind::contact_at_start, EventKind::expected_contact,
                              EventKind::close_pass, EventKind::chart_disagrees}) {
        audit::Event e;
        e.kind = k;
        e.start_s = 1.7e9 + 3.307;
        e.hit = coast::HazardKind::land;
        const std::string label = event_label(e);
        const std::string head = label.substr(0, label.size() - std::string("22:13:23.307Z").size());
        EXPECT_EQ(label.substr(head.size()), "22:13:23.307Z") << label;
        EXPECT_TRUE(words.insert(head).second) << audit::to_string(k) << ": " << label;
        EXPECT_EQ(audit::is_contact(k), head != "close ") << audit::to_string(k) << ": " << label;
    }
}

/// A table names each field once: the layer files' writer appends every field it lists (a
/// JSON object would keep one of two fields of the same name), and a GeoPackage layer has one
/// column a name. Each name is plain printable ASCII.
TEST(ReportFields, EveryTableNamesEachFieldOnce) {
    auto check = [](const auto& table, const char* what) {
        std::set<std::string> seen;
        for (const auto& f : table) {
            EXPECT_TRUE(seen.insert(f.name).second) << what << ": " << f.name << " twice";
            for (const char c : std::string(f.name)) EXPECT_TRUE(c > 0x20 && c < 0x7f && c != '"' && c != '\\') << what << ": " << f.name;
        }
        EXPECT_FALSE(seen.empty()) << what;
    };
    check(fields::event_fields(), "events");
    check(fields::encounter_fields(), "encounters");
    check(fields::track_fields(), "tracks");
    check(fields::hull_fields(), "hulls");
    check(fields::problem_fields(), "problems");
    check(fields::pose_fields(), "poses");
    check(fields::coast_fields(), "coast");
    check(fields::approach_fields(), "approaches");
    check(fields::run_fields(), "run");
    check(fields::summary_fields(), "summary");
    check(fields::breach_fields(), "breaches");
    check(fields::learned_fields(), "learned");
    check(fields::score_fields(), "scores");
    check(fields::criterion_fields(), "criteria");
}

/// The layer files' properties, written without building a JSON object, are what nlohmann's
/// dump() writes of the object of the same fields: random poses and names (quotes, control
/// characters, UTF-8; numbers not finite, negative zero, huge, tiny, random bits).
TEST(ReportFields, LayerPropertiesAreWhatNlohmannWritesOfTheFields) {
    std::mt19937_64 rng(11);
    const std::vector<std::string> pieces{"a", "Z", "9", " ", "\"", "\\", "/", "\n", "\t", "\x01", "\x1f", "\x7f", "\xc3\xa9", "\xe2\x82\xac", "\xf0\x9f\x9a\xa2"};
    auto text = [&] {
        std::string t;
        for (std::size_t k = rng() % 12; k > 0; --k) t += pieces[rng() % (k % 3 == 0 ? pieces.size() : 4)];
        return t;
    };
    auto number = [&] {
        switch (rng() % 8) {
            case 0: return std::vector<double>{NAN, INFINITY, -INFINITY, -0.0, 0.0, 1e300, 1e-300, 5e-324}[rng() % 8];
            case 1: { double d; const std::uint64_t bits = rng(); std::memcpy(&d, &bits, sizeof d); return d; }
            case 2: return std::uniform_real_distribution<double>(-1e6, 1e6)(rng);
            default: return std::uniform_real_distribution<double>(0, 400)(rng);
        }
    };
    const audit::AuditResult r;
    // The oracle: the row's fields in a JSON object, dumped by nlohmann.
    auto nlohmann_dump = [&](const auto& table, const auto& row) {
        nlohmann::ordered_json o = nlohmann::ordered_json::object();
        for (const auto& f : table)
            if (!f.present || f.present(r))  // exercise-mode fields only in exercise mode
            std::visit([&](const auto& x) {
                if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::monostate>) o[f.name] = nullptr;
                else o[f.name] = x;
            }, fields::value_of(f, row));
        return o.dump();
    };
    auto written = [&](const auto& table, const auto& row) {
        std::string out;
        append_object(out, table, row, r);
        return out;
    };
    for (int i = 0; i < 20000; ++i) {
        audit::TrackSummary t;
        t.id = text();
        t.name = text();
        audit::Pose p;
        p.time_s = 1.7e9 + number();
        p.until_s = number();
        p.speed_kn = number();
        p.heading_deg = number();
        p.clearance_m = number();
        p.contact = rng() % 2;
        p.covered = rng() % 2;
        p.fix_index = rng() % 1000000;
        p.fix_line = rng();
        const fields::PoseRow row{t, p};
        ASSERT_EQ(written(fields::pose_fields(), row), nlohmann_dump(fields::pose_fields(), row)) << i;
        const fields::CoastRow coast{text(), "land", "", number()};
        ASSERT_EQ(written(fields::coast_fields(), coast), nlohmann_dump(fields::coast_fields(), coast)) << i;
    }
    // Not UTF-8 (a Latin-1 byte of an input quoted by a message, a field cut inside a
    // character): U+FFFD, as nlohmann's dump() replaces it (before: its error, which ended the
    // run with an internal error and no report).
    audit::TrackSummary bad;
    bad.id = "MMSI \xff";
    std::string got;
    append_object(got, fields::pose_fields(), fields::PoseRow{bad, audit::Pose{}}, r);
    EXPECT_NE(got.find("\"track\":\"MMSI \xef\xbf\xbd\""), std::string::npos) << got;
}

TEST(ReportFields, ValuesAreRoundedAsTheTableSaysAndNotFiniteIsNull) {
    Reports rep;
    const json& p = rep.doc["features"][0]["properties"];
    EXPECT_EQ(p["charted_depth_m"], 3.46);
    EXPECT_EQ(p["duration_s"], 12.346);
    EXPECT_EQ(p["heading"], 123.5);
    EXPECT_EQ(p["stopped_after_s"], 45.7);
    EXPECT_EQ(p["ship_lat"], 50.7123456);
    const json& unknown = rep.doc["features"][1]["properties"];
    EXPECT_TRUE(unknown["heading"].is_null());
    EXPECT_TRUE(unknown["speed_kn"].is_null());
    EXPECT_TRUE(unknown["penetration_m"].is_null());  // a close pass
    EXPECT_TRUE(rep.doc["shoal"]["tracks"][1]["min_clearance_m"].is_null());
    EXPECT_EQ(rep.doc["shoal"]["tracks"][0]["distance_m"], 12345.7);
    const auto tracks = rep.features(*rep.gp, "tracks");
    EXPECT_EQ(tracks[0]->GetFieldAsDouble("distance_m"), 12345.7);
}

TEST(ReportFields, TheGeoJsonMatchesItsSchemaAndTheSchemaListsEveryField) {
    Reports rep;
    const std::string schema_path = source_root() + "/schemas/report.schema.json";
    const std::string cmd = "/usr/bin/python3 -c \"import json,sys,jsonschema; "
                            "jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))\" '" +
                            rep.geojson_path + "' '" + schema_path + "' 2>&1";
    FILE* pipe = ::popen(cmd.c_str(), "r");
    ASSERT_TRUE(pipe);
    std::string out;
    char buf[512];
    while (std::fgets(buf, sizeof buf, pipe)) out += buf;
    EXPECT_EQ(::pclose(pipe), 0) << out;

    const json schema = json::parse(slurp(schema_path));
    const json& shoal = schema["properties"]["shoal"]["properties"];
    const auto listed = [](const json& props, const auto& table, const std::string& where) {
        for (const auto& f : table) EXPECT_TRUE(props.contains(f.name)) << where << " lacks " << f.name;
    };
    const json& feature = schema["properties"]["features"]["items"]["properties"]["properties"]["properties"];
    listed(feature, fields::event_fields(), "features");
    listed(feature, fields::encounter_fields(), "features");
    listed(feature, fields::breach_fields(), "features");
    listed(shoal["assessment"]["properties"]["scores"]["items"]["properties"], fields::score_fields(), "assessment.scores");
    listed(shoal["assessment"]["properties"]["criteria"]["items"]["properties"], fields::criterion_fields(), "assessment.criteria");
    listed(shoal["tracks"]["items"]["properties"], fields::track_fields(), "tracks");
    listed(shoal["problems"]["items"]["properties"], fields::problem_fields(), "problems");
    listed(shoal["closest_approaches"]["items"]["properties"], fields::approach_fields(), "closest_approaches");
    listed(shoal["summary"]["properties"], fields::summary_fields(), "summary");
    listed(shoal, fields::run_fields(), "shoal");
}

TEST(ReportFields, TheUserGuideNamesEveryField) {
    const std::string guide = slurp(source_root() + "/docs/user-guide.md");
    const std::size_t from = guide.find("## The report"), to = guide.find("\n## ", from + 1);
    ASSERT_NE(from, std::string::npos);
    const std::string section = guide.substr(from, to - from);
    const auto named = [&](const auto& table, const char* layer) {
        for (const auto& f : table)
            EXPECT_NE(section.find("`" + std::string(f.name) + "`"), std::string::npos) << layer << "." << f.name << " is not in the user guide";
    };
    named(fields::event_fields(), "events");
    named(fields::encounter_fields(), "encounters");
    named(fields::track_fields(), "tracks");
    named(fields::hull_fields(), "hulls");
    named(fields::problem_fields(), "problems");
    named(fields::approach_fields(), "closest_approaches");
    named(fields::run_fields(), "run");
    named(fields::summary_fields(), "summary");
    named(fields::pose_fields(), "poses");
    named(fields::coast_fields(), "coast");
    named(fields::breach_fields(), "breaches");
    named(fields::score_fields(), "scores");
    named(fields::criterion_fields(), "criteria");
    named(fields::learned_fields(), "learned");
}

}  // namespace
}  // namespace shoal::report
