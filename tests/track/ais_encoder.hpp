#pragma once
/// The tests' own AIS encoder: fields bit-packed most significant bit first and armoured into
/// 6-bit payload characters (ITU-R M.1371 8.2.4), and the NMEA checksum. Independent of
/// shoal's decoder (src/track/ais.cpp), so that messages built with it test that decoder.

#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace shoal::test {

/// Packs fields most significant bit first and armours them (ITU-R M.1371 8.2.4).
class Encoder {
public:
    /// The `bits` low bits of `v` (a negative `v` in two's complement).
    void put(std::int64_t v, int bits) {
        for (int i = bits - 1; i >= 0; --i) m_bits.push_back(((static_cast<std::uint64_t>(v) >> i) & 1U) != 0);
    }
    /// `chars` characters of 6-bit ASCII, `s` padded with `@`.
    void text(const std::string& s, std::size_t chars) {
        for (std::size_t i = 0; i < chars; ++i) {
            const char c = i < s.size() ? s[i] : '@';
            put(c >= 64 ? c - 64 : c, 6);
        }
    }
    std::size_t size() const noexcept { return m_bits.size(); }
    /// The payload and its fill bits.
    std::pair<std::string, int> armour() const {
        std::vector<bool> b = m_bits;
        const int fill = static_cast<int>((6 - b.size() % 6) % 6);
        b.resize(b.size() + fill, false);
        std::string out;
        for (std::size_t i = 0; i < b.size(); i += 6) {
            int v = 0;
            for (std::size_t k = 0; k < 6; ++k) v = v * 2 + (b[i + k] ? 1 : 0);
            out += static_cast<char>(v < 40 ? v + 48 : v + 56);
        }
        return {out, fill};
    }

private:
    std::vector<bool> m_bits;
};

/// `body` followed by `*` and its NMEA checksum (the XOR of its bytes, two hex digits).
inline std::string with_checksum(const std::string& body) {
    unsigned x = 0;
    for (const char c : body) x ^= static_cast<unsigned char>(c);
    char buf[4];
    std::snprintf(buf, sizeof buf, "*%02X", x);
    return body + buf;
}

}  // namespace shoal::test
