#pragma once
/// `CsvSplitter`: CSV text into records, the one splitter of the CSV files shoal reads (tracks,
/// `track/csv_reader.hpp`; the poses of `shoal probe`, `io/pose_csv.hpp`).

#include <cstddef>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

namespace shoal::track {

/// Splits CSV text into records: RFC 4180 quoting (separators, quotes and line breaks inside
/// quotes), LF or CRLF line ends, a UTF-8 byte order mark skipped, blank lines skipped, blanks
/// around unquoted fields trimmed. The separator (`,` `;` or tab) is the one the first line
/// holds most often outside quotes.
///
/// A file may come in blocks: construct with its beginning (`complete` false; it must hold the
/// whole first line, see holds_first_line), take the records next() gives, then call more()
/// with the bytes from consumed() on followed by the next block, and so on; the records are
/// exactly those of the whole text at once.
class CsvSplitter {
public:
    explicit CsvSplitter(std::string_view text, bool complete = true);
    /// The separator found; '\0' when the first line holds none (not a CSV table).
    char separator() const noexcept { return m_sep; }
    /// The next record's fields (views valid until the next call); false at the end, or, when
    /// the text is not complete, when the next record may go on beyond it.
    bool next(std::vector<std::string_view>& fields);
    /// Whether a field of the record last returned held "" (its view then points into the
    /// splitter, valid only until the next call; the others point into the text).
    bool unescaped() const noexcept { return !m_unescaped.empty(); }
    /// 1-based line on which the record last returned starts.
    std::size_t line() const noexcept { return m_record_line; }
    /// Bytes of the current text taken by the records returned so far.
    std::size_t consumed() const noexcept { return m_skipped + m_pos; }
    /// Continues with `text`: the current text from consumed() on, then more of the file.
    void more(std::string_view text, bool complete);
    /// True when `text` (a file's beginning) holds the line the separator is found on.
    static bool holds_first_line(std::string_view text) noexcept;

private:
    std::string_view m_text;
    bool m_complete = true;
    std::size_t m_skipped = 0;  // a byte order mark skipped at the start of the first text
    std::size_t m_pos = 0;
    std::size_t m_line = 1;
    std::size_t m_record_line = 0;
    char m_sep = ',';
    std::deque<std::string> m_unescaped;  // fields that held "" (a deque: views stay valid)
};

}  // namespace shoal::track
