#pragma once
// The subcommands of `shoal`: each adds its options to the CLI11 app in setup() (no files
// opened there) and does its work in run(), returning the exit status.

#include <memory>
#include <vector>

namespace CLI { class App; }

namespace shoal::cli {

enum exit_code : int { exit_ok = 0, exit_found = 1, exit_usage = 2 };

class Command {
public:
    virtual ~Command() = default;
    virtual void setup(CLI::App& app) = 0;
    virtual int run() = 0;
    bool parsed() const;

protected:
    CLI::App* m_sub = nullptr;
};

std::vector<std::unique_ptr<Command>> make_commands();

}  // namespace shoal::cli
