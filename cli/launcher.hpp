#pragma once
// The `shoal` executable and its full command module (docs/performance.md, "Start-up"): the
// executable (launcher.cpp, grid_probe.cpp) links no GDAL and runs a probe of a .shoalgrid
// itself; every other command line goes to the module, which it loads from beside itself (the
// build tree) or from SHOAL_CLI_MODULE_DIR relative to it (an install: ../lib/shoal).

/// The module's one exported function: the whole front end (main.cpp), as main() was.
#define SHOAL_CLI_ENTRY __attribute__((visibility("default")))
#define SHOAL_CLI_ENTRY_NAME "shoal_cli_main"
#define SHOAL_CLI_MODULE_FILE "libshoal_cli_full.so"

extern "C" {
/// Runs `shoal ARGS...` with every command; returns the exit status.
int shoal_cli_main(int argc, char** argv);
}

namespace shoal::cli {

/// The executable's own probe of a grid file: true (and the exit status in `rc`) when it ran
/// it; false, having printed and changed nothing, when the command line is anything else (another
/// command, help, a usage error, a coast that is no grid file, an input GDAL must read: a .gz or
/// zip, standard input, a /vsi path, a FIFO), which the full module then runs.
bool run_grid_probe(int argc, char** argv, int& rc);

}  // namespace shoal::cli
