#pragma once
// What every `shoal` process does around a command, the same in the executable's own probe of a
// grid file (grid_probe.cpp) and in the full command module (main.cpp): fewer malloc arenas,
// Ctrl-C removing the temporary files being written, and the exceptions said as messages with
// their exit status.

#include "util/lazy_libraries.hpp"
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <stdexcept>
#include <thread>

#include "commands.hpp"
#include "options.hpp"
#include <shoal/util/atomic_file.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/printable.hpp>

namespace shoal::cli {

/// Ctrl-C (SIGINT), SIGTERM, SIGHUP (the terminal closed) or SIGQUIT: delete the temporary files being written (a report, a grid,
/// a cache entry: the targets are only ever replaced whole by a rename, so none is left
/// half-written), say so, and exit with 128 + the signal number (130 for Ctrl-C).
/// (The executable and the command module each hold the registry of the files they write: each
/// installs the handler that empties its own, the executable at its start, the module when it is
/// called; a signal ignored from the start stays ignored in both.)
inline void on_interrupt(int sig) {
    shoal::remove_temp_files_in_progress();
    static const char message[] = "\nshoal: interrupted\n";
    [[maybe_unused]] const auto n = ::write(STDERR_FILENO, message, sizeof message - 1);
    ::_exit(128 + sig);
}

/// Around the moment a run puts its outputs in place (commit_all): the interrupts held from
/// before it, so that one that comes while or after the files are renamed is not taken as
/// "interrupted" (exit 130, the summary not printed, a grounding's exit 1 hidden) of a run whose
/// every file is written. outputs_in_place() then ignores them (a pending one is discarded) for
/// the little the run still does; release_interrupts() gives them back when the commit failed.
inline sigset_t hold_interrupts() {
    sigset_t hold, old;
    sigemptyset(&hold);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaddset(&hold, sig);
    ::pthread_sigmask(SIG_BLOCK, &hold, &old);
    return old;
}
inline void release_interrupts(const sigset_t& old) { ::pthread_sigmask(SIG_SETMASK, &old, nullptr); }
inline void outputs_in_place(const sigset_t& old) {
    for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
        struct sigaction sa{};
        sa.sa_handler = SIG_IGN;
        sigemptyset(&sa.sa_mask);
        ::sigaction(sig, &sa, nullptr);
    }
    release_interrupts(old);
}

inline void handle_interrupts() {
    for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
        struct sigaction old{};
        // A signal ignored when we started (nohup, `cmd &` in a script) stays ignored.
        if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        struct sigaction sa{};
        sa.sa_handler = on_interrupt;
        sigemptyset(&sa.sa_mask);
        ::sigaction(sig, &sa, nullptr);
    }
}

/// glibc's malloc gives each thread an arena of its own, up to 8 a core: what the reading
/// threads free (the fixes held packed until a track is swept) stays in their arenas while the
/// sweeping threads grow theirs with the results. One arena a core lets the sweep reuse it: a
/// 10 M-row day peaks at about 505 MB instead of 550-630 (docs/performance.md), in the same
/// time. MALLOC_ARENA_MAX, when set, decides instead.
inline void fewer_malloc_arenas() {
#ifdef __GLIBC__
    if (std::getenv("MALLOC_ARENA_MAX") == nullptr) mallopt(M_ARENA_MAX, static_cast<int>(std::max(2u, std::thread::hardware_concurrency())));
#endif
}

/// Standard input, output and error, when the process was started with one closed, opened on
/// /dev/null for reading: else the first file the run opens would take its number, and be read
/// as `-` (standard input) or written over by a message (standard error). Read-only, so that a
/// report written to a closed standard output (`-o -`) still fails to be written, as before.
inline void keep_standard_streams() {
    for (int fd = 0; fd <= 2; ++fd)
        if (::fcntl(fd, F_GETFD) == -1 && errno == EBADF) {
            const int got = ::open("/dev/null", O_RDONLY);  // the lowest free number: fd
            if (got > fd) ::close(got);
        }
}

/// Runs `command` (returning its exit status) and says its exception, if any, on stderr with the
/// exit status it means (docs/user-guide.md, "Exit status and errors").
template <class F>
int run_reporting_errors(F&& command) {
    try {
        return command();
    } catch (const shoal::InputError& e) {
        std::fprintf(stderr, "shoal: error: %s\n", shoal::printable(in_cli_terms(e.what())).c_str());
        return exit_usage;
    } catch (const shoal::UsageError& e) {
        std::fprintf(stderr, "shoal: usage error: %s\n", shoal::printable(in_cli_terms(e.what())).c_str());
        return exit_usage;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "shoal: error: out of memory (try a larger --cell, or fewer inputs at once)\n");
        return exit_usage;
    } catch (const shoal::detail::MissingLibrary& e) {
        std::fprintf(stderr, "shoal: internal error: %s (the installation is incomplete: install that library, or reinstall shoal)\n",
                     shoal::printable(e.what()).c_str());
        return exit_internal;
    } catch (const shoal::LibraryError& e) {
        std::fprintf(stderr, "shoal: internal error: %s (not the input's fault: please report it)\n", shoal::printable(e.what()).c_str());
        return exit_internal;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "shoal: internal error: %s (a bug in shoal: please report it)\n", shoal::printable(e.what()).c_str());
        return exit_internal;
    }
}

}  // namespace shoal::cli
