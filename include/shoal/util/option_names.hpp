#pragma once
/// What a front end calls an option. The library's messages name the fields of its option
/// structs ("SweepOptions::step_m must be > 0 metres"); the CLI and the Python module each put
/// their own name in its place (--step, step_m), from the one table in option_names.cpp.

#include <string>

namespace shoal {

enum class FrontEnd { cli, python };

/// `message` with every option field it names replaced by the name `front` gives that option
/// (a CLI flag or a Python keyword); a field the front end has no name for stays as it is.
std::string in_terms_of(std::string message, FrontEnd front);

}  // namespace shoal
