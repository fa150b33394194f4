#pragma once
/// Text safe for a terminal: file names, ids and messages that came from input files may hold
/// escape sequences (ESC [ ... moves the cursor, rewrites the screen, sets the title); those
/// bytes are shown as \xHH instead of being sent to the terminal.

#include <cstdio>
#include <string>
#include <string_view>

namespace shoal {

/// `s` with C0 controls (except none), DEL and the UTF-8 encoded C1 controls (U+0080-U+009F)
/// written as \xHH; everything else (UTF-8 letters too) as it is.
inline std::string printable(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    char buf[8];
    for (std::size_t i = 0; i < s.size(); ++i) {
        const auto c = static_cast<unsigned char>(s[i]);
        const bool c1 = c == 0xC2 && i + 1 < s.size() && static_cast<unsigned char>(s[i + 1]) >= 0x80 &&
                        static_cast<unsigned char>(s[i + 1]) <= 0x9F;
        if (c < 0x20 || c == 0x7F || c1) {
            std::snprintf(buf, sizeof buf, "\\x%02X", c);
            out += buf;
            if (c1) {
                std::snprintf(buf, sizeof buf, "\\x%02X", static_cast<unsigned char>(s[++i]));
                out += buf;
            }
        } else {
            out += static_cast<char>(c);
        }
    }
    return out;
}

}  // namespace shoal
