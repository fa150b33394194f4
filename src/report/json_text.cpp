#include "report/json_text.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <variant>

namespace shoal::report {

void append_json_string(std::string& out, std::string_view s) {
    // Printable ASCII other than the quote and the backslash is written as it is; any other
    // text is left to nlohmann (escapes, and the check that it is UTF-8: bytes that are not,
    // a Latin-1 'é' in a bad row's field quoted by its message, or such a field cut at 40
    // bytes inside a character, become U+FFFD; before, the run ended with an internal error
    // and no report).
    for (const char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u >= 0x7f || c == '"' || c == '\\') {
            out += nlohmann::json(std::string(s)).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
            return;
        }
    }
    out += '"';
    out.append(s);
    out += '"';
}

void append_json_value(std::string& out, const fields::Value& v) {
    std::visit(
        [&](const auto& x) {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, std::monostate>) {
                out += "null";
            } else if constexpr (std::is_same_v<T, std::string>) {
                append_json_string(out, x);
            } else if constexpr (std::is_same_v<T, bool>) {
                out += x ? "true" : "false";
            } else if constexpr (std::is_same_v<T, std::int64_t>) {
                char buf[24];
                out.append(buf, static_cast<std::size_t>(std::to_chars(buf, buf + sizeof buf, x).ptr - buf));
            } else {
                if (!std::isfinite(x)) {
                    out += "null";
                    return;
                }
                // What serializer::dump_float writes for a double: nlohmann's own digits.
                std::array<char, 64> buf;
                char* end = nlohmann::detail::to_chars(buf.data(), buf.data() + buf.size(), x);
                out.append(buf.data(), static_cast<std::size_t>(end - buf.data()));
            }
        },
        v);
}

}  // namespace shoal::report
