#pragma once
/// The names a path can give standard input by. Internal.

#include <string>

namespace shoal::detail {

/// Whether `path` names this process's standard input: `-`, `/vsistdin` and `/vsistdin/NAME`
/// (read as such by InputFile), or `/dev/stdin`, `/dev/fd/0`, `/proc/self/fd/0` (the system's
/// names of the same stream). Standard input can be read once: two inputs naming it would race
/// for its bytes.
inline bool reads_standard_input(const std::string& path) noexcept {
    return path == "-" || path.rfind("/vsistdin", 0) == 0 || path == "/dev/stdin" || path == "/dev/fd/0" || path == "/proc/self/fd/0";
}

}  // namespace shoal::detail
