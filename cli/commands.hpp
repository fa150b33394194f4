#pragma once
// The subcommands of `shoal`, one file each (import_command.cpp, info_command.cpp,
// probe_command.cpp, check_command.cpp): each adds its options to the CLI11 app in setup() (no
// files opened there) and does its work in run(), returning the exit status.

#include <memory>
#include <vector>

namespace CLI { class App; }

namespace shoal::cli {

/// Exit status of `shoal` (docs/user-guide.md, "Exit status and errors").
enum exit_code : int {
    exit_ok = 0,        ///< success; check: no grounding
    exit_found = 1,     ///< check: at least one grounding or ship collision
    exit_usage = 2,     ///< bad usage or unreadable input
    exit_internal = 3,  ///< a bug in shoal or a failure inside GDAL/GEOS/PROJ that is not the input's fault
};

class Command {
public:
    virtual ~Command() = default;
    virtual void setup(CLI::App& app) = 0;
    virtual int run() = 0;
    bool parsed() const;

protected:
    CLI::App* m_sub = nullptr;
};

std::unique_ptr<Command> make_import_command();
std::unique_ptr<Command> make_info_command();
std::unique_ptr<Command> make_probe_command();
std::unique_ptr<Command> make_check_command();
std::unique_ptr<Command> make_merge_command();

/// Every command, in the order `shoal --help` lists them.
std::vector<std::unique_ptr<Command>> make_commands();

}  // namespace shoal::cli
