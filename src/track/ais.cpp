#include <shoal/track/ais.hpp>

#include <charconv>

#include "util/parse_util.hpp"
#include <shoal/track/row_rules.hpp>
#include <shoal/track/time.hpp>

namespace shoal::track::ais {

namespace {

constexpr std::size_t max_payload_chars = 2048;  // the longest AIS message is 1008 bits, 168 characters
constexpr std::size_t max_key_chars = 32;        // a sequence id 0-9 and a channel; a tag-block group id

int hex_value(char c) noexcept {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
}

bool is_alnum_upper(char c) noexcept { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'); }

/// Digits only (at most 9), as an int; false for anything else.
bool small_int(std::string_view s, int& out) noexcept {
    if (s.empty() || s.size() > 9) return false;
    for (const char c : s)
        if (c < '0' || c > '9') return false;
    out = 0;
    std::from_chars(s.data(), s.data() + s.size(), out);
    return true;
}

/// The start of a `!--VDM`/`!--VDO` sentence in `text`, npos when none.
std::size_t ais_start(std::string_view text) noexcept {
    for (std::size_t i = text.find('!'); i != std::string_view::npos; i = text.find('!', i + 1)) {
        if (i + 7 > text.size() || !is_alnum_upper(text[i + 1]) || !is_alnum_upper(text[i + 2])) continue;
        const std::string_view kind = text.substr(i + 3, 3);
        if ((kind == "VDM" || kind == "VDO") && text[i + 6] == ',') return i;
    }
    return std::string_view::npos;
}

void split(std::string_view s, char sep, std::vector<std::string_view>& out) {
    out.clear();
    for (std::size_t start = 0;;) {
        const std::size_t at = s.find(sep, start);
        if (at == std::string_view::npos) {
            out.push_back(s.substr(start));
            return;
        }
        out.push_back(s.substr(start, at - start));
        start = at + 1;
    }
}

/// A receive time written before the sentence (or its tag block): epoch seconds or
/// milliseconds, or ISO 8601, perhaps in brackets and followed by a separator.
double receive_time(std::string_view prefix) noexcept {
    prefix = detail::trim(prefix);
    while (!prefix.empty() && (prefix.back() == ',' || prefix.back() == ';' || prefix.back() == ':' || prefix.back() == '|'))
        prefix = detail::trim(prefix.substr(0, prefix.size() - 1));
    if (prefix.size() >= 2 && ((prefix.front() == '(' && prefix.back() == ')') || (prefix.front() == '[' && prefix.back() == ']')))
        prefix = detail::trim(prefix.substr(1, prefix.size() - 2));
    if (prefix.empty()) return NAN;
    if (const auto t = parse_epoch(prefix)) return *t;
    if (const auto t = parse_iso8601(prefix)) return *t;
    return NAN;
}

/// What a tag block (`\s:...,c:...,g:1-2-34*hh\`) says that shoal uses.
struct TagBlock {
    double time_s = NAN;
    std::string_view group;  ///< the `id` of `g:n-N-id`; empty when none
};

bool parse_tag_block(std::string_view tag, TagBlock& out, std::string& problem) {
    std::string_view body;
    if (!checksum_ok(tag, body, problem)) {
        problem = "tag block " + problem;
        return false;
    }
    std::vector<std::string_view> fields;
    split(body, ',', fields);
    for (const std::string_view f : fields) {
        if (f.size() < 2 || f[1] != ':') continue;
        const std::string_view value = f.substr(2);
        if (f[0] == 'c') {
            const auto t = parse_epoch(value);
            if (!t) {
                problem = "tag block time c:" + detail::quoted(value) + " is not epoch seconds or milliseconds";
                return false;
            }
            out.time_s = *t;
        } else if (f[0] == 'g') {
            const std::size_t last = value.rfind('-');
            if (last == std::string_view::npos || last + 1 == value.size()) {
                problem = "tag block group g:" + detail::quoted(value) + " is not n-N-id";
                return false;
            }
            out.group = value.substr(last + 1);
        }
    }
    return true;
}

double scaled_sog(std::uint32_t raw) noexcept { return valid_sog(raw == 1023 ? NAN : raw / 10.0); }
double scaled_cog(std::uint32_t raw) noexcept { return valid_cog(raw / 10.0); }
double scaled_heading(std::uint32_t raw) noexcept { return raw < 360 ? static_cast<double>(raw) : NAN; }

/// A position in 1/`per_degree` degrees; none when not available (181, 91) or off the globe.
std::optional<geo::LonLat> position(std::int32_t lon, std::int32_t lat, double per_degree) noexcept {
    const geo::LonLat p{lon / per_degree, lat / per_degree};
    if (!(std::fabs(p.lon) <= 180.0) || !(std::fabs(p.lat) <= 90.0)) return std::nullopt;
    return p;
}

std::optional<hull::Dimensions> dimensions(const Bits& b, std::size_t at) noexcept {
    const hull::Dimensions d{static_cast<double>(b.u(at, 9)), static_cast<double>(b.u(at + 9, 9)),
                             static_cast<double>(b.u(at + 18, 6)), static_cast<double>(b.u(at + 24, 6))};
    if (d.a > 0 && d.b > 0 && d.c > 0 && d.d > 0) return d;
    return std::nullopt;
}

/// The shortest message of each type shoal reads, in bits (as gpsd accepts them).
std::size_t min_bits(int type, int part) noexcept {
    switch (type) {
        case 1: case 2: case 3: case 18: return 168;
        case 19: return 312;
        case 5: return 420;
        case 24: return part == 0 ? 160 : 168;
        case 27: return 96;
        default: return 0;
    }
}

}  // namespace

bool checksum_ok(std::string_view sentence, std::string_view& body, std::string& problem) {
    const std::size_t star = sentence.find('*');
    if (star == std::string_view::npos) {
        body = sentence;
        return true;
    }
    body = sentence.substr(0, star);
    const int hi = star + 1 < sentence.size() ? hex_value(sentence[star + 1]) : -1;
    const int lo = star + 2 < sentence.size() ? hex_value(sentence[star + 2]) : -1;
    unsigned sum = 0;
    for (const char c : body) sum ^= static_cast<unsigned char>(c);
    if (hi >= 0 && lo >= 0 && static_cast<unsigned>(hi * 16 + lo) == sum) return true;
    const char computed[3] = {"0123456789ABCDEF"[sum >> 4], "0123456789ABCDEF"[sum & 15], '\0'};
    problem = "bad checksum " + detail::quoted(sentence.substr(star, 3)) + " (computed *" + computed + ")";
    return false;
}

// ---------------------------------------------------------------------------------------------
// Bits

bool Bits::assign(std::string_view payload, unsigned fill) {
    m_six.clear();
    m_size = 0;
    if (fill > 5) return false;
    m_six.reserve(payload.size());
    for (const char c : payload) {
        if (!((c >= '0' && c <= 'W') || (c >= '`' && c <= 'w'))) {
            m_six.clear();
            return false;
        }
        int v = c - '0';
        if (v > 40) v -= 8;
        m_six.push_back(static_cast<std::uint8_t>(v));
    }
    m_size = m_six.size() * 6 >= fill ? m_six.size() * 6 - fill : 0;
    return true;
}

std::uint32_t Bits::u(std::size_t start, std::size_t len) const noexcept {
    std::uint32_t v = 0;
    for (std::size_t i = start; i < start + len; ++i) {
        const unsigned bit = i < m_size ? (m_six[i / 6] >> (5 - i % 6)) & 1U : 0U;
        v = (v << 1) | bit;
    }
    return v;
}

std::int32_t Bits::s(std::size_t start, std::size_t len) const noexcept {
    const std::uint32_t v = u(start, len);
    if (len == 0 || len >= 32 || !(v >> (len - 1))) return static_cast<std::int32_t>(v);
    return static_cast<std::int32_t>(static_cast<std::int64_t>(v) - (std::int64_t{1} << len));
}

std::string Bits::text(std::size_t start, std::size_t chars) const {
    std::string out;
    for (std::size_t k = 0; k < chars; ++k) {
        const auto v = static_cast<char>(u(start + 6 * k, 6));
        const char c = v < 32 ? static_cast<char>(v + 64) : v;
        if (c == '@') break;
        out += c;
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    return out;
}

// ---------------------------------------------------------------------------------------------
// Messages

Decode decode(std::string_view payload, unsigned fill, Message& out, std::string& problem) {
    out = Message{};
    Bits b;
    if (payload.size() > max_payload_chars) {
        problem = "AIS payload of " + std::to_string(payload.size()) + " characters is longer than any message";
        return Decode::bad;
    }
    if (!b.assign(payload, fill)) {
        problem = fill > 5 ? "AIS fill bits " + std::to_string(fill) + " (0-5)"
                           : "AIS payload " + detail::quoted(payload) + " holds a character that is not 6-bit armour";
        return Decode::bad;
    }
    if (b.size() < 38) {
        problem = "AIS message of " + std::to_string(b.size()) + " bits is too short for a type and MMSI";
        return Decode::bad;
    }
    out.type = static_cast<int>(b.u(0, 6));
    out.mmsi = b.u(8, 30);
    if (out.type == 24) {
        out.part = static_cast<int>(b.u(38, 2));
        if (out.part > 1) {
            problem = "AIS type 24 part " + std::to_string(out.part) + " (only A = 0 and B = 1 exist)";
            return Decode::bad;
        }
    }
    const std::size_t need = min_bits(out.type, out.part);
    if (need == 0) return Decode::skipped_type;
    if (b.size() < need) {
        problem = "AIS type " + std::to_string(out.type) + " message of " + std::to_string(b.size()) + " bits (needs " +
                  std::to_string(need) + ")";
        return Decode::bad;
    }
    switch (out.type) {
        case 1: case 2: case 3:
            out.nav_status = static_cast<std::uint8_t>(b.u(38, 4));
            out.sog_kn = scaled_sog(b.u(50, 10));
            out.position = position(b.s(61, 28), b.s(89, 27), 600000.0);
            out.cog_deg = scaled_cog(b.u(116, 12));
            out.heading_deg = scaled_heading(b.u(128, 9));
            out.second = static_cast<int>(b.u(137, 6));
            break;
        case 18: case 19:
            out.sog_kn = scaled_sog(b.u(46, 10));
            out.position = position(b.s(57, 28), b.s(85, 27), 600000.0);
            out.cog_deg = scaled_cog(b.u(112, 12));
            out.heading_deg = scaled_heading(b.u(124, 9));
            out.second = static_cast<int>(b.u(133, 6));
            if (out.type == 19) {
                out.name = b.text(143, 20);
                out.ship_type = static_cast<int>(b.u(263, 8));
                out.dims = dimensions(b, 271);
            }
            break;
        case 27: {
            out.nav_status = static_cast<std::uint8_t>(b.u(40, 4));
            out.position = position(b.s(44, 18), b.s(62, 17), 600.0);
            const std::uint32_t sog = b.u(79, 6), cog = b.u(85, 9);
            out.sog_kn = sog == 63 ? NAN : static_cast<double>(sog);
            out.cog_deg = valid_cog(static_cast<double>(cog));
            break;
        }
        case 5: {
            out.name = b.text(112, 20);
            out.ship_type = static_cast<int>(b.u(232, 8));
            out.dims = dimensions(b, 240);
            const std::uint32_t draught = b.u(294, 8);
            if (draught > 0) out.draught_m = draught / 10.0;
            break;
        }
        case 24:
            if (out.part == 0) {
                out.name = b.text(40, 20);
            } else {
                out.ship_type = static_cast<int>(b.u(40, 8));
                if (out.mmsi / 10000000 != 98) out.dims = dimensions(b, 132);  // 98...: auxiliary craft, a mothership MMSI there
            }
            break;
        default:
            break;
    }
    return Decode::ok;
}

// ---------------------------------------------------------------------------------------------
// Lines

bool LineDecoder::is_ais(std::string_view text) noexcept { return ais_start(text) != std::string_view::npos; }

bool LineDecoder::line(std::string_view text, std::size_t line, Decoded& out) {
    const std::size_t start = ais_start(text);
    if (start == std::string_view::npos) return false;
    std::string problem;
    std::string_view prefix = text.substr(0, start);
    TagBlock tag;
    if (const std::size_t close = prefix.find_last_not_of(" \t"); close != std::string_view::npos && prefix[close] == '\\') {
        const std::size_t open = prefix.rfind('\\', close == 0 ? 0 : close - 1);
        if (open != std::string_view::npos && open < close) {
            if (!parse_tag_block(prefix.substr(open + 1, close - open - 1), tag, problem)) {
                m_problem(line, problem);
                return false;
            }
            prefix = prefix.substr(0, open);
        }
    }
    const std::string_view sentence = text.substr(start);
    std::string_view body;
    if (!checksum_ok(sentence.substr(1), body, problem)) {
        m_problem(line, problem);
        return false;
    }
    std::vector<std::string_view> f;
    split(body, ',', f);
    int count = 0, index = 0, fill = 0;
    if (f.size() != 7) {
        m_problem(line, std::string(f[0]) + " with " + std::to_string(f.size()) + " fields (7: count, number, id, channel, payload, fill)");
        return false;
    }
    if (!small_int(f[1], count) || !small_int(f[2], index) || count < 1 || index < 1 || index > count) {
        m_problem(line, std::string(f[0]) + " fragment " + detail::quoted(f[2]) + " of " + detail::quoted(f[1]) + " is not a fragment number");
        return false;
    }
    if (!small_int(detail::trim(f[6]), fill) || fill > 5) {
        m_problem(line, std::string(f[0]) + " fill bits " + detail::quoted(f[6]) + " (0-5)");
        return false;
    }
    const bool own = f[0].substr(2) == "VDO";
    double time_s = tag.time_s;
    if (std::isnan(time_s)) time_s = receive_time(prefix);

    std::string payload;
    Decoded first;
    if (count == 1) {
        payload = f[5];
        first.line = line;
        first.own = own;
        first.time_s = time_s;
    } else {
        // What waits for its next fragment is bounded whatever the lines: a key of a few
        // characters, a payload of at most max_payload_chars, at most max_pending messages.
        const std::string_view id = tag.group.empty() ? f[3] : tag.group;
        if (id.size() + f[4].size() > max_key_chars) {
            m_problem(line, std::string(f[0]) + (tag.group.empty() ? " sequence id and channel " + detail::quoted(std::string(f[3]) + ',' + std::string(f[4]))
                                                                  : " tag block group id " + detail::quoted(tag.group)) +
                                " longer than " + std::to_string(max_key_chars) + " characters (not a message id)");
            return false;
        }
        std::string key = tag.group.empty() ? std::string(f[3]) + ',' + std::string(f[4]) : "g:" + std::string(tag.group);
        key += own ? ",o" : ",m";
        const auto it = m_pending.find(key);
        if (index == 1) {
            if (it != m_pending.end()) drop_half(it);
            if (f[5].size() > max_payload_chars) {
                m_problem(line, "AIS message of more than " + std::to_string(max_payload_chars) + " payload characters");
                return false;
            }
            if (m_pending.size() >= max_pending) drop_half(m_pending.find(m_order.begin()->second));  // the oldest
            Pending& p = m_pending[key];
            p.count = count;
            p.next = 2;
            p.payload = f[5];
            p.first.line = line;
            p.first.own = own;
            p.first.time_s = time_s;
            p.serial = ++m_serial;
            m_order.emplace(p.serial, key);
            return false;
        }
        if (it == m_pending.end() || it->second.next != index || it->second.count != count) {
            m_problem(line, "AIS fragment " + std::to_string(index) + " of " + std::to_string(count) +
                                " without the fragments before it (half message)");
            if (it != m_pending.end()) drop_half(it);
            return false;
        }
        Pending& p = it->second;
        p.payload += f[5];
        if (std::isnan(p.first.time_s)) p.first.time_s = time_s;
        if (p.payload.size() > max_payload_chars) {
            m_problem(p.first.line, "AIS message of more than " + std::to_string(max_payload_chars) + " payload characters");
            erase(it);
            return false;
        }
        if (index < count) {
            p.next = index + 1;
            return false;
        }
        payload = std::move(p.payload);
        first = std::move(p.first);
        erase(it);
    }
    switch (decode(payload, static_cast<unsigned>(fill), first.message, problem)) {
        case Decode::ok:
            out = std::move(first);
            return true;
        case Decode::skipped_type:
            ++m_skipped_types[first.message.type];
            return false;
        case Decode::bad:
            m_problem(first.line, problem);
            return false;
    }
    return false;
}

void LineDecoder::erase(std::map<std::string, Pending>::iterator it) {
    m_order.erase(it->second.serial);
    m_pending.erase(it);
}

void LineDecoder::drop_half(std::map<std::string, Pending>::iterator it) {
    const Pending& p = it->second;
    m_problem(p.first.line, "AIS message of " + std::to_string(p.count) + " fragments without fragment " + std::to_string(p.next) +
                                " (half message)");
    erase(it);
}

void LineDecoder::finish() {
    while (!m_order.empty()) drop_half(m_pending.find(m_order.begin()->second));  // in the order of their lines
}

std::vector<Decoded> decode_lines(std::string_view text, std::vector<std::string>* problems) {
    std::vector<Decoded> out;
    LineDecoder decoder([&](std::size_t line, const std::string& what) {
        if (problems) problems->push_back("line " + std::to_string(line) + ": " + what);
    });
    std::size_t line = 0;
    for (std::size_t pos = 0; pos < text.size();) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        ++line;
        Decoded d;
        if (decoder.line(detail::trim(text.substr(pos, end - pos)), line, d)) out.push_back(std::move(d));
        pos = end + 1;
    }
    decoder.finish();
    return out;
}

}  // namespace shoal::track::ais
