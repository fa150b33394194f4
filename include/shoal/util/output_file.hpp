#pragma once
/// Output files: checked before any work, written beside their targets under a temporary name
/// that says it is shoal's, and put in place (renamed over the targets) together at the end.
///
/// A temporary is named `.NAME.shoal.tmp-PID-XXXXXXXX.EXT` beside the target `NAME` (EXT: the
/// target's extension, so GDAL drivers see the format they expect), with PID the writer's
/// process id. While it is written it is listed in `TempFileInProgress`, so a signal handler
/// that calls `remove_temp_files_in_progress` deletes it; a temporary left by a process that
/// was killed outright (SIGKILL, the OOM killer, a power cut) is recognised by its name and
/// dead PID and removed the next time an output is staged beside the same target.

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace shoal {

class TempFileInProgress;

/// Whether the file at a path is one shoal wrote (of the kind an output holds): read from its
/// first bytes (file_head), or by opening it.
using WrittenByShoal = std::function<bool(const std::string& path)>;

/// An output the user asked for, and how messages name it.
struct OutputSpec {
    std::string path;                  ///< "" or "-": stdout
    std::string option = "-o";         ///< the option that named it ("-o", "--plot"); used in "choose another -o"
    std::string role = "the output";   ///< what it is ("the report", "the picture")
    /// Set: an existing, non-empty regular file at `path` is replaced only when this says shoal
    /// wrote it (check_outputs refuses any other: a track, a chart, someone's notes given as -o
    /// by a slip). Unset: the caller protects the file itself (a sidecar left as it is).
    WrittenByShoal ours = {};
};

/// The first `n` bytes of the file at `path` (fewer when it is shorter; "" when unreadable): what
/// the recognisers of shoal's own files read (each beside the writer of its format:
/// grid::looks_like_grid, io::is_probe_output, report::is_shoal_geojson_report and
/// is_shoal_gpkg_report, report::is_shoal_picture).
std::string file_head(const std::string& path, std::size_t n);

/// Standard output by any of its names: "" and "-" (stdout), /dev/stdout, /dev/fd/1, /proc/self/fd/1.
bool is_standard_output(const std::string& path) noexcept;
/// A path under /dev/ or /proc/: written straight to what it stands for, never replaced, no
/// companion file (a style) beside it.
bool is_system_path(const std::string& path) noexcept;

/// Throws InputError unless a file can be written at `path`: its folder exists and it is not
/// itself a folder ("cannot write 'P': folder 'D' does not exist", "cannot write 'P': it is a
/// directory"). Standard output (is_standard_output) always passes.
void check_output_place(const std::string& path);

/// Before any work: every output can be written where asked (check_output_place); none is one
/// of `inputs`, the same file by any path (UsageError "the output 'O' is the input 'I':
/// writing it would destroy the input; choose another OPTION"); and no two outputs are the
/// same file, or both stdout (UsageError "OPTION 'B' is ROLE OPTION 'A': choose another file
/// for ROLE", e.g. "--plot 'r.geojson' is the report -o 'r.geojson': choose another file for
/// the picture"); and an existing file that an output with OutputSpec::ours would replace is
/// shoal's (UsageError "'P' exists and is not a file shoal wrote (ROLE): shoal replaces only its
/// own files; remove it first, or choose another OPTION").
void check_outputs(const std::vector<OutputSpec>& outputs, const std::vector<std::string>& inputs);

/// One output file being written. The constructor checks the place (check_output_place),
/// removes stale temporaries of dead processes beside the target, and picks the temporary's
/// name; `write` (or a library such as GDAL writing to `temp_path()`) fills it; `commit`
/// renames it over the target. Standard output (is_standard_output) and an existing target
/// under /dev/ or /proc/ (is_system_path) or that is neither a
/// regular file nor a folder (a device such as /dev/null, a pipe) are *direct*: `write` writes
/// to them at once and `commit` has nothing to do. An output destroyed before its commit
/// removes its temporary (with SQLite's -journal, -wal and -shm companions): the target keeps
/// its old contents.
class StagedOutput {
public:
    explicit StagedOutput(std::string target);
    StagedOutput(StagedOutput&&) noexcept;
    StagedOutput& operator=(StagedOutput&&) noexcept;
    ~StagedOutput();

    const std::string& target() const noexcept { return m_target; }
    bool direct() const noexcept { return m_temp.empty(); }
    /// Where the contents go before the commit; empty when direct.
    const std::string& temp_path() const noexcept { return m_temp; }

    /// Writes all of `bytes`: to the temporary (flushed to disk), or straight to a direct
    /// target. Throws InputError naming the target (disk full, ...), removing the temporary.
    void write(std::string_view bytes);
    /// A sink that takes the contents piece by piece.
    using Sink = std::function<void(std::string_view)>;
    /// Writes what `produce` hands to its sink, in order, as `write` writes one string, without
    /// holding it all in memory. If `produce` throws, the temporary is removed and the
    /// exception goes on (a direct target keeps what was written).
    void write_streamed(const std::function<void(const Sink&)>& produce);
    /// Puts the temporary in place of the target (a rename); nothing for a direct target.
    /// Throws InputError naming the target, removing the temporary.
    void commit();

private:
    void discard() noexcept;
    std::string m_target, m_temp;
    std::unique_ptr<TempFileInProgress> m_listed;
};

/// Commits every output in order, with SIGINT, SIGTERM, SIGHUP and SIGQUIT held back until the
/// last rename is done, so that a report, its picture and its style are replaced together at
/// the very end (a signal that arrives meanwhile is handled just after). Throws the first
/// failure (the outputs after it are not committed; their temporaries are removed).
void commit_all(std::vector<StagedOutput>& outputs);

/// Removes the temporaries of `target` (see above) whose writer process no longer exists;
/// returns how many files were removed. Temporaries of live processes are left alone.
std::size_t remove_stale_temporaries(const std::string& target);

/// The temporary's name prefix beside `target`: ".NAME.shoal.tmp-".
std::string temporary_prefix(const std::string& target);

}  // namespace shoal
