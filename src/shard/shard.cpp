#include <shoal/shard/shard.hpp>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include <cctype>
#include <charconv>

#include <shoal/util/error.hpp>

namespace shoal::audit {

std::string Shard::text() const { return active() ? std::to_string(index) + "/" + std::to_string(count) : std::string(); }

namespace {

bool parse_number(std::string_view s, unsigned& out) {
    if (s.empty() || s.size() > 7) return false;
    for (const char c : s)
        if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && end == s.data() + s.size();
}

}  // namespace

Shard parse_shard(std::string_view text) {
    const std::string quoted = "AuditOptions::shard '" + std::string(text) + "'";
    const auto slash = text.find('/');
    if (slash == std::string_view::npos)
        throw InputError(quoted + " is not I/N (shard I of N, e.g. 0/4)");
    Shard s;
    if (!parse_number(text.substr(0, slash), s.index) || !parse_number(text.substr(slash + 1), s.count))
        throw InputError(quoted + " is not I/N with whole numbers I and N (e.g. 0/4)");
    if (s.count == 0 || s.count > 1000000) throw InputError(quoted + ": the count N must be 1 to 1000000");
    if (s.index >= s.count)
        throw InputError(quoted + ": the index I must be under the count " + std::to_string(s.count) + " (shards are 0 to " +
                         std::to_string(s.count - 1) + ")");
    return s;
}

std::string shard_key(const std::string& track_id, const std::optional<std::string>& exercise) { return exercise ? *exercise : track_id; }

unsigned shard_of(std::string_view key, unsigned count) noexcept {
    if (count == 0) return 0;
    return static_cast<unsigned>(XXH3_64bits(key.data(), key.size()) % count);
}

}  // namespace shoal::audit
