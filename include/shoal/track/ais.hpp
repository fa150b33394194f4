#pragma once
/// AIS (ITU-R M.1371) from `!AIVDM` / `!AIVDO` sentences (any talker: AI, BS, AB, ...): the
/// 6-bit payload, the messages shoal reads, multi-sentence reassembly. A function over lines,
/// whatever brought them; the NMEA reader (nmea_reader.hpp) makes tracks of what it gives.
///
/// Messages decoded: 1, 2, 3 (class A position), 18, 19 (class B), 27 (long range), 5 and 24
/// parts A/B (static: name, ship type, A/B/C/D, draught). "Not available" values are unknown,
/// not values: position lon 181 / lat 91 (or anything outside the globe), SOG 102.3, COG 360,
/// heading 511, dimension 0, draught 0. Other message types are counted, not decoded.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <shoal/geo/point.hpp>
#include <shoal/track/track.hpp>

namespace shoal::track::ais {

/// Checks the `*hh` of an NMEA sentence or tag block (`sentence` starts with `$`, `!` or the
/// first character after `\`, and runs to the end of the line or the closing `\`). `body`
/// becomes the text between the first character and `*` (all of it when there is no `*`).
/// Returns false with `problem` ("bad checksum '*3F' (computed *2A)") when `*hh` is there and
/// wrong; true when it matches or is absent.
bool checksum_ok(std::string_view sentence, std::string_view& body, std::string& problem);

/// The bits of an armoured payload: 6 a character (`0`-`W`, `` ` ``-`w`), less the fill bits.
class Bits {
public:
    /// False (and empty) when a character is not armour or `fill` is not 0-5.
    bool assign(std::string_view payload, unsigned fill);
    std::size_t size() const noexcept { return m_size; }
    /// Bits [start, start + len) as an unsigned number (len <= 32; bits past the end read 0).
    std::uint32_t u(std::size_t start, std::size_t len) const noexcept;
    /// The same as two's complement.
    std::int32_t s(std::size_t start, std::size_t len) const noexcept;
    /// `chars` 6-bit ASCII characters from `start`, up to the first `@`, trailing blanks dropped.
    std::string text(std::size_t start, std::size_t chars) const;

private:
    std::vector<std::uint8_t> m_six;  ///< one 6-bit value a character
    std::size_t m_size = 0;
};

/// A decoded message. Fields a type does not carry keep their defaults.
struct Message {
    int type = 0;                          ///< 1-27
    int part = -1;                         ///< type 24: 0 part A, 1 part B
    std::uint32_t mmsi = 0;
    // Position reports (1, 2, 3, 18, 19, 27)
    std::optional<geo::LonLat> position;   ///< none when not available (lon 181, lat 91) or off the globe
    double sog_kn = NAN;                   ///< NAN when not available (102.3)
    double cog_deg = NAN;                  ///< NAN when not available (360)
    double heading_deg = NAN;              ///< NAN when not available (511)
    std::uint8_t nav_status = nav_status_unknown;  ///< 0-15 for 1, 2, 3 and 27
    int second = 60;                       ///< UTC second of the report (60-63: not available)
    // Static data (5, 19, 24)
    std::string name;                      ///< 5, 19, 24 A; empty when not given
    int ship_type = -1;                    ///< 5, 19, 24 B (0 = not available as sent); -1 when not carried
    std::optional<hull::Dimensions> dims;  ///< A, B, C, D when all four are > 0 (5, 19, 24 B)
    double draught_m = NAN;                ///< 5, when > 0

    bool is_position_report() const noexcept { return type == 1 || type == 2 || type == 3 || type == 18 || type == 19 || type == 27; }
};

enum class Decode : std::uint8_t { ok, skipped_type, bad };

/// Decodes one whole payload (the sentences' payloads joined). `skipped_type` for a type shoal
/// does not read (`out.type` and `out.mmsi` set); `bad` with `problem` for a payload that is
/// not armour, too short for its type, or a type 24 part other than A/B.
Decode decode(std::string_view payload, unsigned fill, Message& out, std::string& problem);

/// A message as the lines gave it.
struct Decoded {
    Message message;
    std::size_t line = 0;  ///< the line of its first sentence
    bool own = false;      ///< `!--VDO`: own ship
    /// From its first sentence's line: the tag block's `c:` (seconds, or milliseconds when
    /// > 1e11), else a receive time before the sentence (epoch seconds or milliseconds, ISO
    /// 8601); NAN when neither.
    double time_s = NAN;
};

/// Reads AIS sentences line by line: reassembles multi-sentence messages (by sequence id and
/// channel, or by the NMEA 4.10 tag-block group `g:n-N-id`), verifies checksums, decodes.
/// Every problem goes to the sink with its line ("bad checksum ...", "fragment 2 of 2 without
/// fragment 1", ...): the line is then skipped, nothing else is lost. What it holds between
/// lines is bounded (max_pending messages of at most 2048 payload characters and a message id of
/// at most 32), whatever the lines.
class LineDecoder {
public:
    /// Messages waiting for their next fragment at once, at most: one more is a half message
    /// of the oldest (real logs have a few: sequence ids 0-9 on two channels).
    static constexpr std::size_t max_pending = 1000;
    using Problem = std::function<void(std::size_t line, const std::string& what)>;
    explicit LineDecoder(Problem problem) : m_problem(std::move(problem)) {}

    /// True when `text` holds a `!--VDM`/`!--VDO` sentence (the decoder's business).
    static bool is_ais(std::string_view text) noexcept;
    /// One line (file line number `line`); true when it completes a message of a type shoal
    /// reads, then in `out`.
    bool line(std::string_view text, std::size_t line, Decoded& out);
    /// Says the messages still waiting for fragments (half messages) at the end of the input.
    void finish();
    /// Messages of types shoal does not read, by type.
    const std::map<int, std::size_t>& skipped_types() const noexcept { return m_skipped_types; }

private:
    struct Pending {
        std::string payload;
        int count = 0;
        int next = 0;  ///< the fragment expected next
        Decoded first;
        std::uint64_t serial = 0;  ///< its place in m_order
    };
    void erase(std::map<std::string, Pending>::iterator it);
    /// Says a message that will not be completed (a half message) and forgets it.
    void drop_half(std::map<std::string, Pending>::iterator it);
    Problem m_problem;
    std::map<std::string, Pending> m_pending;          ///< by group key
    std::map<std::uint64_t, std::string> m_order;      ///< the keys of m_pending, oldest first
    std::uint64_t m_serial = 0;
    std::map<int, std::size_t> m_skipped_types;
};

/// Every message of `text` (lines at `\n`) of the types shoal reads; problems into `problems`
/// as "line N: what" when given.
std::vector<Decoded> decode_lines(std::string_view text, std::vector<std::string>* problems = nullptr);

}  // namespace shoal::track::ais
