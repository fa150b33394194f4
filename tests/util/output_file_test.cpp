// The output-file rules: outputs are checked against the inputs and each other before any
// work; an output is written beside its target under a name that marks it as shoal's and
// carries the writer's pid, and put in place only by its commit; a temporary left by a killed
// process is removed the next time an output is staged there.

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "test_support.hpp"
#include <shoal/util/atomic_file.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal {
namespace {

namespace fs = std::filesystem;

std::string read(const std::string& path) {
    const std::vector<char> b = test::read_bytes(path);
    return {b.begin(), b.end()};
}
void put(const std::string& path, const std::string& text) { test::write_bytes(path, {text.begin(), text.end()}); }

std::vector<std::string> names_in(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

template <class E>
std::string message_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const E& e) {
        return e.what();
    }
    return "(nothing thrown)";
}

TEST(CheckOutputs, AMissingFolderOrAFolderAsTheOutputIsAnInputError) {
    test::TempDir dir;
    EXPECT_EQ(message_of<InputError>([&] { check_outputs({{dir.file("no/r.geojson")}}, {}); }),
              "cannot write '" + dir.file("no/r.geojson") + "': folder '" + dir.file("no") + "' does not exist");
    EXPECT_EQ(message_of<InputError>([&] { check_outputs({{dir.path().string()}}, {}); }),
              "cannot write '" + dir.path().string() + "': it is a directory");
    EXPECT_NO_THROW(check_outputs({{"-"}}, {}));
}

TEST(CheckOutputs, AnOutputThatIsAnInputByAnyPathIsRefused) {
    test::TempDir dir;
    const std::string in = dir.file("tracks.csv");
    put(in, "x");
    fs::create_hard_link(in, dir.file("hard.csv"));
    fs::create_symlink(in, dir.file("soft.csv"));
    fs::create_directory(dir.file("sub"));
    for (const std::string& out : {in, dir.file("hard.csv"), dir.file("soft.csv"), dir.file("sub/../tracks.csv")})
        EXPECT_EQ(message_of<UsageError>([&] { check_outputs({{"r.geojson"}, {out, "--plot", "the picture"}}, {"", in}); }),
                  "the output '" + out + "' is the input '" + in + "': writing it would destroy the input; choose another --plot")
            << out;
    EXPECT_EQ(read(in), "x");
    EXPECT_NO_THROW(check_outputs({{dir.file("other.csv")}}, {in}));
}

TEST(CheckOutputs, TwoOutputsThatAreOneFileAreRefused) {
    test::TempDir dir;
    const std::string r = dir.file("r.geojson");
    fs::create_directory(dir.file("sub"));
    const auto refused = [&](const std::string& report, const std::string& plot) {
        return message_of<UsageError>([&] { check_outputs({{report, "-o", "the report"}, {plot, "--plot", "the picture"}}, {}); });
    };
    EXPECT_EQ(refused(r, r), "--plot '" + r + "' is the report -o '" + r + "': choose another file for the picture");
    EXPECT_NE(refused(r, dir.file("./sub/../r.geojson")).find("is the report"), std::string::npos) << "not yet there, another spelling";
    EXPECT_NE(refused("-", "-").find("is the report"), std::string::npos) << "both on stdout";
    put(r, "old");
    fs::create_symlink(r, dir.file("link.svg"));
    EXPECT_NE(refused(r, dir.file("link.svg")).find("is the report"), std::string::npos);
    EXPECT_NO_THROW(check_outputs({{r}, {dir.file("r.svg")}}, {}));
}

TEST(CheckOutputs, ThousandsOfOutputsAndInputsCostLinearTimeAndTheLastDuplicateIsStillFound) {
    // A debrief of thousands of exercises: one page each. Before: every output was compared with
    // every earlier one and every input by same_file, each making both paths canonical (a stat
    // and a readlink per component): 1,000 pages took 28.7 s, 2,000 99.7 s. Now each path is
    // keyed once. 6,000 pages and 6,000 inputs that exist (so that every page is compared with
    // the inputs) in a deep folder: before, 18 million same_file calls (about a quarter of an
    // hour, beyond ctest's 600 s limit for a test: the guard, no clock read here); now
    // milliseconds.
    test::TempDir dir;
    fs::path deep = dir.path();
    for (int i = 0; i < 12; ++i) deep /= "level" + std::to_string(i);
    fs::create_directories(deep);
    std::vector<OutputSpec> pages;
    std::vector<std::string> inputs;
    for (int i = 0; i < 6000; ++i) {
        const std::string page = (deep / ("exercise-" + std::to_string(i) + ".html")).string();
        put(page, "old page");
        pages.push_back({page, "--debrief", "a debrief page"});
        inputs.push_back((deep / ("track-" + std::to_string(i) + ".csv")).string());
        put(inputs.back(), "x");
    }
    EXPECT_NO_THROW(check_outputs(pages, inputs));
    // Still found: the last page by another spelling of the first, and an input among them.
    pages.push_back({(deep / "sub" / ".." / "exercise-0.html").string(), "--plot", "the picture"});
    fs::create_directory(deep / "sub");
    EXPECT_NE(message_of<UsageError>([&] { check_outputs(pages, inputs); }).find("is a debrief page --debrief '" + pages[0].path + "'"),
              std::string::npos);
    pages.pop_back();
    pages.push_back({inputs[5999], "--plot", "the picture"});
    EXPECT_EQ(message_of<UsageError>([&] { check_outputs(pages, inputs); }),
              "the output '" + inputs[5999] + "' is the input '" + inputs[5999] + "': writing it would destroy the input; choose another --plot");
}

TEST(StagedOutput, IsWrittenBesideTheTargetUnderAMarkedNameAndReplacesItOnlyAtTheCommit) {
    test::TempDir dir;
    const std::string r = dir.file("r.geojson");
    put(r, "old");
    {
        StagedOutput out(r);
        ASSERT_FALSE(out.direct());
        const fs::path tmp(out.temp_path());
        EXPECT_EQ(tmp.parent_path(), dir.path());
        EXPECT_EQ(tmp.filename().string().rfind(".r.geojson.shoal.tmp-" + std::to_string(::getpid()) + "-", 0), 0u) << tmp;
        EXPECT_EQ(tmp.extension(), ".geojson") << "the target's extension, for GDAL's drivers";
        out.write("new");
        EXPECT_EQ(read(r), "old");
        EXPECT_EQ(read(out.temp_path()), "new");
        out.commit();
    }
    EXPECT_EQ(read(r), "new");
    EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{"r.geojson"});
}

TEST(StagedOutput, NotCommittedLeavesTheTargetAsItWasAndNoTemporary) {
    test::TempDir dir;
    const std::string r = dir.file("r.gpkg");
    put(r, "old");
    {
        StagedOutput out(r);
        out.write("half");
        put(out.temp_path() + "-journal", "j");
    }
    EXPECT_EQ(read(r), "old");
    EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{"r.gpkg"});
}

TEST(StagedOutput, IsListedForTheInterruptHandlerUntilItsCommit) {
    test::TempDir dir;
    StagedOutput out(dir.file("r.geojson"));
    out.write("x");
    remove_temp_files_in_progress();
    EXPECT_FALSE(fs::exists(out.temp_path()));
    EXPECT_FALSE(fs::exists(dir.file("r.geojson")));
}

TEST(StagedOutput, DevicesAreWrittenDirectly) {
    StagedOutput out("/dev/null");
    EXPECT_TRUE(out.direct());
    EXPECT_TRUE(out.temp_path().empty());
    out.write("x");
    out.commit();
    if (fs::exists("/dev/full")) {
        StagedOutput full("/dev/full");
        EXPECT_EQ(message_of<InputError>([&] { full.write("x"); }), "cannot write '/dev/full': No space left on device");
    }
}

TEST(CommitAll, PutsEveryOutputInPlaceTogetherAtTheEnd) {
    test::TempDir dir;
    const std::string r = dir.file("r.geojson"), p = dir.file("r.svg");
    put(r, "old report");
    put(p, "old picture");
    std::vector<StagedOutput> staged;
    staged.emplace_back(r);
    staged.back().write("new report");
    staged.emplace_back(p);
    staged.back().write("new picture");
    EXPECT_EQ(read(r), "old report");
    EXPECT_EQ(read(p), "old picture");
    commit_all(staged);
    EXPECT_EQ(read(r), "new report");
    EXPECT_EQ(read(p), "new picture");
    EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"r.geojson", "r.svg"}));
    // Signals are not left blocked.
    sigset_t now;
    ASSERT_EQ(::pthread_sigmask(SIG_SETMASK, nullptr, &now), 0);
    EXPECT_EQ(sigismember(&now, SIGINT), 0);
    EXPECT_EQ(sigismember(&now, SIGHUP), 0);
}

TEST(StaleTemporaries, AKilledWritersTemporaryIsRemovedByTheNextWriteThere) {
    test::TempDir dir;
    const std::string r = dir.file("r.gpkg");
    put(r, "old");
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        ::close(ready[0]);
        StagedOutput out(r);
        out.write("half-written");
        put(out.temp_path() + "-journal", "journal");
        [[maybe_unused]] const auto n = ::write(ready[1], "1", 1);
        ::pause();  // killed here: no destructor, no handler
        ::_exit(0);
    }
    ::close(ready[1]);
    char c = 0;
    ASSERT_EQ(::read(ready[0], &c, 1), 1);
    ::close(ready[0]);
    ASSERT_EQ(::kill(child, SIGKILL), 0);
    int st = 0;
    ASSERT_EQ(::waitpid(child, &st, 0), child);
    ASSERT_TRUE(WIFSIGNALED(st));
    const std::string prefix = temporary_prefix(r) + std::to_string(child) + "-";
    std::size_t left = 0;
    for (const std::string& n : names_in(dir.path())) left += n.rfind(prefix, 0) == 0;
    ASSERT_EQ(left, 2u) << "the killed child left its temporary and journal";

    // Not shoal's temporaries, a live writer's, another target's: left alone.
    const std::string mine = dir.file(".r.gpkg.tmp-" + std::to_string(child) + "-1");
    const std::string live = dir.file(temporary_prefix(r) + std::to_string(::getppid()) + "-deadbeef.gpkg");
    const std::string other = dir.file(temporary_prefix(dir.file("s.gpkg")) + std::to_string(child) + "-deadbeef.gpkg");
    for (const std::string& f : {mine, live, other}) put(f, "x");
    write_file_atomically(r, "new");
    EXPECT_EQ(read(r), "new");
    const std::vector<std::string> after = names_in(dir.path());
    for (const std::string& n : after) EXPECT_NE(n.rfind(prefix, 0), 0u) << n << " was left";
    for (const std::string& f : {mine, live, other}) EXPECT_TRUE(fs::exists(f)) << f;
    EXPECT_EQ(remove_stale_temporaries(dir.file("s.gpkg")), 1u);
}

TEST(WriteFileAtomically, KeepsItsMessagesAndLeavesNoTemporary) {
    test::TempDir dir;
    EXPECT_EQ(message_of<InputError>([&] { write_file_atomically(dir.file("no/x"), "x"); }),
              "cannot write '" + dir.file("no/x") + "': folder '" + dir.file("no") + "' does not exist");
    EXPECT_EQ(message_of<InputError>([&] { write_file_atomically(dir.path().string(), "x"); }),
              "cannot write '" + dir.path().string() + "': it is a directory");
    write_file_atomically(dir.file("x"), "abc");
    EXPECT_EQ(read(dir.file("x")), "abc");
    EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{"x"});
}

TEST(CheckOutputs, AnOutputThatIsTheFileBehindAVirtualInputPathIsRefused) {
    test::TempDir dir;
    const std::string zip = dir.file("day.zip"), gz = dir.file("t.csv.gz");
    put(zip, "PK");
    put(gz, "gz");
    EXPECT_THROW(check_outputs({{zip}}, {"/vsizip/" + zip + "/member.csv"}), UsageError);
    EXPECT_THROW(check_outputs({{zip}}, {"/vsizip/" + zip + "/a/b.csv"}), UsageError);
    EXPECT_THROW(check_outputs({{gz}}, {"/vsigzip/" + gz}), UsageError);
    EXPECT_NO_THROW(check_outputs({{dir.file("r.geojson")}}, {"/vsizip/" + zip + "/member.csv"}));
}

TEST(StagedOutput, ASymlinkIsWrittenThroughAndStaysALink) {
    test::TempDir dir;
    fs::create_directory(fs::path(dir.path()) / "real");
    fs::create_directory(fs::path(dir.path()) / "links");
    const std::string target = (fs::path(dir.path()) / "real" / "r.geojson").string();
    const std::string link = (fs::path(dir.path()) / "links" / "r.geojson").string();
    put(target, "old");
    fs::create_symlink("../real/r.geojson", link);
    StagedOutput out(link);
    out.write("new");
    out.commit();
    EXPECT_TRUE(fs::is_symlink(link));
    EXPECT_EQ(read(target), "new");
    fs::remove(target);  // a dangling link: the file it names is made
    StagedOutput again(link);
    again.write("made");
    again.commit();
    EXPECT_TRUE(fs::is_symlink(link));
    EXPECT_EQ(read(target), "made");
}

TEST(StandardOutput, HasSeveralNamesAndSystemPathsAreNeverReplaced) {
    for (const char* p : {"", "-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"}) EXPECT_TRUE(is_standard_output(p)) << p;
    for (const char* p : {"/dev/stderr", "stdout", "r.geojson"}) EXPECT_FALSE(is_standard_output(p)) << p;
    EXPECT_TRUE(is_system_path("/dev/null"));
    EXPECT_TRUE(is_system_path("/proc/self/fd/2"));
    EXPECT_FALSE(is_system_path("/tmp/dev/r.geojson"));
    const StagedOutput null_out("/dev/null");
    EXPECT_TRUE(null_out.direct());
}

}  // namespace
}  // namespace shoal
