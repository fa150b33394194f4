#pragma once
/// GDAL/OGR owners shared by every part that opens datasets (coastlines, expected-contact
/// areas, GPX tracks): driver registration once, a scope that keeps GDAL quiet on stderr and
/// reads its last message back, and the coordinate transformation's owner. Internal.

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_spatialref.h>

#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <system_error>

#include <shoal/util/error.hpp>

#include "util/lazy_libraries.hpp"

namespace shoal::detail {

/// GDAL's quiet error handler (debug messages only, when CPL_DEBUG asks), called from here
/// rather than taken by its address: a program linked without GDAL (the CLI's module, which
/// loads it when first needed: util/lazy_libraries.hpp) can hold no GDAL address before GDAL
/// is loaded.
inline void CPL_STDCALL quiet_error_handler(CPLErr type, CPLErrorNum number, const char* message) {
    CPLQuietErrorHandler(type, number, message);
}

/// GDALAllRegister(), once per process, from any thread. GDAL's gzip reader is told not to
/// write its index (FILE.gz.properties) beside a gzip it reads: shoal writes no file beside
/// its inputs.
inline void register_drivers() {
    need_gdal();
    static std::once_flag once;
    std::call_once(once, [] {
        CPLSetConfigOption("CPL_VSIL_GZIP_WRITE_PROPERTIES", "NO");
        GDALAllRegister();
    });
}

/// Silences GDAL's stderr output for its lifetime; errors are read back with last().
class QuietErrors {
public:
    QuietErrors() {
        need_gdal();
        CPLPushErrorHandler(quiet_error_handler);
        CPLErrorReset();
    }
    ~QuietErrors() { CPLPopErrorHandler(); }
    QuietErrors(const QuietErrors&) = delete;
    QuietErrors& operator=(const QuietErrors&) = delete;
    /// GDAL's last message, or `none` when it gave none.
    static std::string last(const char* none = "") {
        const char* m = CPLGetLastErrorMsg();
        return m && *m ? std::string(m) : std::string(none);
    }
};

/// Like QuietErrors, and keeps what GDAL reports as a failure in its lifetime (CE_Failure and
/// worse): a driver that cannot read part of a file (a Shapefile cut short, a GeoJSON
/// geometry with text for coordinates) often says so only through the error handler, and
/// hands back the feature without its geometry, or no more features.
class GdalFailures {
public:
    GdalFailures() {
        need_gdal();
        CPLPushErrorHandlerEx(handler, this);
        CPLErrorReset();
    }
    ~GdalFailures() { CPLPopErrorHandler(); }
    GdalFailures(const GdalFailures&) = delete;
    GdalFailures& operator=(const GdalFailures&) = delete;
    std::size_t count() const noexcept { return m_count; }
    /// "GDAL: FIRST (and N more)", or "" when GDAL reported no failure.
    std::string said() const {
        if (m_count == 0) return "";
        return "GDAL: " + m_first + (m_count > 1 ? " (and " + std::to_string(m_count - 1) + " more)" : "");
    }

private:
    static void CPL_STDCALL handler(CPLErr type, CPLErrorNum number, const char* message) {
        auto* self = static_cast<GdalFailures*>(CPLGetErrorHandlerUserData());
        if (self && type >= CE_Failure) {
            if (self->m_count++ == 0) self->m_first = message ? message : "";
            return;
        }
        CPLQuietErrorHandler(type, number, message);
    }
    std::size_t m_count = 0;
    std::string m_first;
};

/// Refuses a dataset path (a coastline, a chart, --berths) that is neither a file nor a folder:
/// a device (/dev/zero, /dev/urandom), a pipe or a FIFO. OGR's drivers seek in and read again
/// what they open, so a stream would be drained or read without end (before: /dev/zero as a
/// coast was hashed for the grid cache for ever). Paths GDAL reads itself (/vsi...) and paths
/// that do not exist (the caller says so) pass.
inline void require_dataset_file(const std::string& path, const char* what) {
    if (path.rfind("/vsistdin", 0) == 0)
        throw InputError("'" + path + "': standard input: " + what + " is read by OGR, which needs a file it can read again; save it to a file first");
    if (path.rfind("/vsi", 0) == 0) return;
    std::error_code ec;
    const auto st = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(st) || std::filesystem::is_regular_file(st) || std::filesystem::is_directory(st)) return;
    throw InputError("'" + path + "': not a regular file (a device, a pipe or a FIFO): " + what +
                     " is read by OGR, which needs a file it can read again; save it to a file first");
}

struct TransformDeleter {
    void operator()(OGRCoordinateTransformation* t) const noexcept { OGRCoordinateTransformation::DestroyCT(t); }
};
using TransformPtr = std::unique_ptr<OGRCoordinateTransformation, TransformDeleter>;

}  // namespace shoal::detail
