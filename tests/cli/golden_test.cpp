// Golden CLI tests (as osmium-tool's check_output() and PROJ's test/cli): each case in
// tests/cli/golden/*.case runs one `shoal` command on small committed inputs and compares its
// exit status, standard output and standard error whole with what the case holds; a case may
// also compare a file the command writes. A change of any message, table, help text or exit
// status shows here as a diff, to be made on purpose: SHOAL_GOLDEN_UPDATE=1 rewrites the cases'
// expected sections from what the commands now print (then read the diff before committing).
//
// A case file:
//   # what the case shows (comment lines, kept)
//   setup$ shoal import data/coast/uk_solent_land.geojson -o solent.shoalgrid   (any number; must exit 0 or 1)
//   $ shoal probe --coast solent.shoalgrid --dims 50,10,4,6 in/poses.csv         (the command checked)
//   == status 0
//   == stdout
//   ...
//   == stderr
//   ...
//   == file poses-out.csv                                                          (optional, any number)
//   ...
// Commands run through the shell in a fresh folder holding copies of `data` (tests/data),
// `examples` (examples/data and the example ships) and `in` (tests/cli/golden/inputs), so every path a
// message names is relative and the same on every machine. Two things vary between runs and
// are masked before comparing: the numbers on a "time:" or "build time:" line (durations),
// the run folder's absolute path (<DIR>), and the executable's path (shoal).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "run_shoal.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path cases_dir = fs::path(SHOAL_TEST_DATA).parent_path().parent_path() / "cli" / "golden";

struct Section {
    std::string name;  ///< "stdout", "stderr", or "file NAME"
    std::string text;
};

struct Case {
    std::vector<std::string> header;  ///< comment lines and commands, as written
    std::vector<std::string> setup;   ///< setup commands' arguments (after "setup$ shoal ")
    std::string command;              ///< the checked command's arguments (after "$ shoal ")
    bool has_command = false;
    int status = -1;
    std::vector<Section> sections;
};

std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

Case parse_case(const fs::path& path) {
    std::istringstream in(read_text(path));
    Case c;
    std::string line;
    Section* open = nullptr;
    while (std::getline(in, line)) {
        if (line.rfind("== ", 0) == 0) {
            const std::string what = line.substr(3);
            if (what.rfind("status ", 0) == 0) {
                c.status = std::stoi(what.substr(7));
                open = nullptr;
            } else {
                c.sections.push_back({what, ""});
                open = &c.sections.back();
            }
            continue;
        }
        if (open) {
            open->text += line + "\n";
            continue;
        }
        if (!c.sections.empty() || c.status >= 0) throw std::runtime_error(path.string() + ": text after '== status' outside a section: " + line);
        c.header.push_back(line);
        if (line.rfind("setup$ shoal", 0) == 0) c.setup.push_back(line.substr(12));
        else if (line == "$ shoal" || line.rfind("$ shoal ", 0) == 0) {
            c.command = line.substr(7);
            c.has_command = true;
        }
        else if (!line.empty() && line[0] != '#') throw std::runtime_error(path.string() + ": a line that is neither a comment nor a command: " + line);
    }
    if (!c.has_command) throw std::runtime_error(path.string() + ": no '$ shoal ...' command");
    return c;
}

/// What varies between runs, masked: durations on time lines, the run folder.
std::string normalise(std::string text, const fs::path& dir) {
    for (std::size_t at; (at = text.find(dir.string())) != std::string::npos;) text.replace(at, dir.string().size(), "<DIR>");
    const std::string binary = SHOAL_BINARY;  // help's "Usage: <argv[0]> ..."
    for (std::size_t at; (at = text.find(binary)) != std::string::npos;) text.replace(at, binary.size(), "shoal");
    static const std::regex number("[0-9]+(\\.[0-9]+)?");
    std::istringstream in(text);
    std::string out, line;
    while (std::getline(in, line)) {
        const auto first = line.find_first_not_of(' ');
        const std::string trimmed = first == std::string::npos ? "" : line.substr(first);
        if (trimmed.rfind("time:", 0) == 0 || trimmed.rfind("build time:", 0) == 0) line = std::regex_replace(line, number, "#");
        out += line + "\n";
    }
    if (!text.empty() && text.back() != '\n') out.pop_back();  // a last line without its newline stays so
    return out;
}

std::vector<std::string> case_names() {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(cases_dir))
        if (e.path().extension() == ".case") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

class Golden : public ::testing::TestWithParam<std::string> {};

TEST_P(Golden, OutputStatusAndMessagesAreTheCasesWhole) {
    const fs::path path = cases_dir / (GetParam() + ".case");
    const Case c = parse_case(path);
    const fs::path dir = fs::temp_directory_path() / ("shoal-golden-" + GetParam() + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    // Copies, not links: a command that wrote over an input would spoil the sources.
    const fs::path examples = cases_dir.parent_path().parent_path().parent_path() / "examples";
    fs::copy(fs::path(SHOAL_TEST_DATA), dir / "data", fs::copy_options::recursive);
    fs::create_directories(dir / "examples");
    fs::copy(examples / "data", dir / "examples" / "data", fs::copy_options::recursive);
    for (const char* ship : {"ship.json", "yacht.json"}) fs::copy_file(examples / ship, dir / "examples" / ship);
    fs::copy(cases_dir / "inputs", dir / "in", fs::copy_options::recursive);
    auto run = [&](const std::string& args) {
        return shoal::test::run_shoal(args, dir / "cache", dir / "stderr.txt", dir);
    };
    for (const std::string& s : c.setup) {
        const auto r = run(s);
        ASSERT_TRUE(r.status == 0 || r.status == 1) << "setup `shoal" << s << "` exited " << r.status << ":\n" << r.err;
    }
    const auto r = run(c.command);
    Case now = c;
    now.status = r.status;
    now.sections.clear();
    now.sections.push_back({"stdout", normalise(r.out, dir)});
    now.sections.push_back({"stderr", normalise(r.err, dir)});
    for (const Section& s : c.sections)
        if (s.name.rfind("file ", 0) == 0) {
            const fs::path f = dir / s.name.substr(5);
            now.sections.push_back({s.name, fs::exists(f) ? normalise(read_text(f), dir) : "(no such file)\n"});
        }
    if (std::getenv("SHOAL_GOLDEN_UPDATE")) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        for (const std::string& h : now.header) out << h << "\n";
        out << "== status " << now.status << "\n";
        for (const Section& s : now.sections) out << "== " << s.name << "\n" << s.text;
        std::printf("updated %s\n", path.c_str());
    } else {
        EXPECT_EQ(now.status, c.status) << "`shoal" << c.command << "`: stderr:\n" << r.err;
        for (const Section& expected : c.sections) {
            const auto got = std::find_if(now.sections.begin(), now.sections.end(), [&](const Section& s) { return s.name == expected.name; });
            ASSERT_NE(got, now.sections.end()) << expected.name;
            EXPECT_EQ(got->text, expected.text) << "`shoal" << c.command << "`: " << expected.name << " differs from " << path
                                                << " (SHOAL_GOLDEN_UPDATE=1 rewrites it)";
        }
        for (const char* must : {"stdout", "stderr"})
            EXPECT_TRUE(std::any_of(c.sections.begin(), c.sections.end(), [&](const Section& s) { return s.name == must; }))
                << path << " has no '== " << must << "' section";
    }
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Cases, Golden, ::testing::ValuesIn(case_names()), [](const ::testing::TestParamInfo<std::string>& param_info) {
    std::string n = param_info.param;
    std::replace_if(n.begin(), n.end(), [](char ch) { return !std::isalnum(static_cast<unsigned char>(ch)); }, '_');
    return n;
});

TEST(GoldenCases, ThereAreCasesAndEveryCommandHasOne) {
    const auto names = case_names();
    ASSERT_GE(names.size(), 10u);
    // Every command `shoal --help` lists has at least one case of its own (its name first).
    const auto help = shoal::test::run_shoal("--help", fs::temp_directory_path(), fs::temp_directory_path() / "shoal-golden-help.txt");
    const std::regex command_line("^  ([a-z]+) ");
    std::istringstream in(help.out);
    std::size_t commands = 0;
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (!std::regex_search(line, m, command_line)) continue;
        ++commands;
        const std::string cmd = m[1];
        EXPECT_TRUE(std::any_of(names.begin(), names.end(), [&](const std::string& n) { return n.rfind(cmd + "-", 0) == 0; }))
            << "no golden case for `shoal " << cmd << "` (name one tests/cli/golden/" << cmd << "-WHAT.case)";
    }
    EXPECT_GE(commands, 5u) << "the commands listed by `shoal --help`:\n" << help.out;
}

}  // namespace
