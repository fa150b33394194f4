// Tests of reading inputs through GDAL's virtual file layer (detail/input_file.hpp, issue 19 and
// issue 14): compressed files, virtual paths, pipes and FIFOs, and the read limits.
//
// The independent answer for every compressed or streamed input is the same file read plain
// from disk; the zips and gzips are made here from tests/data files by the `zip` and `gzip`
// tools (not by GDAL), the FIFOs written by a thread of the test.

#include <shoal/track/reader.hpp>
#include <shoal/track/csv_reader.hpp>
#include <shoal/track/nmea_reader.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "util/input_file.hpp"
#include "track/stream_readers.hpp"
#include "test_support.hpp"
#include <shoal/hull/hull.hpp>
#include <shoal/util/error.hpp>

namespace {

namespace fs = std::filesystem;
using shoal::InputError;
using shoal::test::data_path;
using shoal::test::TempDir;
using shoal::track::read_tracks;
using shoal::track::TrackFile;
using testing::HasSubstr;
using testing::ThrowsMessage;

bool have_tool(const std::string& tool) { return std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) == 0; }

void run(const std::string& command) { ASSERT_EQ(std::system(command.c_str()), 0) << command; }

void write(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
}

std::string slurp(const std::string& path) {
    const std::vector<char> b = shoal::test::read_bytes(path);
    return {b.begin(), b.end()};
}

/// The same counts of rows, skipped rows and duplicates.
void expect_same_counts(const shoal::track::ReadReport& got, const shoal::track::ReadReport& want) {
    EXPECT_EQ(got.rows, want.rows);
    EXPECT_EQ(got.skipped, want.skipped);
    EXPECT_EQ(got.duplicates, want.duplicates);
}

/// The same tracks (ids, names, dimensions, every fix) and the same counts.
void expect_same(const TrackFile& got, const TrackFile& want) {
    EXPECT_EQ(got.format, want.format);
    expect_same_counts(got.report, want.report);
    ASSERT_EQ(got.tracks.size(), want.tracks.size());
    for (std::size_t i = 0; i < got.tracks.size(); ++i) {
        const auto &g = got.tracks[i], &w = want.tracks[i];
        EXPECT_EQ(g.id, w.id);
        EXPECT_EQ(g.name, w.name);
        EXPECT_EQ(g.dims, w.dims);
        ASSERT_EQ(g.fixes.size(), w.fixes.size()) << g.id;
        for (std::size_t k = 0; k < g.fixes.size(); ++k) {
            EXPECT_EQ(g.fixes[k].time_s, w.fixes[k].time_s);
            EXPECT_EQ(g.fixes[k].position.lat, w.fixes[k].position.lat);
            EXPECT_EQ(g.fixes[k].position.lon, w.fixes[k].position.lon);
            EXPECT_EQ(g.fixes[k].line, w.fixes[k].line);
        }
    }
}

/// Writes `bytes` into the FIFO `path` from a thread (joined by the destructor).
class FifoWriter {
public:
    FifoWriter(const std::string& path, std::string bytes) {
        if (::mkfifo(path.c_str(), 0600) != 0) throw std::runtime_error("mkfifo " + path);
        m_thread = std::thread([path, bytes = std::move(bytes)] {
            std::ofstream out(path, std::ios::binary);
            out << bytes;
        });
    }
    ~FifoWriter() { m_thread.join(); }
    FifoWriter(const FifoWriter&) = delete;
    FifoWriter& operator=(const FifoWriter&) = delete;

private:
    std::thread m_thread;
};

const std::string dma = "tracks/dma_export_dk_head200.csv";
const std::string nmea = "tracks/plaka_head400.log";
const std::string gpx = "tracks/track_and_route.gpx";

TEST(Input, ZipOfOneCsvReadsAsTheCsv) {
    if (!have_tool("zip")) GTEST_SKIP() << "no zip tool";
    TempDir dir;
    const std::string zip = dir.file("day.zip");
    run("zip -q -j " + zip + " " + data_path(dma));
    const TrackFile want = read_tracks(data_path(dma));
    expect_same(read_tracks(zip), want);
    expect_same(read_tracks("/vsizip/" + zip + "/" + fs::path(dma).filename().string()), want);
    // Named by its magic bytes, not its name.
    fs::copy_file(zip, dir.file("day.csv"));
    expect_same(read_tracks(dir.file("day.csv")), want);
    EXPECT_EQ(shoal::track::expand_inputs({zip}), std::vector<std::string>{zip});
}

TEST(Input, ZipOfSeveralFilesIsAFolderOfThem) {
    if (!have_tool("zip")) GTEST_SKIP() << "no zip tool";
    TempDir dir;
    const std::string zip = dir.file("both.zip");
    run("zip -q -j " + zip + " " + data_path(dma) + " " + data_path(nmea) + " " + data_path("tracks/gpsd_nl_vessels.csv"));
    const std::vector<std::string> inputs = shoal::track::expand_inputs({zip});
    const std::vector<std::string> want{"/vsizip/" + zip + "/dma_export_dk_head200.csv", "/vsizip/" + zip + "/plaka_head400.log"};
    ASSERT_EQ(inputs, want) << "the vessels file is left out, as in a folder";
    expect_same(read_tracks(inputs[0]), read_tracks(data_path(dma)));
    // The log's own track is named after the file's stem, which the member keeps.
    expect_same(read_tracks(inputs[1]), read_tracks(data_path(nmea)));
    EXPECT_THAT([&] { read_tracks(zip); }, ThrowsMessage<InputError>(HasSubstr("a zip of 3 files: name one")));
    // On a pipe the member names cannot be given: the message says what to do instead (before:
    // "name one (/vsizip/FILE/...)", a path that does not exist for a pipe).
    const std::string fifo = dir.file("zip.fifo");
    FifoWriter writer(fifo, slurp(zip));
    EXPECT_THAT([&] { read_tracks(fifo); },
                ThrowsMessage<InputError>(HasSubstr("a zip of 3 files on a pipe or standard input: shoal reads one file from a stream; "
                                                    "save the zip to a file and give that (its files are read as a folder), or pipe "
                                                    "one file of it (unzip -p ZIP dma_export_dk_head200.csv)")));
}

// Issue 39: a corrupt zip said "a zip file without any file in it", as if it were empty. A zip
// cut short (its directory, at the end, lost) is said to be unreadable; a zip made empty by the
// zip tool itself is said to be empty; both name the file.
TEST(Input, CorruptZipIsSaidCorruptAndAnEmptyOneEmpty) {
    if (!have_tool("zip")) GTEST_SKIP() << "no zip tool";
    TempDir dir;
    const std::string zip = dir.file("day.zip");
    run("zip -q -j " + zip + " " + data_path(dma));
    const std::string whole = slurp(zip);
    const std::string cut = dir.file("cut.zip");
    write(cut, whole.substr(0, whole.size() / 2));  // a download stopped half-way
    EXPECT_THAT([&] { read_tracks(cut); },
                ThrowsMessage<InputError>(HasSubstr(cut + ": cannot read (not a readable zip file: it starts like a zip but its directory")));
    // Never called empty (the message before).
    EXPECT_THAT([&] { read_tracks(cut); }, ThrowsMessage<InputError>(testing::Not(HasSubstr("empty"))));
    // The empty zip the zip tool writes when its only file is deleted: 22 bytes, an end record.
    const std::string empty = dir.file("empty.zip");
    run("cp " + zip + " " + empty + " && zip -q -d " + empty + " " + fs::path(dma).filename().string());
    ASSERT_EQ(fs::file_size(empty), 22u) << "zip -d of the only file leaves the end record alone";
    EXPECT_THAT([&] { read_tracks(empty); }, ThrowsMessage<InputError>(HasSubstr(empty + ": cannot read (an empty zip file (no file in it))")));
}

TEST(Input, GzipReadsAsThePlainFileWhateverItsName) {
    TempDir dir;
    for (const std::string& name : {std::string("day.csv.gz"), std::string("day.csv"), std::string("day.dat")}) {
        run("gzip -c " + data_path(dma) + " > " + dir.file(name));
        expect_same(read_tracks(dir.file(name)), read_tracks(data_path(dma)));
    }
    run("gzip -c " + data_path(gpx) + " > " + dir.file("t.gpx.gz"));
    expect_same(read_tracks(dir.file("t.gpx.gz")), read_tracks(data_path(gpx)));
    expect_same(read_tracks("/vsigzip/" + dir.file("day.dat")), read_tracks(data_path(dma)));
}

TEST(Input, FoldersListZipAndGzipFiles) {
    TempDir dir;
    run("gzip -c " + data_path(dma) + " > " + dir.file("a.csv.gz"));
    write(dir.file("b.csv"), slurp(data_path(dma)));
    write(dir.file("notes.md"), "not a track\n");
    EXPECT_EQ(shoal::track::expand_inputs({dir.path().string()}),
              (std::vector<std::string>{dir.file("a.csv.gz"), dir.file("b.csv")}));
}

TEST(Input, FifoIsReadOnceAndWhole) {
    TempDir dir;
    for (const std::string& rel : {dma, nmea, gpx, std::string("tracks/points.geojson")}) {
        fs::create_directory(dir.path() / "fifo");  // the same name: tracks are named after it
        const std::string fifo = (dir.path() / "fifo" / fs::path(rel).filename()).string();
        TrackFile got;
        {
            FifoWriter writer(fifo, slurp(data_path(rel)));
            got = read_tracks(fifo);
        }
        expect_same(got, read_tracks(data_path(rel)));
    }
}

TEST(Input, GzipOnAFifoReadsAsThePlainFile) {
    TempDir dir;
    run("gzip -c " + data_path(dma) + " > " + dir.file("day.csv.gz"));
    TrackFile got;
    {
        FifoWriter writer(dir.file("fifo"), slurp(dir.file("day.csv.gz")));
        got = read_tracks(dir.file("fifo"));
    }
    expect_same(got, read_tracks(data_path(dma)));
}

TEST(Input, FifoIsListedWithoutBeingOpened) {
    TempDir dir;
    const std::string fifo = dir.file("f.csv");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // No writer: opening it would block; expand_inputs must not.
    EXPECT_EQ(shoal::track::expand_inputs({fifo, "-"}), (std::vector<std::string>{fifo, "-"}));
}

TEST(Input, DevZeroIsRefusedAfterTheSniffLimit) {
    EXPECT_THAT([] { read_tracks("/dev/zero"); }, ThrowsMessage<InputError>(HasSubstr("/dev/zero: not a track format")));
    EXPECT_THAT([] { shoal::hull::Hull::load("/dev/zero"); },
                ThrowsMessage<InputError>(HasSubstr("/dev/zero: larger than 1 MiB, the most a ship file may be")));
}

/// Fields a reader gives, every one (NaN equal to NaN).
bool same_number(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

void expect_same_packed(const shoal::track::PackedTrackFile& got, const shoal::track::PackedTrackFile& want) {
    expect_same_counts(got.report, want.report);
    EXPECT_EQ(got.report.reordered, want.report.reordered);
    EXPECT_EQ(got.report.messages, want.report.messages);
    ASSERT_EQ(got.tracks.size(), want.tracks.size());
    for (std::size_t i = 0; i < got.tracks.size(); ++i) {
        const auto &g = got.tracks[i], &w = want.tracks[i];
        SCOPED_TRACE("track " + w.id);
        EXPECT_EQ(g.id, w.id);
        EXPECT_EQ(g.name, w.name);
        EXPECT_EQ(g.dims, w.dims);
        EXPECT_EQ(g.dims_source, w.dims_source);
        EXPECT_TRUE(same_number(g.draught_m, w.draught_m));
        EXPECT_EQ(g.ship_type, w.ship_type);
        EXPECT_EQ(g.role, w.role);
        ASSERT_EQ(g.size(), w.size());
        for (std::size_t k = 0; k < g.size(); ++k) {
            const shoal::track::Fix a = g.fix(k), b = w.fix(k);
            EXPECT_TRUE(same_number(a.time_s, b.time_s) && a.position.lat == b.position.lat && a.position.lon == b.position.lon &&
                        same_number(a.heading_deg, b.heading_deg) && same_number(a.cog_deg, b.cog_deg) && same_number(a.sog_kn, b.sog_kn) &&
                        a.nav_status == b.nav_status && a.line == b.line)
                << "fix " << k << " line " << b.line;
        }
    }
}

TEST(Input, ACsvReadByTwoThreadsIsTheCsvReadByOne) {
    // Random files of everything a row can hold or lack (quoted and escaped fields, line breaks
    // inside quotes, CRLF, blank lines, bad fields of every column, times of day before and
    // after a vessel's first date, rows over the line limit), read in blocks of 997 bytes to
    // 1 MiB by one thread and by two (ReadOptions::threads): the same tracks, fixes, lines and
    // messages as the whole text read at once.
    std::mt19937_64 rng(15);
    auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
    TempDir dir;
    for (int file = 0; file < 6; ++file) {
        std::string text = file % 2 ? "\xEF\xBB\xBF" : "";
        text += "MMSI,time,lat,lon,SOG,COG,Heading,Status,VesselName,A,B,C,D,Draught,ShipType,role\n";
        const std::vector<std::string> ids = {"211000001", "\"211000002\"", "\"21\"\"3\"", "0211", "abc", "211000001 ", "", "999"};
        const std::vector<std::string> numbers = {"59.5", "-0.0", "12", "1e1", "59.123456789012345678", "abc", "", " 7.25 ", "\"8.5\"", "0.1e-2",
                                                  "5.", ".5", "+3.5", "1,5", "nan", "inf", "91", "-181"};
        const std::vector<std::string> names = {"NAME", "\"A, B\"", "\"line\nbreak\"", "\"say \"\"hi\"\"\"", "", "\xE9t\xE9"};
        const std::size_t rows = 300 + pick(3000);
        for (std::size_t r = 0; r < rows; ++r) {
            const std::size_t kind = pick(40);
            const std::string end = pick(5) == 0 ? "\r\n" : "\n";
            if (kind == 0) {
                text += end;  // blank line
                continue;
            }
            if (kind == 1) {
                text += ids[pick(ids.size())] + ",2024-05-01T10:00:00Z" + end;  // too few fields
                continue;
            }
            std::string time = pick(6) == 0 ? "10:" + std::to_string(10 + pick(50)) + ":00" : "2024-05-01T" + std::to_string(10 + pick(10)) + ":" + std::to_string(10 + pick(50)) + ":" + std::to_string(10 + pick(50)) + "Z";
            if (kind == 2) time = pick(2) ? "" : "yesterday";
            std::string lat = pick(8) ? std::to_string(59.0 + static_cast<double>(pick(1000000)) / 1e6) : numbers[pick(numbers.size())];
            std::string lon = pick(8) ? std::to_string(24.0 + static_cast<double>(pick(1000000)) / 1e6) : numbers[pick(numbers.size())];
            auto num = [&] { return pick(3) ? std::to_string(pick(3600) / 10.0) : numbers[pick(numbers.size())]; };
            std::string row = ids[pick(ids.size())] + "," + time + "," + lat + "," + lon + "," + num() + "," + num() + "," + num() + "," +
                              std::to_string(pick(16)) + "," + names[pick(names.size())] + "," + num() + "," + num() + "," + num() + "," + num() +
                              "," + num() + "," + std::to_string(pick(90)) + "," + (pick(30) ? "target" : pick(2) ? "own" : "neither");
            if (kind == 3 && file < 3 && pick(10) == 0) row += "," + std::string((1 << 20) + pick(3000), 'x');  // over the line limit
            text += row + end;
        }
        if (pick(2)) text += ids[0] + ",2024-05-01T23:00:00Z,59.5,24.5,1,2,3,0,LAST,1,2,3,4,5,70,target";  // no line end
        const std::string path = dir.file("f" + std::to_string(file) + ".csv");
        write(path, text);
        shoal::track::ReadOptions options;
        options.role_column = "role";
        options.max_messages = 1000;
        const shoal::track::PackedTrackFile want = shoal::track::read_csv_text_packed(text, path, options);
        ASSERT_GT(want.tracks.size(), 2u);
        ASSERT_GT(want.report.skipped, 5u);
        // (Small blocks only without rows over the limit: each block would read such a row again.)
        const std::vector<std::size_t> blocks = file < 3 ? std::vector<std::size_t>{65536, std::size_t{1} << 20} : std::vector<std::size_t>{997, 4096, std::size_t{1} << 20};
        for (const std::size_t block : blocks) {
            for (const unsigned threads : {1u, 2u}) {
                SCOPED_TRACE("file " + std::to_string(file) + ", block " + std::to_string(block) + ", threads " + std::to_string(threads));
                options.threads = threads;
                shoal::detail::InputFile in(path);
                expect_same_packed(shoal::track::detail::read_csv_stream(in, {}, false, options, block), want);
            }
        }
    }
}

TEST(Input, ACsvReadByTwoThreadsStopsAtABadHeaderAsOneDoes) {
    TempDir dir;
    write(dir.file("bad.csv"), "a,b,c\n" + std::string(3 << 20, 'x'));
    shoal::track::ReadOptions options;
    options.threads = 2;
    shoal::detail::InputFile in(dir.file("bad.csv"));
    EXPECT_THAT([&] { shoal::track::detail::read_csv_stream(in, {}, false, options, 4096); },
                ThrowsMessage<InputError>(HasSubstr("the header has no time")));
}

TEST(Input, CsvLineOverTheLimitIsABadRow) {
    TempDir dir;
    const std::string header = "mmsi,timestamp,lat,lon,note\n";
    const std::string a = "1,2024-05-01T10:00:00Z,50.1,-1.2\n", b = "1,2024-05-01T10:01:00Z,50.2,-1.2\n";
    // Every field of the long row is fine (the last a note no one reads).
    const std::string huge = "1,2024-05-01T10:00:30Z,50.15,-1.2," + std::string(3 << 20, '7') + "\n";
    write(dir.file("long.csv"), header + a + huge + b);
    write(dir.file("short.csv"), header + a + "\n" + b);  // the independent answer: the line gone
    const TrackFile got = read_tracks(dir.file("long.csv")), want = read_tracks(dir.file("short.csv"));
    EXPECT_EQ(got.report.rows, 3u);
    EXPECT_EQ(got.report.skipped, 1u);
    ASSERT_EQ(got.report.messages.size(), 1u);
    EXPECT_THAT(got.report.messages[0], HasSubstr("long.csv line 3: longer than 1 MiB, the longest line shoal reads; row skipped"));
    ASSERT_EQ(got.tracks.size(), 1u);
    EXPECT_EQ(got.tracks[0].fixes.size(), want.tracks[0].fixes.size());
    EXPECT_EQ(got.tracks[0].fixes.back().line, want.tracks[0].fixes.back().line);
    // A first line without end is refused at the limit, not read forever.
    write(dir.file("commas.csv"), std::string(17 << 20, ','));
    EXPECT_THAT([&] { read_tracks(dir.file("commas.csv")); },
                ThrowsMessage<InputError>(HasSubstr("its first line is longer than 16 MiB")));
}

TEST(Input, TheLineLimitIsExactWhereverTheLineLies) {
    // A row of exactly the limit is read; one byte more is a bad row: in the middle of the file,
    // and as the last line without a line end (before: read up to about 2 MiB as a good row).
    TempDir dir;
    const std::string header = "mmsi,timestamp,lat,lon,note\n";
    const std::string a = "1,2024-05-01T10:00:00Z,50.1,-1.2\n";
    const std::string start = "1,2024-05-01T10:00:30Z,50.15,-1.2,";
    auto padded = [&](std::size_t bytes) { return start + std::string(bytes - start.size(), '7'); };
    const std::size_t limit = shoal::detail::max_line_bytes;
    for (const bool last : {false, true}) {
        for (const std::size_t bytes : {limit, limit + 1, limit + 100000}) {
            const std::string tail = last ? "" : "\n1,2024-05-01T10:01:00Z,50.2,-1.2\n";
            for (const char* end : {"\n", "\r\n"}) {
                if (last && std::string(end) == "\r\n") continue;
                const std::string body = header + a + padded(bytes) + (last ? "" : end) + tail.substr(last ? 0 : 1);
                write(dir.file("long.csv"), body);
                const TrackFile got = read_tracks(dir.file("long.csv"));
                SCOPED_TRACE(std::to_string(bytes) + (last ? " last" : " middle") + (std::string(end) == "\r\n" ? " crlf" : ""));
                const std::size_t want_fixes = (bytes <= limit ? 2u : 1u) + (last ? 0u : 1u);
                ASSERT_EQ(got.tracks.size(), 1u);
                EXPECT_EQ(got.tracks[0].fixes.size(), want_fixes);
                if (bytes > limit) {
                    ASSERT_EQ(got.report.messages.size(), 1u);
                    EXPECT_THAT(got.report.messages[0], HasSubstr("long.csv line 3: longer than 1 MiB, the longest line shoal reads; row skipped"));
                } else {
                    EXPECT_TRUE(got.report.messages.empty());
                }
            }
        }
    }
}

TEST(Input, NmeaLineOverTheLimitIsABadLine) {
    TempDir dir;
    const std::string log = slurp(data_path("tracks/mixed_talkers.nmea"));
    write(dir.file("long.nmea"), log + std::string(2 << 20, 'x') + "\n" + log);
    write(dir.file("short.nmea"), log + "\n" + log);
    shoal::track::ReadOptions options;
    options.max_messages = 1000;
    const TrackFile got = read_tracks(dir.file("long.nmea"), options), want = read_tracks(dir.file("short.nmea"), options);
    EXPECT_EQ(got.report.rows, want.report.rows + 1);
    EXPECT_EQ(got.report.skipped, want.report.skipped + 1);
    const std::size_t line = static_cast<std::size_t>(std::count(log.begin(), log.end(), '\n')) + 1;
    EXPECT_THAT(got.report.messages,
                testing::Contains(dir.file("long.nmea") + " line " + std::to_string(line) + ": longer than 1 MiB, the longest line shoal reads; line skipped"));
    ASSERT_EQ(got.tracks.size(), want.tracks.size());
    EXPECT_EQ(got.tracks[0].fixes.size(), want.tracks[0].fixes.size());
}

TEST(Input, AnNmeaLogReadInBlocksIsTheLogReadWhole) {
    // Issue 42: a log is read line by line from blocks (never held whole), so 5 M bad lines cost
    // what the good ones do. Whatever the block size (a line split across blocks, a block of
    // one byte, a line over the limit in the middle, a last line without its end), the same
    // tracks, counts and messages as the whole text read at once.
    TempDir dir;
    const std::string log = slurp(data_path("tracks/ais_raw/gpsd_ait250.log")) + slurp(data_path("tracks/mixed_talkers.nmea"));
    const std::string text = log + std::string((1 << 20) + 5, 'x') + "\r\n" + log + "$GPRMC,235959,A,5241.9,N,00517.5";
    write(dir.file("log.nmea"), text);
    shoal::track::ReadOptions options;
    options.max_messages = 1000;
    const TrackFile want = shoal::track::read_nmea_text(text, dir.file("log.nmea"), options);
    ASSERT_GT(want.report.skipped, 3u);
    for (const std::size_t block : {std::size_t{1}, std::size_t{61}, std::size_t{4096}, std::size_t{1} << 20}) {
        SCOPED_TRACE("block " + std::to_string(block));
        shoal::detail::InputFile in(dir.file("log.nmea"));
        const TrackFile got = shoal::track::detail::read_nmea_stream(in, {}, false, options, block);
        expect_same(got, want);
        EXPECT_EQ(got.report.messages, want.report.messages);
    }
}

TEST(Input, AnNmeaLogWithCrLineEndsIsTheLogWithLfLineEnds) {
    // A log written with CR line ends (some loggers, old Mac programs) or CR LF: the same
    // sentences on the same lines as with LF, whole or in blocks that cut a CR LF in two.
    // Before, a CR-only log was one line: its first sentence read, the rest lost without a word.
    TempDir dir;
    std::string lf;
    for (const char c : slurp(data_path("tracks/ais_raw/gpsd_ait250.log")) + slurp(data_path("tracks/mixed_talkers.nmea")) +
                            slurp(data_path("tracks/bad_checksum.nmea")))
        if (c != '\r') lf += c;
    shoal::track::ReadOptions options;
    options.max_messages = 1000;
    const TrackFile want = shoal::track::read_nmea_text(lf, dir.file("log.nmea"), options);
    ASSERT_GT(want.report.rows, 100u);
    ASSERT_GT(want.report.skipped, 0u);
    for (const std::string end : {"\r", "\r\n", "\n\r\n"}) {
        std::string text;
        for (const char c : lf) text += c == '\n' ? end : std::string(1, c);
        SCOPED_TRACE("line end " + std::to_string(end.size()) + " bytes");
        if (end == "\n\r\n") {  // a blank line after each: every line number doubled, the same sentences
            const TrackFile got = shoal::track::read_nmea_text(text, dir.file("log.nmea"), options);
            EXPECT_EQ(got.report.rows, want.report.rows);
            EXPECT_EQ(got.report.skipped, want.report.skipped);
            continue;
        }
        const TrackFile whole = shoal::track::read_nmea_text(text, dir.file("log.nmea"), options);
        expect_same(whole, want);
        EXPECT_EQ(whole.report.messages, want.report.messages);
        write(dir.file("log.nmea"), text);
        for (const std::size_t block : {std::size_t{1}, std::size_t{2}, std::size_t{61}, std::size_t{4096}}) {
            SCOPED_TRACE("block " + std::to_string(block));
            shoal::detail::InputFile in(dir.file("log.nmea"));
            const TrackFile got = shoal::track::detail::read_nmea_stream(in, {}, false, options, block);
            expect_same(got, want);
            EXPECT_EQ(got.report.messages, want.report.messages);
        }
    }
}

TEST(Input, ACsvFileWithCrLineEndsIsTheFileWithLfLineEnds) {
    // A spreadsheet's "CSV (Macintosh)" (CR line ends): each CR a line end, the same rows on
    // the same lines as with LF, whole or in blocks. Before: one line, "no usable fix (0 rows read)".
    TempDir dir;
    std::string lf = "mmsi,timestamp,lat,lon,name\n";
    for (int i = 0; i < 300; ++i)
        lf += std::to_string(230000000 + i % 7) + ",2024-05-01T10:" + std::to_string(10 + i / 7 % 50) + ":00Z," +
              (i % 17 == 0 ? "91" : "60." + std::to_string(100 + i)) + ",24.9," + (i % 11 == 0 ? "\"A\nB\"" : "X") + "\n";
    lf += "1,2024-05-01T10:00:00Z,91,24\n";  // a bad row, named by its line
    std::string cr = lf;
    std::replace(cr.begin(), cr.end(), '\n', '\r');
    write(dir.file("lf.csv"), lf);
    write(dir.file("cr.csv"), cr);
    // "\r\r\n" (a CR LF file converted twice) is one line end, as editors count it.
    std::string crcrlf;
    for (const char c : lf) crcrlf += c == '\n' ? std::string("\r\r\n") : std::string(1, c);
    write(dir.file("crcrlf.csv"), crcrlf);
    shoal::track::ReadOptions options;
    options.max_messages = 1000;
    const shoal::track::PackedTrackFile want = shoal::track::read_csv_text_packed(lf, dir.file("cr.csv"), options);
    ASSERT_GT(want.report.skipped, 10u);
    for (const std::size_t block : {std::size_t{7}, std::size_t{4096}, std::size_t{1} << 20}) {
        SCOPED_TRACE("block " + std::to_string(block));
        shoal::detail::InputFile in(dir.file("cr.csv"));
        expect_same_packed(shoal::track::detail::read_csv_stream(in, {}, false, options, block), want);
    }
    EXPECT_EQ(read_tracks(dir.file("cr.csv"), options).report.messages.size(), want.report.messages.size());
    for (const std::size_t block : {std::size_t{2}, std::size_t{4096}}) {
        SCOPED_TRACE("crcrlf, block " + std::to_string(block));
        shoal::detail::InputFile in(dir.file("crcrlf.csv"));
        const shoal::track::PackedTrackFile got = shoal::track::detail::read_csv_stream(in, {}, false, options, block);
        ASSERT_EQ(got.tracks.size(), want.tracks.size());
        for (std::size_t i = 0; i < got.tracks.size(); ++i) {
            ASSERT_EQ(got.tracks[i].size(), want.tracks[i].size());
            for (std::size_t k = 0; k < got.tracks[i].size(); ++k) EXPECT_EQ(got.tracks[i].fix(k).line, want.tracks[i].fix(k).line);
        }
    }
}

TEST(Input, NmeaSentencesRunTogetherOnALineAreEachRead) {
    // A logger that lost line ends ("...*6C$GPRMC,..." on one line; before, all but the first
    // sentence of the line were lost without a word): the same sentences read as when each has
    // its line, AIS with its tag block too.
    TempDir dir;
    const std::string log = slurp(data_path("tracks/plaka_head400.log")) + slurp(data_path("tracks/mixed_talkers.nmea")) +
                            slurp(data_path("tracks/bad_checksum.nmea")) +
                            "\\s:rx1,c:1408104100*0E\\!AIVDM,1,1,,A,13u?etPv2;0n:dDPwUM1U1Cb069D,0*24\n"
                            "\\s:rx1,c:1408104110*0F\\!AIVDM,1,1,,A,13u?etPv2;0n:dDPwUM1U1Cb069D,0*24\n"
                            "\\s:rx1,c:1408104120*0C\\!AIVDM,1,1,,A,13u?etPv2;0n:dDPwUM1U1Cb069D,0*24\n";
    std::vector<std::string> lines;
    for (std::size_t pos = 0; pos < log.size();) {
        const std::size_t end = log.find('\n', pos);
        lines.push_back(log.substr(pos, end - pos));
        pos = end + 1;
    }
    std::string glued;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        glued += lines[i];
        // Each line that begins with its sentence (or a tag block) joins the one before it,
        // every other time.
        const bool joins_next = i % 2 == 0 && i + 1 < lines.size() && !lines[i + 1].empty() && std::string("$!\\").find(lines[i + 1][0]) != std::string::npos &&
                                lines[i].find_first_of("$!") != std::string::npos;
        if (!joins_next) glued += '\n';
    }
    ASSERT_LT(std::count(glued.begin(), glued.end(), '\n'), std::count(log.begin(), log.end(), '\n') * 3 / 4);
    shoal::track::ReadOptions options;
    options.max_messages = 1000;
    const TrackFile want = shoal::track::read_nmea_text(log, "log.nmea", options);
    const TrackFile got = shoal::track::read_nmea_text(glued, "log.nmea", options);
    ASSERT_GT(want.report.rows, 300u);
    // The AIS reports are timed by their tag blocks (c:), also when glued to the line before.
    bool tagged = false;
    for (const auto& t : got.tracks)
        for (const auto& f : t.fixes) tagged = tagged || f.time_s == 1408104110.0;
    EXPECT_TRUE(tagged);
    EXPECT_EQ(got.report.rows, want.report.rows);
    EXPECT_EQ(got.report.skipped, want.report.skipped);
    ASSERT_EQ(got.tracks.size(), want.tracks.size());
    for (std::size_t i = 0; i < got.tracks.size(); ++i) {
        ASSERT_EQ(got.tracks[i].fixes.size(), want.tracks[i].fixes.size()) << want.tracks[i].id;
        for (std::size_t k = 0; k < got.tracks[i].fixes.size(); ++k) {
            EXPECT_EQ(got.tracks[i].fixes[k].time_s, want.tracks[i].fixes[k].time_s);
            EXPECT_EQ(got.tracks[i].fixes[k].position.lat, want.tracks[i].fixes[k].position.lat);
            EXPECT_EQ(got.tracks[i].fixes[k].position.lon, want.tracks[i].fixes[k].position.lon);
        }
    }
}

TEST(Input, NmeaSentencesAreSplitOnlyAfterTheirChecksumAndCrCrLfIsOneLineEnd) {
    // A line is split only past the first sentence's own checksum: one whose whole checksum
    // holds a '$' inside (a real log's "$SDVLW,$SDVLW,,N,...*16") is one sentence, and one cut
    // short before another ("...,E,2$GPRMC,...*11") fails its checksum as one sentence, as
    // before (split, its cut-off piece would be read without a checksum: 2 kn for 22.4). A log
    // whose first line ends in LF counts lines at LF alone, as grep and editors do ("\r\r\n"
    // is one line end).
    const std::string text =
        "$GPRMC,100000,A,6005.000,N,02455.000,E,22.4,90.0,010524,,*16\r\r\n"
        "$SDVLW,$SDVLW,,N,12.3,N*16\r\r\n"
        "$GPRMC,100010,A,6005.000,N,02455.234,E,2$GPRMC,100020,A,6005.000,N,02455.500,E,22.4,90.0,010524,,*11\r\r\n"
        "$GPRMC,100020,A,6005.000,N,02455.500,E,22.4,90.0,010524,,*11\r\r\n"
        "$GPRMC,100030,A,6005.000,N,02455.750,E,22.4,90.0,010524,,*1X\r\r\n";
    const TrackFile f = shoal::track::read_nmea_text(text, "v.nmea", {});
    ASSERT_EQ(f.tracks.size(), 1u);
    ASSERT_EQ(f.tracks[0].fixes.size(), 2u);
    EXPECT_EQ(f.tracks[0].fixes[0].line, 1u);
    EXPECT_EQ(f.tracks[0].fixes[1].line, 4u);
    EXPECT_EQ(f.report.skipped, 2u);
    ASSERT_EQ(f.report.messages.size(), 2u);
    EXPECT_THAT(f.report.messages[0], HasSubstr("v.nmea line 3: bad checksum '*11'"));
    EXPECT_THAT(f.report.messages[1], HasSubstr("v.nmea line 5: bad checksum '*1X'"));
}

TEST(Input, HullsLargerThanAnyShipAreRefused) {
    using shoal::hull::Hull;
    EXPECT_NO_THROW(Hull::from_dims_string("400,50,30,30"));
    EXPECT_THAT([] { Hull::from_dims_string("450,60,5,5"); },
                ThrowsMessage<InputError>(HasSubstr("a length (a + b) of 510 m is more than the 500 m of any ship")));
    EXPECT_THAT([] { Hull::from_dims_string("100,60,50,51"); },
                ThrowsMessage<InputError>(HasSubstr("a beam (c + d) of 101 m is more than the 100 m of any ship")));
    EXPECT_THAT([] { Hull::parse(R"({"name": "big", "a": 100000, "b": 10, "c": 5, "d": 5})", "big.json"); },
                ThrowsMessage<InputError>(HasSubstr("In ship file 'big.json': a length (a + b) of 100010 m")));
    // Under a millimetre: before, an outline of no area, said of every track.
    EXPECT_NO_THROW(Hull::from_dims_string("0.01,0.01,0.01,0.01"));
    EXPECT_THAT([] { Hull::from_dims_string("1e-300,1e-300,1e-300,1e-300"); },
                ThrowsMessage<InputError>(HasSubstr("less than the 0.001 m a hull needs")));
    EXPECT_THAT([] { Hull::from_dims_string("10,10,0.0004,0.0004"); }, ThrowsMessage<InputError>(HasSubstr("a beam (c + d) of 8e-04 m is less")));
    // A track's AIS dimensions that small are not its hull (the default serves it), as those
    // larger than any ship.
    EXPECT_FALSE(Hull::plausible({0.0004, 0.0004, 5, 5}));
    EXPECT_FALSE(Hull::plausible({5, 5, 0.0004, 0.0004}));
    EXPECT_TRUE(Hull::plausible({0.01, 0.01, 0.01, 0.01}));
}

TEST(Input, TrackWithImpossibleAisDimensionsKeepsItsFixesAndLosesTheDimensions) {
    TempDir dir;
    write(dir.file("dims.csv"),
          "mmsi,timestamp,lat,lon,a,b,c,d\n"
          "1,2024-05-01T10:00:00Z,50.1,-1.2,900,100,10,10\n"
          "1,2024-05-01T10:01:00Z,50.2,-1.2,900,100,10,10\n"
          "2,2024-05-01T10:00:00Z,50.1,-1.3,90,10,10,10\n");
    const TrackFile got = read_tracks(dir.file("dims.csv"));
    ASSERT_EQ(got.tracks.size(), 2u);
    EXPECT_FALSE(got.tracks[0].dims);
    EXPECT_EQ(got.tracks[0].fixes.size(), 2u);
    EXPECT_EQ(got.tracks[1].dims, (shoal::hull::Dimensions{90, 10, 10, 10}));
    ASSERT_EQ(got.report.messages.size(), 1u);
    EXPECT_THAT(got.report.messages[0], HasSubstr("1 track gives AIS dimensions larger than any ship"));
    EXPECT_THAT(got.report.messages[0], HasSubstr("e.g. 1 (a=900 b=100 c=10 d=10): the default hull is used"));
}

}  // namespace

// The raw reads of the input layer (a file's fingerprint, a folder's vessels table, a zip's
// magic bytes): a plain file by the system's calls and a /vsizip member by GDAL give the file's
// bytes as they are (not unpacked), in blocks of any size; a FIFO, a folder, `-` and a missing
// file are no regular file and are never opened (no writer: opening the FIFO would block).
TEST(Input, RawReadsGiveTheBytesAsTheyAreAndOpenNoStream) {
    TempDir dir;
    std::mt19937 rng(40);
    std::string bytes(300000, '\0');
    for (char& c : bytes) c = static_cast<char>(rng());
    write(dir.file("raw.bin"), bytes);
    run("gzip -c " + dir.file("raw.bin") + " > " + dir.file("raw.bin.gz"));
    const std::string gz = slurp(dir.file("raw.bin.gz"));
    std::vector<std::pair<std::string, std::string>> cases{{dir.file("raw.bin"), bytes}, {dir.file("raw.bin.gz"), gz}};
    if (have_tool("zip")) {  // a member of a zip, read by GDAL
        run("cd " + dir.path().string() + " && zip -q -0 raw.zip raw.bin");
        cases.emplace_back("/vsizip/" + dir.file("raw.zip") + "/raw.bin", bytes);
    }
    for (const auto& [path, want] : cases) {
        EXPECT_TRUE(shoal::detail::is_regular_input(path)) << path;
        for (const std::size_t block : {std::size_t{1}, std::size_t{4096}, std::size_t{65537}, std::size_t{1} << 20}) {
            if (block == 1 && path.rfind("/vsi", 0) == 0) continue;  // a byte at a time through GDAL: slow, and no other path
            std::string got;
            std::size_t calls = 0;
            EXPECT_TRUE(shoal::detail::read_blocks(path, block, [&](const char* p, std::size_t n) {
                EXPECT_LE(n, block);
                got.append(p, n);
                ++calls;
            }));
            EXPECT_EQ(got, want) << path << " in blocks of " << block;
            EXPECT_EQ(calls, (want.size() + block - 1) / block);
        }
        EXPECT_EQ(shoal::detail::read_head(path, 10), want.substr(0, 10));
        EXPECT_EQ(shoal::detail::read_head(path, 1 << 21), want);
    }
    const std::string fifo = dir.file("fifo");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    fs::create_directory(dir.path() / "folder");
    for (const std::string& path : {fifo, dir.file("folder"), std::string("-"), dir.file("missing")}) {
        EXPECT_FALSE(shoal::detail::is_regular_input(path)) << path;
        EXPECT_FALSE(shoal::detail::read_blocks(path, 4096, [](const char*, std::size_t) { ADD_FAILURE() << "read"; })) << path;
    }
    EXPECT_EQ(shoal::detail::read_head(dir.file("missing"), 10), "");
}
