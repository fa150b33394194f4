// shoal: the command-line front end. Parsing, messages and exit codes only; every
// capability lives in the library (src/).
//
// Exit status: 0 success (check: no grounding), 1 check found at least one grounding,
// 2 bad usage or unreadable input.

#include <CLI/CLI.hpp>
#include <cpl_error.h>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "util/error.hpp"

int main(int argc, char** argv) {
    // GDAL reports through our exceptions, which name the file and feature; keep its own lines off stderr.
    CPLSetErrorHandler(CPLQuietErrorHandler);
    CLI::App app{"shoal: audit ship tracks against chart coastlines"};
    app.require_subcommand(1);
    // One line per usage error, like every other error (subcommands inherit this).
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("shoal: usage error: ") + e.what() + " (see shoal COMMAND --help)\n";
    });
    app.set_version_flag("--version", "shoal 0.1.0");
    app.footer("Exit status: 0 ok / no grounding, 1 grounding found (check), 2 bad usage or unreadable input.\n"
               "Run 'shoal COMMAND --help' for a command's options; docs/user-guide.md has the details.");
    std::vector<std::unique_ptr<shoal::cli::Command>> commands = shoal::cli::make_commands();
    for (auto& c : commands) c->setup(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);
        return rc == 0 ? 0 : shoal::cli::exit_usage;
    }
    try {
        for (auto& c : commands)
            if (c->parsed()) return c->run();
    } catch (const shoal::InputError& e) {
        std::fprintf(stderr, "shoal: error: %s\n", e.what());
        return shoal::cli::exit_usage;
    } catch (const shoal::UsageError& e) {
        std::fprintf(stderr, "shoal: usage error: %s\n", e.what());
        return shoal::cli::exit_usage;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "shoal: error: out of memory (try a larger --cell, or fewer inputs at once)\n");
        return shoal::cli::exit_usage;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "shoal: internal error: %s\n", e.what());
        return shoal::cli::exit_usage;
    }
    return shoal::cli::exit_usage;
}
