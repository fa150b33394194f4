// Tests of track::read_gpx and track::read_geojson on hand-made files in tests/data/tracks.
//
// The GPX files were checked independently with GDAL's own tool: `ogrinfo -q FILE track_points`
// (and route_points) lists each point with its time (one track point without a time, one with
// +02 offset; GPX 1.0 course 80.5 and speed 2.572 m/s). Every GeoJSON value asserted below can
// be read in the file itself. Epoch seconds: date -u -d '2014-08-15T19:00:00Z' +%s -> 1408129200.

#include <shoal/track/ogr_reader.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "test_support.hpp"
#include <shoal/util/error.hpp>

namespace {

using shoal::InputError;
using shoal::test::data_path;
using namespace shoal::track;
using testing::AllOf;
using testing::ElementsAre;
using testing::HasSubstr;
using testing::ThrowsMessage;

constexpr double t0 = 1408129200.0;  // 2014-08-15T19:00:00Z

std::vector<double> times(const Track& t) {
    std::vector<double> out;
    for (const auto& f : t.fixes) out.push_back(f.time_s - t0);
    return out;
}

TEST(GpxReader, ReadsTracksAndRoutesWithTheirNames) {
    const std::string path = data_path("tracks/track_and_route.gpx");
    const auto f = read_gpx(path);
    EXPECT_EQ(f.format, "gpx");
    EXPECT_EQ(f.report.rows, 8u);  // 5 track points + 3 route points
    EXPECT_EQ(f.report.skipped, 1u);
    ASSERT_EQ(f.tracks.size(), 2u);
    const Track& trk = f.tracks[0];
    EXPECT_EQ(trk.id, "Trainee A");
    // Two segments joined; the +02:00 point is 19:00:20 UTC; the untimed 4th point is skipped.
    EXPECT_THAT(times(trk), ElementsAre(0.0, 10.5, 20.0, 40.0));
    EXPECT_DOUBLE_EQ(trk.fixes[3].position.lon, 24.904);
    EXPECT_DOUBLE_EQ(trk.fixes[3].position.lat, 60.15);
    EXPECT_EQ(trk.fixes[3].line, 5u);
    const Track& rte = f.tracks[1];
    EXPECT_EQ(rte.id, "Plan B");
    EXPECT_THAT(times(rte), ElementsAre(-3600.0, -3000.0, -2400.0));
    EXPECT_EQ(rte.fixes[0].line, 6u);
    ASSERT_EQ(f.report.messages.size(), 1u);
    EXPECT_EQ(f.report.messages[0], path + " point 4 (track 'Trainee A'): no time; point skipped");
}

TEST(GpxReader, UnnamedSingleTrackTakesTheStemAndGpx10CourseAndSpeed) {
    const auto f = read_gpx(data_path("tracks/unnamed_track.gpx"));
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "unnamed_track");
    ASSERT_EQ(f.tracks[0].fixes.size(), 2u);
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[0].cog_deg, 80.5);
    EXPECT_NEAR(f.tracks[0].fixes[0].sog_kn, 2.572 * 3600.0 / 1852.0, 1e-12);  // m/s -> knots
    EXPECT_TRUE(std::isnan(f.tracks[0].fixes[1].sog_kn));
}

TEST(GpxReader, RouteWithoutTimesIsAnErrorNamingFileAndRoute) {
    EXPECT_THAT([] { read_gpx(data_path("tracks/route_without_times.gpx")); },
                ThrowsMessage<InputError>(AllOf(HasSubstr("route_without_times.gpx: route 'Planned passage' (route 1)"),
                                                HasSubstr("has no times"))));
}

TEST(GpxReader, NotGpxIsAnInputError) {
    EXPECT_THAT([] { read_gpx(data_path("tracks/unknown_format.txt")); },
                ThrowsMessage<InputError>(HasSubstr("unknown_format.txt: not a GPX file")));
}

TEST(GeoJsonReader, LineStringWithTimesArray) {
    const std::string path = data_path("tracks/line_times.geojson");
    const auto f = read_geojson(path);
    EXPECT_EQ(f.format, "geojson");
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "Aava");
    EXPECT_EQ(f.tracks[0].name, "Aava");
    EXPECT_THAT(times(f.tracks[0]), ElementsAre(0.0, 10.0, 20.25, 40.0));
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[3].position.lon, 24.94);
    EXPECT_EQ(f.report.rows, 5u);
    EXPECT_EQ(f.report.skipped, 1u);
    ASSERT_EQ(f.report.messages.size(), 1u);
    EXPECT_EQ(f.report.messages[0], path + " feature 1 vertex 4: times \"not a time\" is not a valid time; point skipped");
}

TEST(GeoJsonReader, MultiLineStringWithCoordinatePropertiesAndMillisecondCoordTimes) {
    const auto f = read_geojson(data_path("tracks/line_coordinate_properties.geojson"));
    ASSERT_EQ(f.tracks.size(), 2u);
    EXPECT_EQ(f.tracks[0].id, "244000001");  // the feature's id
    EXPECT_THAT(times(f.tracks[0]), ElementsAre(0.0, 10.0, 20.0, 30.0));
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[2].position.lon, 5.32);
    EXPECT_EQ(f.tracks[1].id, "244000002");  // the mmsi property, a number
    EXPECT_THAT(times(f.tracks[1]), ElementsAre(0.0, 10.0));
}

TEST(GeoJsonReader, LineStringWithMeasureCoordinates) {
    const auto f = read_geojson(data_path("tracks/line_m.geojson"));
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "M-ship");
    EXPECT_THAT(times(f.tracks[0]), ElementsAre(0.0, 10.0, 20.5));
}

TEST(GeoJsonReader, PointsAreSplitByMmsiInFirstAppearanceOrder) {
    // points.geojson: 230000002 at 19:00:00 (sog 6.5, cog 45, heading 511) and 19:00:10;
    // 230000001 at 19:00:05 (heading 270), one point without time, a numeric timestamp
    // 1408129215, and a Polygon feature.
    const auto f = read_geojson(data_path("tracks/points.geojson"));
    EXPECT_EQ(f.report.rows, 6u);
    EXPECT_EQ(f.report.skipped, 2u);
    ASSERT_EQ(f.tracks.size(), 2u);
    EXPECT_EQ(f.tracks[0].id, "230000002");
    EXPECT_EQ(f.tracks[1].id, "230000001");
    EXPECT_THAT(times(f.tracks[0]), ElementsAre(0.0, 10.0));
    EXPECT_THAT(times(f.tracks[1]), ElementsAre(5.0, 15.0));
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[0].sog_kn, 6.5);
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[0].cog_deg, 45.0);
    EXPECT_TRUE(std::isnan(f.tracks[0].fixes[0].heading_deg));
    EXPECT_DOUBLE_EQ(f.tracks[1].fixes[0].heading_deg, 270.0);
    EXPECT_THAT(f.report.messages.at(0), HasSubstr("feature 4: Point without a 'time' or 'timestamp' property"));
    EXPECT_THAT(f.report.messages.at(1), HasSubstr("feature 6: a Polygon is not a track"));
}

TEST(GeoJsonReader, PointFeatureIdsDoNotSplitTracks) {
    const auto f = read_geojson_text(R"({"type": "FeatureCollection", "features": [
        {"type": "Feature", "id": 1, "properties": {"time": "2014-08-15T19:00:00Z"}, "geometry": {"type": "Point", "coordinates": [24.9, 60.1]}},
        {"type": "Feature", "id": 2, "properties": {"time": "2014-08-15T19:00:10Z"}, "geometry": {"type": "Point", "coordinates": [24.91, 60.1]}}]})",
                                     "/x/trainee-7.geojson");
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "trainee-7");
    EXPECT_THAT(times(f.tracks[0]), ElementsAre(0.0, 10.0));
}

TEST(GeoJsonReader, ALineThatCannotBeReadCostsThatFeatureNamedAndNotTheFile) {
    const auto a = read_geojson(data_path("tracks/line_without_times.geojson"));
    EXPECT_TRUE(a.tracks.empty());
    EXPECT_EQ(a.report.skipped, 1u);
    EXPECT_THAT(a.report.messages, ElementsAre(AllOf(HasSubstr("line_without_times.geojson feature 1 ('no clock')"),
                                                     HasSubstr("line without times"), HasSubstr("feature skipped"))));
    const auto b = read_geojson(data_path("tracks/line_times_mismatch.geojson"));
    EXPECT_THAT(b.report.messages, ElementsAre(HasSubstr("feature 1: 'times' has 1 times for 2 vertices; feature skipped")));
    // Before, one such line cost every track of its file.
    const auto c = read_geojson_text(R"({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"id": "ok", "times": ["2014-08-15T19:00:00Z", "2014-08-15T19:00:10Z"]}, "geometry": {"type": "LineString", "coordinates": [[24.9, 60.1], [24.91, 60.1]]}},
        {"type": "Feature", "properties": {"id": "short", "times": ["2014-08-15T19:00:00Z"]}, "geometry": {"type": "LineString", "coordinates": [[24.9, 60.1], [24.91, 60.1]]}},
        {"type": "Feature", "properties": {"id": "none"}, "geometry": {"type": "LineString", "coordinates": [[24.9, 60.1], [24.91, 60.1]]}},
        {"type": "Feature", "properties": {"id": "ok2", "times": ["2014-08-15T19:00:00Z", "2014-08-15T19:00:10Z"]}, "geometry": {"type": "LineString", "coordinates": [[24.9, 60.2], [24.91, 60.2]]}}]})",
                                     "three.geojson");
    ASSERT_EQ(c.tracks.size(), 2u);
    EXPECT_EQ(c.tracks[0].id, "ok");
    EXPECT_EQ(c.tracks[1].id, "ok2");
    EXPECT_EQ(c.tracks[1].fixes.size(), 2u);
    EXPECT_EQ(c.report.skipped, 2u);
    EXPECT_THAT(c.report.messages, ElementsAre(HasSubstr("three.geojson feature 2: 'times' has 1 times for 2 vertices; feature skipped"),
                                               HasSubstr("three.geojson feature 3 ('none'): line without times")));
}

TEST(GeoJsonReader, RejectsBrokenJsonOtherJsonAndOtherCrs) {
    EXPECT_THAT([] { read_geojson_text("{\"type\": \"FeatureCollection\", ", "cut.geojson"); },
                ThrowsMessage<InputError>(HasSubstr("cut.geojson: not valid JSON")));
    // A number too large for a double (nlohmann's out_of_range, not a parse_error) is bad input too.
    EXPECT_THAT([] { read_geojson_text(R"({"type": "FeatureCollection", "features": [], "x": 1e999})", "huge.geojson"); },
                ThrowsMessage<InputError>(HasSubstr("huge.geojson: not valid JSON")));
    EXPECT_THAT([] { read_geojson_text(R"({"name": "tanker", "a": 100})", "ship.json"); },
                ThrowsMessage<InputError>(HasSubstr("ship.json: not a track format shoal reads")));
    EXPECT_THAT(
        [] {
            read_geojson_text(R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "EPSG:3067"}},
                                  "features": []})",
                              "tm35.geojson");
        },
        ThrowsMessage<InputError>(HasSubstr("tm35.geojson: crs 'EPSG:3067' is not WGS84")));
    EXPECT_THAT([] { read_geojson_text(R"({"type": "LineString", "coordinates": [[0, 0], [1, 1]]})", "bare.geojson"); },
                ThrowsMessage<InputError>(HasSubstr("bare.geojson: a bare LineString geometry has no times")));
}

}  // namespace

namespace {

// Exercise mode (issue 18): the exercise and role columns are GeoJSON properties too.
TEST(GeoJsonReader, ExerciseAndRolePropertiesKeyTracksByExerciseAndId) {
    const std::string text = R"({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"mmsi": 235000001, "EXERCISE": "A", "Role": "own ship", "time": "2024-05-01T10:00:00Z"},
         "geometry": {"type": "Point", "coordinates": [-1.0, 50.7]}},
        {"type": "Feature", "properties": {"mmsi": 235000001, "EXERCISE": "B", "Role": "target", "time": "2024-05-01T10:00:00Z"},
         "geometry": {"type": "Point", "coordinates": [-1.0, 50.71]}},
        {"type": "Feature", "properties": {"mmsi": 235000001, "EXERCISE": 7, "Role": "trainee", "times": ["2024-05-01T10:00:00Z", "2024-05-01T10:01:00Z"]},
         "geometry": {"type": "LineString", "coordinates": [[-1.0, 50.72], [-0.99, 50.72]]}},
        {"type": "Feature", "properties": {"mmsi": 235000001, "Role": "trainee", "time": "2024-05-01T10:01:00Z"},
         "geometry": {"type": "Point", "coordinates": [-0.99, 50.7]}},
        {"type": "Feature", "properties": {"mmsi": 235000001, "EXERCISE": "A", "Role": "pilot", "time": "2024-05-01T10:01:00Z"},
         "geometry": {"type": "Point", "coordinates": [-0.99, 50.7]}},
        {"type": "Feature", "properties": {"mmsi": 235000001, "EXERCISE": "B", "Role": "trainee", "time": "2024-05-01T10:01:00Z"},
         "geometry": {"type": "Point", "coordinates": [-0.99, 50.71]}}]})";
    ReadOptions o;
    o.exercise_column = "exercise";
    o.role_column = "role";
    const TrackFile f = read_geojson_text(text, "ex.geojson", o);
    std::vector<std::string> keys;
    for (const auto& t : f.tracks) keys.push_back(t.exercise + "/" + t.id + "/" + t.role + "/" + std::to_string(t.fixes.size()));
    EXPECT_THAT(keys, ElementsAre("A/235000001/trainee/1", "B/235000001/target/2", "7/235000001/trainee/2"));
    EXPECT_EQ(f.report.skipped, 2u);
    std::string said;
    for (const auto& m : f.report.messages) said += m + "\n";
    EXPECT_THAT(said, HasSubstr("ex.geojson feature 4: no exercise (property 'exercise' is missing or empty); feature skipped"));
    EXPECT_THAT(said, HasSubstr("ex.geojson feature 5: role \"pilot\" (property 'role') is neither trainee (own, own ship) nor target; feature skipped"));
    EXPECT_THAT(said, HasSubstr("ex.geojson: track '235000001' of exercise 'B': its features disagree on the role (target in feature 2, trainee "
                                "in feature 6 of property 'role'): it is taken as a target"));
    // No feature has the property: the file is refused, naming it and the column.
    ReadOptions other;
    other.exercise_column = "drill";
    EXPECT_THAT([&] { read_geojson_text(text, "ex.geojson", other); },
                ThrowsMessage<InputError>(HasSubstr("ex.geojson: no feature has the property 'drill', the exercise column")));
}

TEST(GeoJsonReader, BlanksAroundAnExerciseAreIgnoredAsInACsvAndBlanksAloneAreNone) {
    const std::string text = R"({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"mmsi": 1, "exercise": "A", "time": "2024-05-01T10:00:00Z"},
         "geometry": {"type": "Point", "coordinates": [-1.0, 50.7]}},
        {"type": "Feature", "properties": {"mmsi": 1, "exercise": " A\t", "time": "2024-05-01T10:01:00Z"},
         "geometry": {"type": "Point", "coordinates": [-0.99, 50.7]}},
        {"type": "Feature", "properties": {"mmsi": 1, "exercise": "  ", "time": "2024-05-01T10:02:00Z"},
         "geometry": {"type": "Point", "coordinates": [-0.98, 50.7]}}]})";
    ReadOptions o;
    o.exercise_column = "exercise";
    const TrackFile f = read_geojson_text(text, "ex.geojson", o);
    ASSERT_EQ(f.tracks.size(), 1u) << "' A' is exercise A";
    EXPECT_EQ(f.tracks[0].exercise, "A");
    EXPECT_EQ(f.tracks[0].fixes.size(), 2u);
    EXPECT_EQ(f.report.skipped, 1u) << "blanks alone: no exercise";
}

}  // namespace
