// The pose file of `shoal probe`, split by the track reader's CsvSplitter: against a line-by-line
// reference on many random files with every kind of line the format allows or refuses, and on
// hand-made cases.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <shoal/track/csv_splitter.hpp>
#include <shoal/io/pose_csv.hpp>
#include <shoal/util/error.hpp>

namespace shoal::io {
namespace {

// ---- the reference: line by line (std::getline, one std::string per field), the fields split
// as RFC 4180 and the track reader split them: one separator, the one of ',', ';' and tab the
// first row holds most outside quotes (a quote anywhere turns the count on or off); a field whose
// first character but blanks is a quote runs to the closing quote ("" in it is a quote), what
// follows it up to the separator dropped; any other field trimmed of blanks, its quotes kept.
// (The files made below hold no separator or line end inside quotes.) ----

bool is_comment_or_blank(const std::string& line) {
    const auto lead = line.find_first_not_of(" \t");
    return lead == std::string::npos || line[lead] == '#';
}

char ref_separator(const std::vector<std::string>& lines, std::size_t from) {
    std::size_t commas = 0, semicolons = 0, tabs = 0;
    bool quoted = false;
    for (std::size_t i = from; i < lines.size(); ++i) {
        // A comment line below the first row counts as empty (one whose quote is open goes on).
        if (i == from || !is_comment_or_blank(lines[i]) || lines[i].find_first_not_of(" \t") == std::string::npos)
            for (char c : lines[i]) {
                if (c == '"') quoted = !quoted;
                if (quoted) continue;
                commas += c == ',';
                semicolons += c == ';';
                tabs += c == '\t';
            }
        if (!quoted) break;
    }
    if (commas == 0 && semicolons == 0 && tabs == 0) return ',';
    if (commas >= semicolons && commas >= tabs) return ',';
    return semicolons >= tabs ? ';' : '\t';
}

std::vector<std::string> ref_split(const std::string& line, char sep) {
    std::vector<std::string> out;
    std::size_t i = 0;
    for (;;) {
        while (i < line.size() && line[i] == ' ') ++i;
        std::string field;
        if (i < line.size() && line[i] == '"') {
            for (++i; i < line.size(); ++i) {
                if (line[i] == '"') {
                    if (i + 1 < line.size() && line[i + 1] == '"') {
                        field += '"';
                        ++i;
                        continue;
                    }
                    ++i;
                    break;
                }
                field += line[i];
            }
            while (i < line.size() && line[i] != sep) ++i;
        } else {
            const std::size_t start = i;
            while (i < line.size() && line[i] != sep) ++i;
            field = line.substr(start, i - start);
            const auto b = field.find_first_not_of(" \t");
            const auto e = field.find_last_not_of(" \t");
            field = b == std::string::npos ? "" : field.substr(b, e - b + 1);
        }
        out.push_back(field);
        if (i >= line.size()) break;
        ++i;  // the separator
    }
    return out;
}

bool ref_double(const std::string& s, double& v, char sep = ',') {
    if (s.empty()) return false;
    const char* first = s.data();
    if (*first == '+') ++first;
    const auto [p, ec] = std::from_chars(first, s.data() + s.size(), v);
    if (ec == std::errc() && p == s.data() + s.size()) return true;
    // A decimal comma with ';' or tab separators: one comma, read as a point.
    if (sep == ',' || std::count(s.begin(), s.end(), ',') != 1) return false;
    std::string dotted = s;
    dotted[dotted.find(',')] = '.';
    return ref_double(dotted, v);
}

PoseFile reference(const std::string& text, const std::string& name) {
    PoseFile out;
    int col_lat = 0, col_lon = 1, col_hdg = 2;
    std::size_t header_fields = 0;
    bool first = true;
    std::istringstream in(text);
    std::string line;
    std::size_t lineno = 0;
    auto bad = [&](const std::string& why) {
        ++out.skipped;
        if (out.errors.size() < 10) out.errors.push_back(name + " line " + std::to_string(lineno) + ": " + why + "; row skipped");
    };
    std::vector<std::string> lines;
    while (std::getline(in, line)) {
        if (lines.empty() && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(line);
    }
    std::size_t first_row = 0;
    while (first_row < lines.size() && is_comment_or_blank(lines[first_row])) ++first_row;
    const char sep = ref_separator(lines, first_row);
    for (const std::string& l : lines) {
        line = l;
        ++lineno;
        if (is_comment_or_blank(line)) continue;
        const std::vector<std::string> f = ref_split(line, sep);
        if (first) {
            first = false;
            if (std::any_of(line.begin(), line.end(), [](unsigned char c) { return std::isalpha(c) && c != 'e' && c != 'E'; })) {
                col_lat = col_lon = col_hdg = -1;
                header_fields = f.size();
                for (int i = 0; i < static_cast<int>(f.size()); ++i) {
                    std::string h = f[static_cast<std::size_t>(i)];
                    for (char& c : h) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
                    if (h == "lat" || h == "latitude") col_lat = i;
                    else if (h == "lon" || h == "lng" || h == "long" || h == "longitude") col_lon = i;
                    else if (h == "heading" || h == "hdg" || h == "heading_deg") col_hdg = i;
                }
                if (col_lat < 0 || col_lon < 0 || col_hdg < 0)
                    throw InputError(name + " line 1: the header needs columns lat, lon and heading (got '" + line + "')");
                continue;
            }
        }
        const int need = std::max({col_lat, col_lon, col_hdg});
        if (static_cast<int>(f.size()) <= need) {
            bad("expected at least " + std::to_string(need + 1) + " fields, got " + std::to_string(f.size()));
            continue;
        }
        const std::size_t known = header_fields > 0 ? header_fields : 3;
        bool extra = false;
        for (std::size_t i = known; i < f.size(); ++i) extra = extra || f[i].find_first_not_of(" \t") != std::string::npos;
        if (extra) {
            bad("has " + std::to_string(f.size()) + " fields, " + (header_fields > 0 ? "the header " : "a row without a header ") +
                std::to_string(known) + (sep == ',' ? " (a decimal comma in a comma-separated file?)" : " (a separator inside an unquoted field?)"));
            continue;
        }
        PoseRow r;
        r.line = lineno;
        const std::string& slat = f[static_cast<std::size_t>(col_lat)];
        const std::string& slon = f[static_cast<std::size_t>(col_lon)];
        const std::string& shdg = f[static_cast<std::size_t>(col_hdg)];
        if (!ref_double(slat, r.lat, sep) || !std::isfinite(r.lat) || std::fabs(r.lat) > 90) {
            bad("latitude '" + slat + "' is not a number in [-90, 90]");
            continue;
        }
        if (!ref_double(slon, r.lon, sep) || !std::isfinite(r.lon) || std::fabs(r.lon) > 180) {
            bad("longitude '" + slon + "' is not a number in [-180, 180]");
            continue;
        }
        if (!ref_double(shdg, r.heading_deg, sep) || !std::isfinite(r.heading_deg)) {
            bad("heading '" + shdg + "' is not a number of degrees");
            continue;
        }
        if (r.heading_deg == 511) {  // AIS's "not available"
            bad("heading 511 is AIS's \"not available\": probe needs the ship's heading");
            continue;
        }
        r.heading_deg = std::fmod(r.heading_deg, 360.0) + 0.0;  // (+ 0.0: -0 and -360 are 0, not "-0.0")
        if (r.heading_deg < 0) r.heading_deg += 360.0;
        out.poses.push_back(r);
    }
    if (first) throw InputError(name + ": empty file (no header and no poses)");
    return out;
}

// ---- random files ----

std::string random_file(std::mt19937_64& rng) {
    auto pick = [&](std::initializer_list<const char*> l) { return std::string(l.begin()[rng() % l.size()]); };
    std::string t;
    if (rng() % 8 == 0) t += "\xEF\xBB\xBF";
    if (rng() % 2) t += pick({"lat,lon,heading", "Latitude;Longitude;HDG", "heading,lat,lon", "x,lat,lon,heading_deg", "lat,lon",
                              "\"lat\",\"lon\",\"heading\"", " lat\t lon \theading "}) + pick({"\n", "\r\n"});
    // Mostly one separator a file (a field now and then with another).
    const std::string sep = pick({",", ";", "\t", ", "});
    const int rows = static_cast<int>(rng() % 40);
    for (int k = 0; k < rows; ++k) {
        std::string line;
        // Mostly three fields (a header's fourth column, or a trailing separator, now and then).
        const int fields = rng() % 3 ? 3 : 1 + static_cast<int>(rng() % 5);
        for (int i = 0; i < fields; ++i) {
            if (i) line += rng() % 10 ? sep : pick({",", ";", "\t", ", "});
            line += pick({"60.1", "-59.25", "+24.5", "1e1", "  12.5 ", "\"33.3\"", "3\"4", "", "abc", "nan", "inf", "95", "-181",
                          "720.5", "511", "\"1,5\"", "2,25", "-45", "-0", "-360", "0x10", "1.5e400", "7.", ".5", "#", " "});
        }
        if (rng() % 10 == 0) line = pick({"", "   ", "# a comment", "\t", "  # indented comment"});
        t += line;
        if (k + 1 < rows || rng() % 2) t += pick({"\n", "\r\n", "\n\n"});
    }
    return t;
}

void expect_same(const std::string& text) {
    PoseFile want, got;
    std::string want_error, got_error;
    try {
        want = reference(text, "f.csv");
    } catch (const InputError& e) {
        want_error = e.what();
    }
    try {
        got = parse_pose_csv(text, "f.csv");
    } catch (const InputError& e) {
        got_error = e.what();
    }
    ASSERT_EQ(got_error, want_error) << text;
    ASSERT_EQ(got.poses.size(), want.poses.size()) << text;
    for (std::size_t i = 0; i < got.poses.size(); ++i) {
        EXPECT_EQ(got.poses[i].line, want.poses[i].line);
        // Bit for bit (NaN never gets here: rows with one are skipped).
        EXPECT_EQ(got.poses[i].lat, want.poses[i].lat);
        EXPECT_EQ(got.poses[i].lon, want.poses[i].lon);
        EXPECT_EQ(got.poses[i].heading_deg, want.poses[i].heading_deg);
    }
    EXPECT_EQ(got.skipped, want.skipped) << text;
    EXPECT_EQ(got.errors, want.errors) << text;
}

TEST(PoseCsv, SameAsTheLineByLineReferenceOnRandomFiles) {
    std::mt19937_64 rng(15);
    std::size_t poses = 0, skipped = 0;
    for (int k = 0; k < 5000; ++k) {
        const std::string text = random_file(rng);
        expect_same(text);
        if (HasFatalFailure()) return;
        try {
            const PoseFile f = parse_pose_csv(text, "f.csv");
            poses += f.poses.size();
            skipped += f.skipped;
        } catch (const InputError&) {
        }
    }
    EXPECT_GT(poses, 1500u) << "too few good rows to mean anything";
    EXPECT_GT(skipped, 2000u) << "too few bad rows to mean anything";
}

TEST(PoseCsv, HandMadeCases) {
    const PoseFile f = parse_pose_csv("\xEF\xBB\xBFlat;lon;heading\r\n\"60.5\" ; 24.25;-90\r\n\n# c\n61;25;725", "p.csv");
    ASSERT_EQ(f.poses.size(), 2u);
    EXPECT_EQ(f.poses[0].line, 2u);
    EXPECT_EQ(f.poses[0].lat, 60.5);
    EXPECT_EQ(f.poses[0].lon, 24.25);
    EXPECT_EQ(f.poses[0].heading_deg, 270.0);
    EXPECT_EQ(f.poses[1].line, 5u);
    EXPECT_EQ(f.poses[1].heading_deg, 5.0);
    const PoseFile z = parse_pose_csv("60,24,-0\n60,24,-360\n", "z.csv");  // (written back as "0.0", not "-0.0")
    ASSERT_EQ(z.poses.size(), 2u);
    EXPECT_FALSE(std::signbit(z.poses[0].heading_deg));
    EXPECT_FALSE(std::signbit(z.poses[1].heading_deg));
    const PoseFile b = parse_pose_csv("60,24\n60,x,1\n", "p.csv");
    EXPECT_TRUE(b.poses.empty());
    ASSERT_EQ(b.errors.size(), 2u);
    EXPECT_EQ(b.errors[0], "p.csv line 1: expected at least 3 fields, got 2; row skipped");
    EXPECT_EQ(b.errors[1], "p.csv line 2: longitude 'x' is not a number in [-180, 180]; row skipped");
    EXPECT_THROW(parse_pose_csv("lat,lon\n1,2\n", "p.csv"), InputError);
    // More fields than there are columns, one not blank: a bad row (before: "60,24,24,9,90",
    // decimal commas, was the pose 60, 24, 24); a trailing separator is nothing.
    const PoseFile x = parse_pose_csv("60,24,24,9,90\n60.05,24.9,90,extra\n60.05,24.9,90, \n", "x.csv");
    ASSERT_EQ(x.poses.size(), 1u);
    EXPECT_EQ(x.poses[0].line, 3u);
    ASSERT_EQ(x.errors.size(), 2u);
    EXPECT_EQ(x.errors[0], "x.csv line 1: has 5 fields, a row without a header 3 (a decimal comma in a comma-separated file?); row skipped");
    EXPECT_EQ(x.errors[1], "x.csv line 2: has 4 fields, a row without a header 3 (a decimal comma in a comma-separated file?); row skipped");
    const PoseFile y = parse_pose_csv("lat;lon;heading;t\n60,5;24;90;1;2\n60,5;24;90;1\n", "y.csv");
    ASSERT_EQ(y.poses.size(), 1u);
    ASSERT_EQ(y.errors.size(), 1u);
    EXPECT_EQ(y.errors[0], "y.csv line 2: has 5 fields, the header 4 (a separator inside an unquoted field?); row skipped");
    // Quotes are honoured: a separator inside them does not split, "" is a quote; a comment
    // line may hold a quote, and the separator is found on the first row, not on a comment.
    // A quote that does not close (it would take in the rows after it): that row alone.
    const PoseFile o = parse_pose_csv("lat,lon,heading\n60,24,1\n60,24,\"9\n61,25,2\n62,26,3\n", "o.csv");
    ASSERT_EQ(o.poses.size(), 3u);
    EXPECT_EQ(o.poses[1].line, 4u);
    EXPECT_EQ(o.poses[2].lat, 62);
    ASSERT_EQ(o.errors.size(), 1u);
    EXPECT_EQ(o.errors[0], "o.csv line 3: " + std::string(shoal::track::quote_not_closed_message) + "; row skipped");
    const PoseFile q = parse_pose_csv("# a \"comment\n\n\"lat\";\"lon\";heading\n60;\"24.5\";\"9\"\"\"\n\"60,5\";24;1\n", "q.csv");
    // With ';' a decimal comma is read (as in a track file): "60,5" is 60.5.
    ASSERT_EQ(q.poses.size(), 1u);
    EXPECT_EQ(q.poses[0].lat, 60.5);
    ASSERT_EQ(q.errors.size(), 1u) << q.errors.size();
    EXPECT_EQ(q.errors[0], "q.csv line 4: heading '9\"' is not a number of degrees; row skipped");
    const PoseFile c = parse_pose_csv("lat,lon,heading\n\"60,5\",24,1\n", "c.csv");  // with ',' it is not
    ASSERT_EQ(c.errors.size(), 1u);
    EXPECT_EQ(c.errors[0], "c.csv line 2: latitude '60,5' is not a number in [-90, 90]; row skipped");
    const PoseFile t = parse_pose_csv("lat\tlon\theading\n60,25\t24,5\t90,5\n", "t.csv");
    ASSERT_EQ(t.poses.size(), 1u);
    EXPECT_EQ(t.poses[0].lon, 24.5);
    EXPECT_EQ(t.poses[0].heading_deg, 90.5);
    // AIS's "not available" heading is not a heading (the track reader's rule); any other
    // number of degrees is taken modulo 360, 871 too.
    EXPECT_THROW(parse_pose_csv("", "e.csv"), InputError);
    EXPECT_THROW(parse_pose_csv("\n  \n# only a comment\n", "e.csv"), InputError);
    EXPECT_TRUE(parse_pose_csv("lat,lon,heading\n", "e.csv").poses.empty());
    const PoseFile h = parse_pose_csv("lat,lon,heading\n60,24,511\n60,24,511.0\n60,24,871\n", "h.csv");
    ASSERT_EQ(h.poses.size(), 1u);
    EXPECT_EQ(h.poses[0].line, 4u);
    EXPECT_EQ(h.poses[0].heading_deg, 151.0);
    ASSERT_EQ(h.errors.size(), 2u);
    EXPECT_EQ(h.errors[0], "h.csv line 2: heading 511 is AIS's \"not available\": probe needs the ship's heading; row skipped");
    EXPECT_EQ(h.errors[1], "h.csv line 3: heading 511 is AIS's \"not available\": probe needs the ship's heading; row skipped");
}

}  // namespace
}  // namespace shoal::io
