#pragma once
/// The small set of exceptions shoal throws. Exit codes are decided only in cli/main.cpp:
/// `InputError` and `UsageError` map to exit status 2.

#include <stdexcept>
#include <string>

namespace shoal {

/// A file, layer, feature or row that cannot be used, with a message naming it.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Options that contradict each other or are out of range.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A failure inside GEOS or GDAL that is not the input's fault.
struct LibraryError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace shoal
