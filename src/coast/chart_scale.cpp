#include <shoal/coast/chart_scale.hpp>

#include <algorithm>

#include <shoal/util/error.hpp>

#include "coast/ogr_source.hpp"

namespace shoal::coast {

std::optional<double> compilation_scale(const std::vector<std::string>& paths) {
    std::optional<double> out;
    for (const std::string& path : paths) {
        if (!ogr::may_be_s57(path)) continue;
        try {
            GDALDatasetUniquePtr ds = ogr::open_vector(path);
            if (!ds || !ogr::is_s57(*ds)) continue;
            OGRLayer* dsid = ds->GetLayerByName("DSID");
            if (!dsid || dsid->GetLayerDefn()->GetFieldIndex("DSPM_CSCL") < 0) continue;
            dsid->ResetReading();
            for (auto& f : *dsid) {
                const int scale = f->GetFieldAsInteger("DSPM_CSCL");
                if (scale > 0) out = std::max(out.value_or(0.0), static_cast<double>(scale));
            }
        } catch (const InputError&) {  // told where the chart is read
        }
    }
    return out;
}

}  // namespace shoal::coast
