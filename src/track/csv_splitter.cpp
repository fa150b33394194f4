// CsvSplitter: CSV text into records (GDAL-free, in shoal_core: the track reader's and the pose
// reader's one splitter; the `shoal` executable's own probe of a grid file reads poses with it).
#include <shoal/track/csv_splitter.hpp>

#include <algorithm>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "util/parse_util.hpp"

namespace shoal::track {

using detail::trim;

namespace {

/// The separator the first line holds most often outside quotes ('\0' for none); `ended` tells
/// whether that line ended within `text`.
char detect_separator(std::string_view text, bool* ended = nullptr) {
    std::size_t commas = 0, semicolons = 0, tabs = 0;
    bool quoted = false, newline = false;
    for (const char c : text) {
        if (c == '"') quoted = !quoted;
        if (quoted) continue;
        if (c == '\n') {
            newline = true;
            break;
        }
        commas += c == ',';
        semicolons += c == ';';
        tabs += c == '\t';
    }
    if (ended) *ended = newline;
    if (commas == 0 && semicolons == 0 && tabs == 0) return '\0';
    if (commas >= semicolons && commas >= tabs) return ',';
    return semicolons >= tabs ? ';' : '\t';
}

/// The first position at or after `pos` holding `sep` or a line end (t.size() if none):
/// the end of an unquoted field. Sixteen bytes at a time where SSE2 is there.
std::size_t field_end(std::string_view t, std::size_t pos, char sep) noexcept {
    const std::size_t n = t.size();
#if defined(__SSE2__)
    const __m128i vs = _mm_set1_epi8(sep), vn = _mm_set1_epi8('\n');
    while (pos + 16 <= n) {
        const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(t.data() + pos));
        const unsigned mask = static_cast<unsigned>(_mm_movemask_epi8(_mm_or_si128(_mm_cmpeq_epi8(v, vs), _mm_cmpeq_epi8(v, vn))));
        if (mask != 0) return pos + static_cast<std::size_t>(__builtin_ctz(mask));
        pos += 16;
    }
#endif
    while (pos < n && t[pos] != sep && t[pos] != '\n') ++pos;
    return pos;
}

/// Bit i set where t[pos + i] is `sep`, a line end or a quote, over the 64 bytes from `pos`
/// (fewer at the end of `t`).
std::uint64_t stops(std::string_view t, std::size_t pos, char sep) noexcept {
    const std::size_t n = t.size();
    std::uint64_t m = 0;
#if defined(__SSE2__)
    if (pos + 64 <= n) {
        const __m128i vs = _mm_set1_epi8(sep), vn = _mm_set1_epi8('\n'), vq = _mm_set1_epi8('"');
        for (unsigned k = 0; k < 4; ++k) {
            const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(t.data() + pos + 16 * k));
            const __m128i hit = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(v, vs), _mm_cmpeq_epi8(v, vn)), _mm_cmpeq_epi8(v, vq));
            m |= static_cast<std::uint64_t>(static_cast<unsigned>(_mm_movemask_epi8(hit))) << (16 * k);
        }
        return m;
    }
#endif
    const std::size_t end = std::min(n, pos + 64);
    for (std::size_t i = pos; i < end; ++i) {
        const char c = t[i];
        if (c == sep || c == '\n' || c == '"') m |= std::uint64_t{1} << (i - pos);
    }
    return m;
}

}  // namespace

CsvSplitter::CsvSplitter(std::string_view text, bool complete) : m_text(text), m_complete(complete) {
    if (m_text.substr(0, 3) == "\xEF\xBB\xBF") {
        m_text.remove_prefix(3);
        m_skipped = 3;
    }
    m_sep = detect_separator(m_text);
}

bool CsvSplitter::holds_first_line(std::string_view text) noexcept {
    bool ended = false;
    detect_separator(text, &ended);
    return ended;
}

void CsvSplitter::more(std::string_view text, bool complete) {
    m_text = text;
    m_complete = complete;
    m_skipped = 0;
    m_pos = 0;
}

bool CsvSplitter::quote_left_open(bool closed, char sep) const noexcept {
    const std::string_view t = m_text;
    const std::size_t n = t.size();
    if (!closed) return m_pos < n || m_complete;  // too many lines, or the end of the file: the end of the text alone may be a block's
    std::size_t p = m_pos;
    while (p < n && (t[p] == ' ' || t[p] == '\r')) ++p;
    return p < n && t[p] != sep && t[p] != '\n';  // text after the closing quote
}

bool CsvSplitter::next(std::vector<std::string_view>& fields) {
    const std::string_view t = m_text;
    const std::size_t n = t.size();
    const char sep = m_sep ? m_sep : ',';
    m_unescaped.clear();
    m_quote_not_closed = false;
    m_quoted_line_ends = 0;
    while (m_pos < n) {
        fields.clear();
        m_record_line = m_line;
        // Most records hold no quote: their fields end at the separators and the line end, found
        // 64 bytes at a time. A record with a quote anywhere is read again field by field below.
        {
            std::size_t base = m_pos, start = m_pos;
            std::uint64_t m = stops(t, base, sep);
            bool plain = true, ended = false;
            for (;;) {
                while (m == 0 && base + 64 < n) {
                    base += 64;
                    m = stops(t, base, sep);
                }
                if (m == 0) break;  // the text ends within the record
                const std::size_t at = base + static_cast<std::size_t>(__builtin_ctzll(m));
                m &= m - 1;
                const char c = t[at];
                if (c == '"') {
                    plain = false;
                    break;
                }
                fields.push_back(trim(t.substr(start, at - start)));
                start = at + 1;
                if (c == '\n') {
                    ended = true;
                    break;
                }
            }
            if (plain) {
                if (!ended) {  // the record runs to the end of the text
                    if (!m_complete) {  // it may go on in the next block: read it again then
                        fields.clear();
                        return false;
                    }
                    fields.push_back(trim(t.substr(start)));
                    m_pos = n;
                } else {
                    m_pos = start;
                    ++m_line;
                }
                if (fields.size() == 1 && fields[0].empty()) continue;  // blank line
                return true;
            }
            fields.clear();
        }
        const std::size_t record_start = m_pos;
        bool at_end = false;  // the record ran to the end of the text (no line end)
        for (;;) {
            while (m_pos < n && t[m_pos] == ' ' && sep != ' ') ++m_pos;
            if (m_pos < n && t[m_pos] == '"') {
                const std::size_t start = ++m_pos;
                const std::size_t field_line = m_line;
                bool escaped = false, closed = false;
                std::size_t end = n;
                while (m_pos < n) {
                    const char c = t[m_pos];
                    if (c == '\n' && ++m_line - field_line >= max_quoted_lines) break;
                    if (c == '"') {
                        if (m_pos + 1 < n && t[m_pos + 1] == '"') {
                            escaped = true;
                            m_pos += 2;
                            continue;
                        }
                        end = m_pos++;
                        closed = true;
                        break;
                    }
                    ++m_pos;
                }
                const bool over_lines = m_line > field_line, left_open = over_lines && quote_left_open(closed, sep);
                if (over_lines && !left_open) m_quoted_line_ends += m_line - field_line;
                if (left_open) {
                    // A quote that takes in the lines after its own but does not close as a
                    // field's quotes do: a stray quote (an AIS name "ALPHA), which would take
                    // every row up to the next quote, or to the end of the file. Only its own
                    // line is lost: it is split as it stands, and said (quote_not_closed()).
                    const std::size_t line_end = t.find('\n', record_start);
                    fields.clear();
                    m_unescaped.clear();
                    for (std::size_t from = record_start;;) {
                        const std::size_t to = std::min(t.find(sep, from), line_end);
                        fields.push_back(trim(t.substr(from, to - from)));
                        if (to == line_end) break;
                        from = to + 1;
                    }
                    m_pos = line_end + 1;
                    m_line = m_record_line + 1;
                    m_quote_not_closed = true;
                    m_quoted_line_ends = 0;
                    return true;
                }
                std::string_view value = t.substr(start, end - start);
                if (escaped) {
                    std::string& s = m_unescaped.emplace_back();
                    s.reserve(value.size());
                    for (std::size_t i = 0; i < value.size(); ++i) {
                        s += value[i];
                        if (value[i] == '"') ++i;  // "" -> "
                    }
                    value = s;
                }
                fields.push_back(value);
                m_pos = field_end(t, m_pos, sep);  // text after the quote
            } else {
                const std::size_t start = m_pos;
                m_pos = field_end(t, m_pos, sep);
                fields.push_back(trim(t.substr(start, m_pos - start)));
            }
            if (m_pos >= n) {
                at_end = true;
                break;
            }
            if (t[m_pos] == sep) {
                ++m_pos;
                continue;
            }
            ++m_pos;  // '\n'
            ++m_line;
            break;
        }
        if (at_end && !m_complete) {  // it may go on in the next block: read it again then
            m_pos = record_start;
            m_line = m_record_line;
            fields.clear();
            m_unescaped.clear();
            m_quoted_line_ends = 0;
            return false;
        }
        if (fields.size() == 1 && fields[0].empty()) continue;  // blank line
        return true;
    }
    return false;
}

}  // namespace shoal::track
