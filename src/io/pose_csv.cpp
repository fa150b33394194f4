#include <shoal/io/pose_csv.hpp>

#include <filesystem>

#include <shoal/util/error.hpp>
#include "util/input_file.hpp"

namespace shoal::io {

PoseFile read_pose_csv(const std::string& path) {
    // Standard input (-, /vsistdin) and GDAL's paths (/vsigzip/..., /vsizip/...) are read as a
    // track file's are (util/input_file.hpp); a path on disk must be there, and be a file.
    if (!detail::is_virtual_path(path)) {
        std::error_code ec;
        if (!std::filesystem::exists(path, ec)) throw InputError("'" + path + "': no such file or directory");
        if (std::filesystem::is_directory(path, ec)) throw InputError("'" + path + "' is a directory, not a CSV file");
    }
    std::string text;
    try {
        text = detail::read_input(path, max_pose_file_bytes, "a pose file");
    } catch (const detail::InputOpenError& e) {
        throw InputError("cannot open '" + path + "' (" + e.reason + ")");
    }
    return parse_pose_csv(text, path);
}

}  // namespace shoal::io
