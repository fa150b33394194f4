// shoal: the command-line front end. Parsing, messages and exit codes only; every
// capability lives in the library (src/).
//
// This is the full front end, every command, in the module libshoal_cli_full.so (it calls
// GDAL, GEOS and PROJ, loaded when a run first needs them): the `shoal` executable (launcher.cpp, GDAL-free) runs a probe of a grid file itself and
// loads this module for everything else, calling shoal_cli_main with its arguments.
//
// Exit status: 0 success (check: no grounding), 1 check found at least one grounding,
// 2 bad usage or unreadable input, 3 internal error (a bug, or a failure inside GDAL, GEOS or
// PROJ that is not the input's fault), 128 + N on signal N (130 for Ctrl-C).

#include <CLI/CLI.hpp>
#include <cpl_error.h>

#include <algorithm>
#include <cstdio>
#include <cctype>
#include <string>
#include <vector>

#include "commands.hpp"
#include "launcher.hpp"
#include "options.hpp"
#include "process.hpp"
#include "util/gdal_support.hpp"
#include "util/lazy_libraries.hpp"
#include <shoal/util/printable.hpp>
#include <shoal/version.hpp>

namespace {

/// The edit distance (insertions, deletions, substitutions, and swaps of two neighbours) between
/// `a` and `b`: "chek" is one from "check", "chekc" one from "check".
std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
        for (std::size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

/// The commands, in the order of `shoal --help`: "import, info, probe, check, merge".
std::string command_names(const CLI::App& app) {
    std::string names;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) names += (names.empty() ? "" : ", ") + sub->get_name();
    return names;
}

/// A first argument that is no command and no option ("shoal chek ..."): the usage error that says
/// so and names the nearest command (CLI11 alone says "A subcommand is required", which hides the typo).
std::string unknown_command(const CLI::App& app, const std::string& given) {
    std::string nearest;
    std::size_t best = static_cast<std::size_t>(-1);
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
        const std::string& n = sub->get_name();
        std::string lower = given;
        std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        const std::size_t d = edit_distance(lower, n);
        if (d < best) best = d, nearest = n;
    }
    // Near enough to be a typo: at most 2 edits, and fewer than half the command's letters.
    const bool suggest = best <= 2 && 2 * best < nearest.size();
    return "unknown command '" + shoal::printable(given) + "'" + (suggest ? " (did you mean '" + nearest + "'?)" : "") + "; the commands are " +
           command_names(app);
}

}  // namespace

extern "C" SHOAL_CLI_ENTRY int shoal_cli_main(int argc, char** argv) {
    using namespace shoal::cli;
    fewer_malloc_arenas();
    handle_interrupts();
    // GDAL reports through our exceptions, which name the file and feature; keep its own lines off
    // stderr. This module is linked without GDAL, GEOS and PROJ, and loads each when a run first
    // needs it (util/lazy_libraries.hpp): the handler is set then.
    shoal::detail::on_gdal_loaded([] { CPLSetErrorHandler(shoal::detail::quiet_error_handler); });
    CLI::App app{"shoal: audit ship tracks against chart coastlines"};
    app.require_subcommand(1);
    // One line per usage error, like every other error (subcommands inherit this).
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("shoal: usage error: ") + e.what() + " (see shoal COMMAND --help)\n";
    });
    app.set_version_flag("--version", std::string("shoal ") + SHOAL_VERSION_STRING);
    app.footer("Exit status: 0 ok / no grounding, 1 grounding found (check), 2 bad usage or unreadable input,\n"
               "3 internal error (please report it), 130 interrupted (Ctrl-C; nothing half-written is left).\n"
               "Run 'shoal COMMAND --help' for a command's options; docs/user-guide.md has the details.");
    std::vector<std::unique_ptr<shoal::cli::Command>> commands = shoal::cli::make_commands();
    for (auto& c : commands) c->setup(app);
    // `shoal COMMAND --list-options`: the command's options, one a line, for drivers that pass
    // a command line on (python3 -m shoal.dask): NAMES (comma-separated) TAB how many values
    // each use takes: 0 (a flag), 1, or many (every value up to the next option).
    if (argc == 3 && std::string(argv[2]) == "--list-options")
        for (const CLI::App* sub : app.get_subcommands({}))
            if (sub->get_name() == argv[1]) {
                for (const CLI::Option* o : sub->get_options()) {
                    if (o->get_positional()) continue;
                    std::string names;
                    for (const std::string& n : o->get_snames()) names += (names.empty() ? "-" : ",-") + n;
                    for (const std::string& n : o->get_lnames()) names += (names.empty() ? "--" : ",--") + n;
                    const bool flag = o->get_type_size_max() == 0 || o->get_expected_max() == 0 || o->get_expected_min() == 0;
                    const bool many = !flag && o->get_expected_max() > 1 && o->get_allow_extra_args();
                    std::printf("%s\t%s\n", names.c_str(), flag ? "0" : many ? "many" : "1");
                }
                return 0;
            }
    // No command at all (CLI11 alone says "A subcommand is required"): say which there are.
    if (argc < 2) {
        std::fprintf(stderr, "shoal: usage error: no command given; the commands are %s (see shoal --help)\n", command_names(app).c_str());
        return shoal::cli::exit_usage;
    }
    if (argv[1][0] != '-' && argv[1][0] != '\0') {
        const std::string first = argv[1];
        const auto all = app.get_subcommands([](const CLI::App*) { return true; });
        if (std::none_of(all.begin(), all.end(), [&](const CLI::App* sub) { return sub->check_name(first); })) {
            std::fprintf(stderr, "shoal: usage error: %s (see shoal --help)\n", unknown_command(app, first).c_str());
            return shoal::cli::exit_usage;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);
        return rc == 0 ? 0 : shoal::cli::exit_usage;
    }
    // An option given an empty value (--plot "", --debrief "", a variable that expanded to
    // nothing) would do nothing, in silence: a usage error naming it.
    for (const CLI::App* sub : app.get_subcommands())
        for (const CLI::Option* o : sub->get_options())
            if (!o->get_positional() && o->get_type_size_min() > 0)
                for (const std::string& value : o->results())
                    if (value.empty()) {
                        std::fprintf(stderr, "shoal: usage error: %s '' is empty: give it a value, or leave the option out (see shoal %s --help)\n",
                                     o->get_name().c_str(), sub->get_name().c_str());
                        return shoal::cli::exit_usage;
                    }
    return run_reporting_errors([&] {
        for (auto& c : commands)
            if (c->parsed()) return c->run();
        return static_cast<int>(shoal::cli::exit_usage);
    });
}
