// Where each point of a GPX file is written, and its lat and lon as written: what GDAL's GPX
// driver does not say. It reads a `lat="abc"` as latitude 0 and drops a point without `lat`
// without a word; its features carry no line. Read with expat, the XML parser GDAL's driver
// itself uses, through GDAL's virtual file system (the same path GDAL opens).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace shoal::track::detail {

/// One <trkpt> or <rtept> element (40 bytes: a file of 10 million points is 400 MB of them).
struct GpxPoint {
    double lat = 0, lon = 0;
    /// Its own <time> (the element's child) read as shoal reads a time (track/time.hpp,
    /// ISO 8601: `2024-05-01 10:04:00Z` too, which GDAL's driver reads as midnight); NaN when
    /// it has none, or one that is no time (then `problem` says so).
    double time_s = NAN;
    std::uint32_t line = 0;    ///< 1-based line of its start tag (saturated at 2^32 - 1)
    std::uint32_t column = 0;  ///< 1-based column of its start tag (saturated)
    std::int32_t parent = -1;  ///< 0-based index of the last <trk> or <rte> begun (GDAL's track_fid, route_fid); -1 before any
    /// 0 when lat, lon (and the time, when it has one) are there and readable; else 1 + the
    /// index in GpxPoints::problems of what is wrong ("latitude 'abc' is not a number", "no
    /// lon attribute", "time '2024-05-01' is a date without a time of day").
    std::uint32_t problem : 29 = 0;
    std::uint32_t time_problem : 1 = 0;  ///< `problem` is its time's (its lat and lon are fine)
    std::uint32_t date_alone : 1 = 0;    ///< that time is a date alone (which GDAL reads as midnight)
    std::uint32_t shares_line : 1 = 0;   ///< another point of its kind starts on the same line
};

/// Every <trkpt> and <rtept> of a GPX file, each in document order: GDAL's GPX driver gives the
/// k-th element of each kind the FID k in its track_points / route_points layer (an element it
/// drops still takes its number). The reader checks each feature against its element (its lat
/// and lon) before it relies on that.
struct GpxPoints {
    std::vector<GpxPoint> track, route;  ///< up to the error, when there is one
    std::vector<std::string> problems;   ///< what is wrong with the points that have a problem
    bool read = false;  ///< the whole file was parsed as XML
    std::string error;  ///< else expat's reason ("" when the file could not be opened)
    std::size_t error_line = 0, error_column = 0;
};

/// Scans the file at `gdal_path` (a path GDAL's VSI opens: a file, /vsimem/, /vsizip/...). A file
/// that is not well-formed XML gives read = false, where and why, and the points before it.
GpxPoints scan_gpx_points(const std::string& gdal_path);

}  // namespace shoal::track::detail
