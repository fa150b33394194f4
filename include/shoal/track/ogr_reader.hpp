#pragma once
/// GPX and GeoJSON tracks.
///
/// GPX, read with OGR's GPX driver: every track (layer `track_points`, segments joined) and every
/// route (layer `route_points`) is a track; its id is its name, else the file's stem when the
/// file holds one track or route, else `STEM:track2` / `STEM:route1` (1-based). Tracks or routes
/// with the same name are one track. GPX 1.0 `course` and `speed` (m/s) are used when present.
///
/// GeoJSON (RFC 7946, WGS84), read with nlohmann::json: GDAL 3.6's GeoJSON driver drops the M
/// of 4-D coordinates and hands nested `coordinateProperties` over as JSON text, so the file is
/// parsed directly, in one pass.
/// - LineString / MultiLineString features with a time per vertex: a property array `times`,
///   `coordTimes`, `timestamps` or `coordinateProperties.times` (ISO 8601 strings or epoch
///   numbers, seconds, or milliseconds when > 1e11; arrays of arrays for MultiLineString), else
///   the M of 4-D coordinates `[lon, lat, z, m]` as epoch seconds. A line without times is an
///   InputError naming the file and the feature.
/// - Point features with a `time` or `timestamp` property, split into tracks by the `id`,
///   `mmsi`, `vessel` or `name` property (else the file's stem: a Point's feature id names the
///   point, not the vessel); optional
///   `heading`, `cog`, `sog` properties as in CSV files.
/// Track ids of lines: the same properties, else the feature id, else the stem (one feature) or
/// `STEM:feature3` (1-based). Features with the same id are one track.

#include <string>
#include <string_view>

#include <shoal/track/reader.hpp>

namespace shoal::track {

TrackFile read_gpx(const std::string& path, const ReadOptions& options = {});

/// Reads GeoJSON text (a whole file's bytes); `file` names it in messages.
TrackFile read_geojson_text(std::string_view text, const std::string& file, const ReadOptions& options = {});
TrackFile read_geojson(const std::string& path, const ReadOptions& options = {});

}  // namespace shoal::track
