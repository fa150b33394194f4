#pragma once
/// GDAL/OGR owners shared by every part that opens datasets (coastlines, expected-contact
/// areas, GPX tracks): driver registration once, a scope that keeps GDAL quiet on stderr and
/// reads its last message back, and the coordinate transformation's owner. Internal.

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_spatialref.h>

#include <memory>
#include <mutex>
#include <string>

namespace shoal::detail {

/// GDALAllRegister(), once per process, from any thread.
inline void register_drivers() {
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
}

/// Silences GDAL's stderr output for its lifetime; errors are read back with last().
class QuietErrors {
public:
    QuietErrors() {
        CPLPushErrorHandler(CPLQuietErrorHandler);
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

struct TransformDeleter {
    void operator()(OGRCoordinateTransformation* t) const noexcept { OGRCoordinateTransformation::DestroyCT(t); }
};
using TransformPtr = std::unique_ptr<OGRCoordinateTransformation, TransformDeleter>;

}  // namespace shoal::detail
