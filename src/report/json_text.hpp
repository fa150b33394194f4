#pragma once
/// A report field's value as JSON text, the very bytes nlohmann::json's dump() writes for it
/// (the report's writer before), without building a json value: a layer's rows (a pose a
/// fix of a day of AIS) are written by appending.

#include <string>
#include <string_view>

#include <shoal/report/report_fields.hpp>

namespace shoal::report {

/// Appends `s` as a JSON string: quoted, escaped as dump() escapes (and, as dump(), throws
/// nlohmann's type_error for text that is not UTF-8).
void append_json_string(std::string& out, std::string_view s);

/// Appends `v` as dump() writes it: null, a string, an integer, a number (nlohmann's shortest
/// round-trip digits; null when not finite), true or false.
void append_json_value(std::string& out, const fields::Value& v);

}  // namespace shoal::report
