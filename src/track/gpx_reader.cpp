// GPX tracks, read with OGR: the one track format that needs GDAL, in a file of its own (a
// program without GDAL could define detail::read_gpx_at otherwise).
#include "util/gdal_support.hpp"
#include <shoal/track/ogr_reader.hpp>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "track/gpx_points.hpp"
#include "util/parse_util.hpp"
#include <shoal/track/row_rules.hpp>
#include "track/stream_readers.hpp"
#include "track/track_set.hpp"
#include <shoal/track/csv_reader.hpp>
#include <shoal/track/time.hpp>
#include <shoal/util/error.hpp>

namespace shoal::track {

namespace {

using detail::TrackSet;

/// GDAL's quiet scope; its last message, or "no reason given".
class QuietErrors : public shoal::detail::QuietErrors {
public:
    static std::string last() { return shoal::detail::QuietErrors::last("no reason given"); }
};
using shoal::detail::register_drivers;

/// One GPX track or route as OGR numbers it in the `tracks` / `routes` layer.
struct GpxParent {
    std::string name;
    std::size_t timed = 0;
    std::size_t points = 0;
};

class GpxReader {
public:
    GpxReader(const std::string& gdal_path, const std::string& file, const ReadOptions& options)
        : m_gdal_path(gdal_path), m_file(file), m_set(m_out, m_file) {
        m_out.format = "gpx";
        m_out.report.max_messages = options.max_messages;
    }

    TrackFile read() {
        register_drivers();
        QuietErrors quiet;
        const char* const drivers[] = {"GPX", nullptr};
        GDALDatasetUniquePtr ds(GDALDataset::Open(m_gdal_path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, drivers));
        if (!ds) throw InputError(m_file + ": not a GPX file OGR can read (" + QuietErrors::last() + ")");
        auto tracks = parents(*ds, "tracks");
        auto routes = parents(*ds, "routes");
        const bool single = tracks.size() + routes.size() == 1;
        const detail::GpxPoints where = detail::scan_gpx_points(m_gdal_path);
        // A point GDAL gave no feature without a reason of its own was lost to the XML's break
        // further on (GDAL's parser drops the features of the block it fails in).
        const std::string lost = where.read ? "GDAL's GPX driver read no point there"
                                            : "not read: the XML is not well-formed further on, at line " + std::to_string(where.error_line);
        points(*ds, "track_points", "track_fid", "track", tracks, single, &where.track, where.problems, lost);
        points(*ds, "route_points", "route_fid", "route", routes, single, &where.route, where.problems, lost);
        if (!where.read && !where.error.empty())  // GDAL's parser stops there too, without a word
            m_out.report.skip_all(0, m_file + " line " + std::to_string(where.error_line) + " column " +
                                         std::to_string(where.error_column) + ": the XML is not well-formed (" + where.error +
                                         "): no point after it is read");
        for (Track& t : m_out.tracks) normalise(t, m_out.report);
        return std::move(m_out);
    }

private:
    static std::map<GIntBig, GpxParent> parents(GDALDataset& ds, const char* layer_name) {
        std::map<GIntBig, GpxParent> out;
        OGRLayer* layer = ds.GetLayerByName(layer_name);
        if (!layer) return out;
        const int name_field = layer->GetLayerDefn()->GetFieldIndex("name");
        for (auto& f : *layer)
            out[f->GetFID()].name = name_field >= 0 && f->IsFieldSetAndNotNull(name_field) ? f->GetFieldAsString(name_field) : "";
        return out;
    }

    std::string id_of(const char* kind, GIntBig fid, const GpxParent& parent, bool single) const {
        if (!parent.name.empty()) return parent.name;
        if (single) return detail::file_stem(m_file);
        return detail::file_stem(m_file) + ":" + kind + std::to_string(fid + 1);
    }

    static std::optional<double> time_of(OGRFeature& f, int field) {
        if (field < 0 || !f.IsFieldSetAndNotNull(field)) return std::nullopt;
        int y = 0, mo = 0, d = 0, h = 0, mi = 0, tz = 0;
        float s = 0.0f;
        if (!f.GetFieldAsDateTime(field, &y, &mo, &d, &h, &mi, &s, &tz)) return std::nullopt;
        // OGR keeps seconds as a float: round to the millisecond GPX files write.
        const double sec = std::round(static_cast<double>(s) * 1000.0) / 1000.0;
        auto t = utc_seconds(y, mo, d, h, mi, std::min(sec, 59.999));
        if (!t) return std::nullopt;
        if (tz > 1) *t -= (tz - 100) * 15.0 * 60.0;  // 100 = UTC, each step 15 minutes east
        return t;
    }

    /// " line L" of a point's tag, with its column when another point starts on that line.
    static std::string where(const detail::GpxPoint& at) {
        return " line " + std::to_string(at.line) + (at.shares_line ? " column " + std::to_string(at.column) : "");
    }

    void points(GDALDataset& ds, const char* layer_name, const char* parent_field, const char* kind,
                std::map<GIntBig, GpxParent>& parents, bool single, const std::vector<detail::GpxPoint>* scanned,
                const std::vector<std::string>& problems, const std::string& lost) {
        OGRLayer* layer = ds.GetLayerByName(layer_name);
        if (!layer) return;
        OGRFeatureDefn* defn = layer->GetLayerDefn();
        const int fid_field = defn->GetFieldIndex(parent_field);
        const int time_field = defn->GetFieldIndex("time");
        const int course_field = defn->GetFieldIndex("course");
        const int speed_field = defn->GetFieldIndex("speed");
        m_current = nullptr;
        // The elements GDAL's driver gave no feature (no lat or lon): each a bad row, in file order.
        std::size_t next = 0;
        auto dropped_before = [&](std::size_t end) {
            for (; scanned && next < end && next < scanned->size(); ++next) {
                const detail::GpxPoint& at = (*scanned)[next];
                ++m_out.report.rows;
                const auto parent = static_cast<GIntBig>(at.parent);
                m_out.report.skip(m_file + where(at) + " (" + kind + " '" + id_of(kind, parent, parents[parent], single) + "'): " +
                                  (at.problem ? problems[at.problem - 1] : lost) + "; point skipped");
            }
        };
        // GDAL's driver gives the k-th element FID k (those it drops too), the FIDs rising. Each
        // feature is checked to lie at the lat and lon written in its element (one whose element
        // holds no number is not compared: GDAL reads 'abc' as 0); should one not, the mapping
        // is given up and the points from there on are named by their number in the file.
        GIntBig last_fid = -1;
        for (auto& f : *layer) {
            const GIntBig fid = f->GetFID();
            const OGRGeometry* g = f->GetGeometryRef();
            const bool point = g && wkbFlatten(g->getGeometryType()) == wkbPoint && !g->IsEmpty();
            ++m_out.report.rows;
            ++m_point;
            const detail::GpxPoint* at = nullptr;
            if (scanned) {
                bool fits = fid > last_fid && static_cast<std::size_t>(fid) < scanned->size();
                if (fits) {
                    const detail::GpxPoint& e = (*scanned)[static_cast<std::size_t>(fid)];
                    fits = (e.problem && !e.time_problem) || (point && g->toPoint()->getX() == e.lon && g->toPoint()->getY() == e.lat);
                }
                if (fits) {
                    dropped_before(static_cast<std::size_t>(fid));
                    next = static_cast<std::size_t>(fid) + 1;
                    last_fid = fid;
                    at = &(*scanned)[static_cast<std::size_t>(fid)];
                } else {
                    scanned = nullptr;
                }
            }
            const GIntBig parent = fid_field >= 0 ? f->GetFieldAsInteger64(fid_field) : 0;
            GpxParent& p = parents[parent];
            ++p.points;
            auto skip = [&](const std::string& what) {
                m_out.report.skip(m_file + (at ? where(*at) : " point " + std::to_string(m_point)) + " (" + kind + " '" +
                                  id_of(kind, parent, p, single) + "'): " + what + "; point skipped");
            };
            std::optional<double> t = time_of(*f, time_field);
            // What its element says is wrong: a lat or lon that is no number ('abc', which GDAL
            // reads as 0), or a <time> that is no time (GDAL reads a date alone as midnight). A
            // point with a time (or one written) counts as timed: its track is not one
            // without times.
            // A time shoal does not read but GDAL does (a leap second, 23:59:60; a trailing
            // non-breaking space) is GDAL's, as before; a date alone GDAL reads as midnight.
            const bool gdal_time = at && at->problem && at->time_problem && !at->date_alone && t;
            if (at && at->problem && !gdal_time) {
                if (at->time_problem || t || std::isfinite(at->time_s)) ++p.timed;
                skip(problems[at->problem - 1]);
                continue;
            }
            // GDAL's driver reads "2024-05-01 10:04:00Z" as midnight: the time as written, read
            // as a CSV's is, where the two differ (GDAL's where they agree, to the millisecond).
            if (!gdal_time && at && std::isfinite(at->time_s) && !(t && std::fabs(*t - at->time_s) < 0.002)) {
                const double whole = std::floor(at->time_s);
                t = whole + std::round((at->time_s - whole) * 1000.0) / 1000.0;
            }
            if (!t) {
                skip("no time");
                continue;
            }
            if (!plausible_fix_time(*t)) {
                skip("time " + format_iso8601(*t, 0) + " is outside the years " + fix_time_range);
                continue;
            }
            ++p.timed;
            if (!point) {
                skip("no point geometry");
                continue;
            }
            Fix fix;
            fix.time_s = *t;
            fix.position = {g->toPoint()->getX(), g->toPoint()->getY()};
            if (std::string what; position_problem(fix.position.lat, fix.position.lon, what)) {
                skip(what);
                continue;
            }
            if (course_field >= 0 && f->IsFieldSetAndNotNull(course_field))
                fix.cog_deg = valid_cog(f->GetFieldAsDouble(course_field));
            if (speed_field >= 0 && f->IsFieldSetAndNotNull(speed_field))
                fix.sog_kn = valid_sog(f->GetFieldAsDouble(speed_field) * 3600.0 / 1852.0);
            fix.line = at ? at->line : m_point;
            if (!m_current || parent != m_current_parent) {
                m_current = &m_set.get(id_of(kind, parent, p, single), p.name);
                m_current_parent = parent;
            }
            m_current->fixes.push_back(fix);
        }
        if (scanned) dropped_before(scanned->size());
        for (const auto& [fid, p] : parents)
            if (p.points > 0 && p.timed == 0)
                throw InputError(m_file + ": " + kind + " '" + id_of(kind, fid, p, single) + "' (" + kind + " " +
                                 std::to_string(fid + 1) + ") has no times; shoal needs a time on every point");
    }

    std::string m_gdal_path;
    std::string m_file;
    TrackFile m_out;
    TrackSet m_set;
    std::size_t m_point = 0;
    Track* m_current = nullptr;  ///< track of the latest point (valid until the next get)
    GIntBig m_current_parent = -1;
};

}  // namespace

TrackFile detail::read_gpx_at(const std::string& gdal_path, const std::string& file, const ReadOptions& options) {
    return GpxReader(gdal_path, file, options).read();
}

TrackFile read_gpx(const std::string& path, const ReadOptions& options) { return detail::read_gpx_at(path, path, options); }

}  // namespace shoal::track
