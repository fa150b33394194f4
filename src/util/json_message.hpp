#pragma once
/// nlohmann-json's error messages, fit for a user's terminal. Internal.

#include <cstddef>
#include <string>
#include <string_view>

namespace shoal::detail {

/// The longest JSON error message quoted (bytes).
inline constexpr std::size_t max_json_message_bytes = 240;

/// `text` cut to `max` bytes ("..." after it when cut), for a value of a hostile file quoted in a message.
inline std::string shortened(std::string_view text, std::size_t max = 80) {
    if (text.size() <= max) return std::string{text};
    return std::string{text.substr(0, max)} + "...";
}

/// `what` of a nlohmann::json exception without its "[json.exception.parse_error.101] " tag, cut
/// to max_json_message_bytes: its "last read: '...'" quotes the whole token, which may be
/// megabytes of a hostile file.
inline std::string json_error_text(const char* what) {
    std::string_view text{what};
    if (!text.empty() && text.front() == '[') {
        const auto close = text.find("] ");
        if (close != std::string_view::npos) text.remove_prefix(close + 2);
    }
    return shortened(text, max_json_message_bytes);
}

}  // namespace shoal::detail
