#include "commands.hpp"

#include <CLI/CLI.hpp>

namespace shoal::cli {

bool Command::parsed() const { return m_sub && m_sub->parsed(); }

std::vector<std::unique_ptr<Command>> make_commands() {
    std::vector<std::unique_ptr<Command>> v;
    v.push_back(make_import_command());
    v.push_back(make_info_command());
    v.push_back(make_probe_command());
    v.push_back(make_check_command());
    v.push_back(make_merge_command());
    return v;
}

}  // namespace shoal::cli
