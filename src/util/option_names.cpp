#include <shoal/util/option_names.hpp>

#include <cstring>

namespace shoal {

namespace {

/// Each option field, with the CLI flag and the Python keyword that set it (null: none).
struct OptionName {
    const char* field;
    const char* flag;
    const char* keyword;
};

constexpr OptionName names[] = {
    {"SweepOptions::step_m", "--step", "step_m"},
    {"EncounterOptions::step_m", "--step", "step_m"},
    {"EncounterOptions::ship_margin_m", "--ship-margin", "ship_margin_m"},
    {"EncounterOptions::max_gap_s", "--max-gap", "max_gap_s"},
    {"WildFixOptions::max_speed_kn", "--max-speed", "max_speed_kn"},
    {"ImportOptions::limiting_depth_m", "--hazard-depth", "hazard_depth_m"},
    {"AuditOptions::hazard_depth_m", "--hazard-depth", "hazard_depth_m"},
    {"AuditOptions::ukc_m", "--ukc", "ukc"},
    {"ImportOptions::source_crs", "--source-crs", "source_crs"},
    {"ImportOptions::danger_radius_m", "--danger-radius", "danger_radius_m"},
    {"ImportOptions::depth_field", "--depth-field", "depth_field"},
    {"ImportOptions::layers", "--layer", "layers"},
    {"BuildRequest::crs", "--crs", "crs"},
    {"BuildRequest::cell_m", "--cell", "cell_m"},
    {"BuildRequest::ship_length_m", "--ship-length", "ship_length_m"},
    {"BuildRequest::cache_dir", "--cache-dir", "cache_dir"},
    {"AuditOptions::shard", "--shard", nullptr},
    {"AuditOptions::exercise_by", "--exercise-by", nullptr},
    {"ReadOptions::exercise_column", "--exercise-by column:NAME", nullptr},
    {"ReadOptions::date_s", "--date", nullptr},
    {"Hull::dims", "--dims", "dims"},
    {"ReadOptions::hull_from_length_width", "--hull-from-length-width", nullptr},
    {"ReadOptions::role_column", "--role-column", nullptr},
    {"AuditOptions::max_encounters_per_ship", "--max-encounters-per-ship", "max_encounters_per_ship"},
};

}  // namespace

std::string in_terms_of(std::string message, FrontEnd front) {
    for (const OptionName& n : names) {
        const char* name = front == FrontEnd::cli ? n.flag : n.keyword;
        if (!name) continue;
        for (std::size_t at; (at = message.find(n.field)) != std::string::npos;) message.replace(at, std::strlen(n.field), name);
    }
    return message;
}

}  // namespace shoal
