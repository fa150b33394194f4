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
/// What a reader says of a line whose quote did not close (CsvSplitter::quote_not_closed()),
/// before "; row skipped".
inline constexpr std::string_view quote_not_closed_message =
    "a quote (\") opens a field that does not close as a field's quotes do (it would take in the lines after it)";

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
    /// Whether the record last returned is a line whose quote did not close: a quoted field
    /// that went on over a line end and then did not end as a field ends (text after its
    /// closing quote), did not close by the end of the file, or went on over
    /// `max_quoted_lines` line ends. Such a line is split as it stands, its quotes text, so
    /// that the lines after it are read as their own records; a reader skips it and says so.
    bool quote_not_closed() const noexcept { return m_quote_not_closed; }
    /// Line ends inside the quoted fields of the record last returned (0 for most records).
    std::size_t quoted_line_ends() const noexcept { return m_quoted_line_ends; }
    /// The most line ends a quoted field may hold.
    static constexpr std::size_t max_quoted_lines = 64;
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
    bool m_quote_not_closed = false;
    std::size_t m_quoted_line_ends = 0;
    /// After a quoted field that went over a line end (m_pos past it): whether it left its
    /// quote open (see quote_not_closed()).
    bool quote_left_open(bool closed, char sep) const noexcept;
};

}  // namespace shoal::track
