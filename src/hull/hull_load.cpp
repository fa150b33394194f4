// Hull::load: a ship file read through GDAL's virtual file layer (detail::read_input: gzip,
// zip, standard input, /vsi paths). Apart from hull.cpp so that the GDAL-free core the C API
// links (src/CMakeLists.txt: shoal_core) has Hull without GDAL; libshoal_c reads ship files
// itself (plain files) and gives them to Hull::parse.

#include <shoal/hull/hull.hpp>

#include <filesystem>
#include <string>
#include <system_error>

#include <shoal/util/error.hpp>
#include "util/input_file.hpp"

namespace shoal::hull {

Hull Hull::load(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw InputError{"Cannot open ship file '" + path + "': it is a folder"};
    std::string text;
    try {
        text = detail::read_input(path, max_file_bytes, "a ship file");
    } catch (const detail::InputOpenError& e) {
        throw InputError{"Cannot open ship file '" + path + "': " + (e.reason == "is a folder" ? "it is a folder" : e.reason)};
    }
    return parse(text, path);
}

}  // namespace shoal::hull
