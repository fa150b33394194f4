"""Run a ``shoal check`` as tasks on a Dask cluster, then ``shoal merge`` the parts.

    python3 -m shoal.dask [--scheduler tcp://HOST:PORT | --local N] [--partitions K | --shards K | --per-file]
                          [--retries R] [--shoal PATH] [--parts-dir DIR] check ARGS...

ARGS are those of ``shoal check`` (see ``shoal check --help``; the driver parses them as
check does, from the option list ``shoal check --list-options`` prints).

By default (``--partitions K``) the run goes in three stages, each started when every task of
the one before has succeeded: one task per track input as given (a file, folder or zip)
reads it once and writes its fixes hashed by vessel into K partition files (``shoal check
--partitions K -o DIR INPUT``); one task per partition writes its vessels' traffic, the
real world's evidence (``--from-partitions ... --shard i/K --traffic-only``; not with
``--world simulated``, whose chart is the world: no traffic is taken); one task per
partition audits its vessels whole (``--from-partitions ... --shard i/K --traffic ...``),
writing the part ``--shard i/K`` over all the inputs writes. Vessels with fixes in several
inputs (daily files) are one track each, as in one run. With ``--shards K`` instead: one
task per shard ``--shard i/K``, each reading every input; with ``--per-file``: one task per
input, ``--shard 0/1``, which ``shoal merge`` refuses, naming the vessel, when a vessel has
fixes in two inputs. Exercise mode (``--encounters`` and the options that imply it) is one
exercise: it needs ``--shards``.

Each task runs the ``shoal`` executable, which writes its output atomically; a task that
fails (a non-zero exit other than 1, "a grounding was found", or a process killed by a
signal) is retried R times and, if it still fails, named on stderr, and the exit status is
2: a part is never silently missing. The parts are then merged (``shoal merge``) into the
report one ``shoal check`` of the same arguments writes, byte for byte, and the exit status
is check's (0 no grounding, 1 a grounding). The report is GeoJSON, or a GeoPackage for ``-o
REPORT.gpkg`` (the parts are then GeoPackages). With ``--debrief FOLDER`` and ``--plot
FILE``, whole-run outputs no task holds, each task also writes its debrief record beside its
part (``check --debrief-record``) and the merge makes the pages and the picture from the
records (``shoal merge ... --debrief FOLDER --plot FILE``), those one ``shoal check`` writes;
the records go and are cleaned with the parts.

The grid: coastline sources given to ``--coast`` are built into a grid once, here (``shoal
probe`` into a private cache folder), its bytes scattered to the workers and written once per
worker under its local directory, named by fingerprint; each task finds it there (the grid
cache, SHOAL_CACHE_DIR). A ``.shoalgrid`` given to ``--coast`` is read from its path by every
task (a shared path). Workers must see the inputs, the coast sources and the parts folder
at the same paths as this process (a shared file system), and run from the same folder.

A file at a part's path in ``--parts-dir`` that this driver did not write (it lists its own
parts there, in ``.shoal-dask-parts``) is never replaced: the run stops first, exit status 2.
A scheduler that cannot be reached is one line on stderr and exit status 2.

Needs only Debian's python3-distributed (2022.12) and the ``shoal`` executable, not the
compiled module. No dashboard is started (bokeh is not in Debian 12).
"""

import argparse
import ctypes
import logging
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

# check's options that take no value (FLAGS) and those that take every value up to the next
# option (MULTI), as the shoal CLI parses them: asked from the executable itself (`shoal
# check --list-options`, check_options), so the driver parses what check parses.
FLAGS = set()
MULTI = set()


def check_options(shoal):
    """Fills FLAGS and MULTI from `shoal check --list-options` (NAMES TAB 0|1|many a line)."""
    p = subprocess.run([shoal, "check", "--list-options"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    lines = [line.split("\t") for line in p.stdout.splitlines() if "\t" in line]
    if p.returncode != 0 or not lines:
        raise UsageError("'%s check --list-options' gave no option list (exit status %d): a shoal older than this driver?" % (shoal, p.returncode))
    FLAGS.clear()
    MULTI.clear()
    for names, takes in lines:
        for n in names.split(","):
            if takes == "0":
                FLAGS.add(n)
            elif takes == "many":
                MULTI.add(n)
# check's options that make a run one exercise (exercise mode): checked whole, by --shards only.
EXERCISE = ("--encounters", "--exercise-by", "--roles", "--assess", "--role-column")
# Options a task sets itself; given by the user they are refused or replaced.
REFUSED = {"--shard": "the driver sets --shard itself",
           "--partitions": "the driver partitions the inputs itself", "--from-partitions": "the driver sets it itself",
           "--traffic": "the driver sets it itself", "--traffic-only": "the driver sets it itself",
           "--debrief-record": "the driver sets it itself (give --debrief FOLDER or --plot FILE: the merge makes them)",
           "--format": "the report's format is -o's extension: -o REPORT.geojson or -o REPORT.gpkg"}


class UsageError(Exception):
    pass


def split_check_args(args):
    """check's ARGS as (options: list of [flag, values...], tracks: list, output: str)."""
    options, tracks, output = [], [], None
    i = 0
    while i < len(args):
        a = args[i]
        if a == "--":
            tracks.extend(args[i + 1:])
            break
        if a.startswith("-") and a != "-":
            name, eq, value = a.partition("=")
            if name in REFUSED:
                raise UsageError(f"check option {name}: {REFUSED[name]}")
            if name in FLAGS:
                options.append([a])
                i += 1
                continue
            if eq:
                values = [value]
                i += 1
            elif name in MULTI:
                j = i + 1
                while j < len(args) and not (args[j].startswith("-") and args[j] != "-"):
                    j += 1
                values = args[i + 1:j]
                i = j
            else:
                if i + 1 >= len(args):
                    raise UsageError(f"check option {name} needs a value")
                values = [args[i + 1]]
                i += 2
            if name in ("-o", "--output"):
                output = values[0]
            else:
                options.append([name] + values)
            continue
        tracks.append(a)
        i += 1
    if output is None:
        raise UsageError("check needs -o REPORT.geojson or -o REPORT.gpkg")
    if not tracks:
        raise UsageError("check needs at least one TRACK file or folder")
    return options, tracks, output


def option_values(options, name):
    for o in options:
        if o[0] == name:
            return o[1:]
    return None


def flat(options):
    return [x for o in options for x in o]


def find_shoal(given):
    if given:
        return os.path.abspath(given)
    here = os.path.dirname(os.path.abspath(__file__))
    for candidate in (os.path.join(here, "..", "..", "cli", "shoal"),               # build/python/shoal -> build/cli
                      os.path.join(here, "..", "..", "build", "cli", "shoal")):     # python/shoal -> build/cli
        if os.access(candidate, os.X_OK):
            return os.path.abspath(candidate)
    found = shutil.which("shoal")
    if found:
        return found
    raise UsageError("no shoal executable: give --shoal PATH, or put shoal on PATH")


def build_grid(shoal, options, workdir):
    """Builds the grid of --coast (with the ship and build options) into a private cache
    folder, as check would; returns (file name, bytes), or None for a .shoalgrid given."""
    coast = option_values(options, "--coast") or []
    if len(coast) == 1 and coast[0].endswith(".shoalgrid"):
        return None
    keep = {"--coast", "--ship", "--dims", "--cell", "--ship-length", "--crs", "--layer", "--source-crs", "--ukc",
            "--hazard-depth", "--depth-field", "--danger-radius"}
    cache = os.path.join(workdir, "grid-cache")
    os.makedirs(cache, exist_ok=True)
    poses = os.path.join(workdir, "no-poses.csv")
    with open(poses, "w") as f:
        f.write("lat,lon,heading\n")
    cmd = [shoal, "probe"] + flat([o for o in options if o[0] in keep]) + [poses, "-o", os.devnull]
    env = dict(os.environ, SHOAL_CACHE_DIR=cache)
    p = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.stderr.write(p.stderr)
        raise UsageError("building the grid failed (shoal probe exit status %d)" % p.returncode)
    grids = [n for n in os.listdir(cache) if n.endswith(".shoalgrid")]
    if len(grids) != 1:
        raise RuntimeError("expected one grid in %s, found %s" % (cache, grids))
    with open(os.path.join(cache, grids[0]), "rb") as f:
        return grids[0], f.read()


def _grid_cache_on_worker(grid):
    """The worker's cache folder holding `grid` (name, bytes), written once per worker."""
    from distributed import get_worker
    name, data = grid
    folder = os.path.join(get_worker().local_directory, "shoal-grid-cache")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, name)
    if not (os.path.exists(path) and os.path.getsize(path) == len(data)):
        fd, tmp = tempfile.mkstemp(dir=folder, prefix="." + name + ".tmp-")
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)  # atomic: tasks on other threads see the whole file or none
    return folder


def _die_with_parent():
    """In a child, before exec: SIGTERM when the process that started it dies (Linux
    PR_SET_PDEATHSIG), so that a shoal check never outlives its worker or this driver (it then
    removes its temporaries and exits 143)."""
    try:
        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGTERM, 0, 0, 0)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


def run_task(name, cmd, cwd, grid, fresh=None):
    """One task: runs `cmd` (a shoal check writing its part); raises on failure (Dask retries).
    `fresh`: a partition folder of the driver's work folder that `cmd` creates, removed first
    (an earlier try may have left it). Returns (name, exit status, seconds, check's line about
    the partitions it wrote, or "")."""
    env = dict(os.environ)
    if grid is not None:
        env["SHOAL_CACHE_DIR"] = _grid_cache_on_worker(grid)
    if fresh is not None and os.path.lexists(fresh):
        shutil.rmtree(fresh)
    t0 = time.monotonic()
    p = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                       preexec_fn=_die_with_parent)
    if p.returncode not in (0, 1):
        why = "killed by signal %d" % -p.returncode if p.returncode < 0 else "exit status %d" % p.returncode
        tail = p.stderr.strip().splitlines()[-3:]
        raise RuntimeError("%s: shoal check %s%s" % (name, why, (": " + " | ".join(tail)) if tail else ""))
    said = [line[len("shoal: partitions: "):] for line in p.stderr.splitlines() if line.startswith("shoal: partitions: ")]
    return name, p.returncode, time.monotonic() - t0, said[-1] if said else ""


class _UnretrievedTimeouts(logging.Filter):
    """Drops asyncio's "Future exception was never retrieved" for a TimeoutError: under load,
    distributed.wait(timeout=...) leaves such a future in the client's loop (the wait's timeout,
    which _completed handles), and asyncio says so on stderr when the driver exits, after the
    run's own last line. Any other asyncio message is kept."""

    def filter(self, record):
        exc = record.exc_info[1] if record.exc_info else None
        # By name: asyncio's TimeoutError is not the builtin before Python 3.11 (as _completed has it).
        return not (type(exc).__name__ == "TimeoutError" and record.getMessage().startswith("Future exception was never retrieved"))


def main(argv=None):
    logging.getLogger("asyncio").addFilter(_UnretrievedTimeouts())
    ap = argparse.ArgumentParser(prog="python3 -m shoal.dask", description=__doc__.split("\n\n")[0])
    where = ap.add_mutually_exclusive_group()
    where.add_argument("--scheduler", help="address of a running Dask scheduler, tcp://HOST:PORT")
    where.add_argument("--local", type=int, metavar="N", help="a LocalCluster of N worker processes (default 2)")
    ap.add_argument("--partitions", type=int, metavar="K",
                    help="the default way: each input read once (one task per input), its fixes shuffled by vessel into K partitions, "
                         "each audited whole by one task (default K: twice the --local workers, else one per input, at least 2)")
    ap.add_argument("--shards", type=int, metavar="K", help="instead: K tasks, --shard i/K, each reading every input")
    ap.add_argument("--per-file", action="store_true",
                    help="instead: one task per input, --shard 0/1 (refused at the merge when a vessel has fixes in two inputs)")
    ap.add_argument("--retries", type=int, default=2, metavar="R", help="retries of a failed task (default 2)")
    ap.add_argument("--shoal", help="the shoal executable (default: the build tree's, else PATH)")
    ap.add_argument("--parts-dir", help="folder for the parts (default: a temporary folder beside the report); kept only if given")
    ap.add_argument("--worker-timeout", type=float, default=60, metavar="S",
                    help="give up, exit status 3, when the cluster has had no worker for S seconds with tasks left (default 60)")
    ap.add_argument("command", choices=["check"])
    ap.add_argument("args", nargs=argparse.REMAINDER, help="shoal check's arguments")
    a = ap.parse_args(argv)
    # SIGTERM and SIGHUP end the run as Ctrl-C does: its tasks stopped, its work folder removed.
    previous = {}
    for s in (signal.SIGTERM, signal.SIGHUP):
        if signal.getsignal(s) is not signal.SIG_IGN:  # nohup: stays ignored
            previous[s] = signal.signal(s, _interrupted)
    try:
        return run(a)
    except UsageError as e:
        print("shoal.dask: usage error: %s" % e, file=sys.stderr)
        return 2
    except ClusterError as e:
        print("shoal.dask: error: %s" % e, file=sys.stderr)
        return 2
    except ClusterFailed as e:
        print("shoal.dask: error: %s" % e, file=sys.stderr)
        return 3
    except Interrupted as e:
        print("shoal.dask: interrupted (%s): tasks stopped, no report written" % signal.Signals(e.signum).name, file=sys.stderr)
        return 128 + e.signum
    except KeyboardInterrupt:
        print("shoal.dask: interrupted (SIGINT): tasks stopped, no report written", file=sys.stderr)
        return 130
    finally:
        for s, h in previous.items():
            signal.signal(s, h)


class Interrupted(BaseException):
    """SIGTERM or SIGHUP: unwinds like KeyboardInterrupt, so every cleanup on the way runs."""

    def __init__(self, signum):
        super().__init__(signum)
        self.signum = signum


def _interrupted(signum, frame):
    # Once: a second signal during the cleanup must not cut it short.
    signal.signal(signum, signal.SIG_IGN)
    raise Interrupted(signum)


class ClusterFailed(Exception):
    """The cluster failed under the run (no worker left, the scheduler lost): one line, exit status 3."""


class ClusterError(Exception):
    """The cluster cannot be used (its scheduler unreachable): one line, exit status 2."""


# The parts this driver wrote into a --parts-dir, one name a line: only those it replaces.
PARTS_MARKER = ".shoal-dask-parts"
# Beside each part with --debrief or --plot: its debrief record (check --debrief-record).
RECORD = ".debrief.cbor"


def part_paths(a, tracks, output, parts_dir):
    ext = ".gpkg" if output.endswith(".gpkg") else ".geojson"  # parts of the report's format: merge reads those
    if a.shards:
        return [os.path.join(parts_dir, "part-%05d-of-%05d%s" % (i, a.shards, ext)) for i in range(a.shards)]
    if a.per_file:
        return [os.path.join(parts_dir, "part-%05d%s" % (i, ext)) for i in range(len(tracks))]
    return [os.path.join(parts_dir, "partition-%05d-of-%05d%s" % (i, a.partitions, ext)) for i in range(a.partitions)]


def claim_parts(parts_dir, paths):
    """Refuses to replace a file at a part's path that this driver did not write (a user's own
    file in --parts-dir); lists `paths` as written by it, so that a later run may replace them."""
    marker = os.path.join(parts_dir, PARTS_MARKER)
    ours = set()
    if os.path.exists(marker):
        with open(marker, encoding="utf-8", errors="replace") as f:
            ours = {line.rstrip("\n") for line in f}
    for p in paths:
        name = os.path.basename(p)
        if os.path.lexists(p) and name not in ours:
            raise UsageError("'%s' is there and was not written by shoal.dask: not replaced (give another --parts-dir, or move it)" % p)
    fd, tmp = tempfile.mkstemp(dir=parts_dir, prefix=PARTS_MARKER + ".tmp-")
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        f.write("".join(n + "\n" for n in sorted(ours | {os.path.basename(p) for p in paths})))
    os.replace(tmp, marker)


def run(a):
    if a.local is not None and a.local < 1:
        raise UsageError("--local N needs N >= 1")
    if a.shards is not None and a.shards < 1:
        raise UsageError("--shards K needs K >= 1")
    if a.retries < 0:
        raise UsageError("--retries R needs R >= 0")
    if a.partitions is not None and a.partitions < 1:
        raise UsageError("--partitions K needs K >= 1")
    if sum(x is not None and x is not False for x in (a.shards, a.partitions, a.per_file or None)) > 1:
        raise UsageError("--shards, --partitions and --per-file are three ways to split the run: give one")
    shoal = find_shoal(a.shoal)
    check_options(shoal)
    options, tracks, output = split_check_args(a.args)
    exercise = [name for name in EXERCISE if option_values(options, name) is not None]
    if exercise and a.shards is None:
        raise UsageError("%s: an exercise is checked whole; give --shards K (the exercise is one shard)" % exercise[0])
    if a.shards is None and not a.per_file and a.partitions is None:
        # Twice the workers of --local (a worker takes the next partition while a slow one ends);
        # on a cluster, one partition per input (a year of days: 366 tasks of a day's fixes each).
        a.partitions = 2 * (a.local or 2) if a.scheduler is None else max(2, len(tracks))
    # --debrief and --plot are the whole run's: each task writes its debrief record beside its
    # part (--debrief-record) and the merge makes the pages and the picture from the records.
    pages = []
    for name in ("--debrief", "--plot"):
        values = option_values(options, name)
        if values is not None:
            pages += [name, values[0]]
    a.pages = pages
    options = [o for o in options if o[0] not in ("--cache-dir", "--progress", "--no-progress", "--debrief", "--plot")]
    options.append(["--no-progress"])
    cwd = os.getcwd()
    out_dir = os.path.dirname(os.path.abspath(output))
    if not os.path.isdir(out_dir):
        raise UsageError("cannot write '%s': folder '%s' does not exist" % (output, out_dir))
    if a.parts_dir:  # before any work: a user's file at a part's path is never replaced
        parts_dir = os.path.abspath(a.parts_dir)
        os.makedirs(parts_dir, exist_ok=True)
        claim_parts(parts_dir, [x for p in part_paths(a, tracks, output, parts_dir) for x in ([p, p + RECORD] if pages else [p])])
    workdir = tempfile.mkdtemp(prefix=".shoal-dask-", dir=out_dir)
    parts_dir = os.path.abspath(a.parts_dir) if a.parts_dir else workdir
    try:
        return drive(a, shoal, options, tracks, output, cwd, workdir, parts_dir)
    finally:
        shutil.rmtree(workdir, ignore_errors=True)


def drive(a, shoal, options, tracks, output, cwd, workdir, parts_dir):
    from distributed import Client, LocalCluster

    grid = build_grid(shoal, options, workdir)
    if a.local is None and a.scheduler is None:
        a.local = 2
    if a.local is not None and option_values(options, "--jobs") is None and option_values(options, "-j") is None:
        options.append(["--jobs", str(max(1, (os.cpu_count() or 1) // a.local))])
    parts = part_paths(a, tracks, output, parts_dir)
    record = ["--debrief-record"] if a.pages else []
    stages = []  # each a list of (name, output path, command), run one after the other
    if a.shards:
        stages.append([("shard %d/%d" % (i, a.shards), part,
                         [shoal, "check"] + flat(options) + ["--shard", "%d/%d" % (i, a.shards)] + record + ["-o", part, "--"] + tracks)
                       for i, part in enumerate(parts)])
    elif a.per_file:
        stages.append([(t, part, [shoal, "check"] + flat(options) + ["--shard", "0/1"] + record + ["-o", part, "--", t])
                       for t, part in zip(tracks, parts)])
    else:
        # 1. Each input read once, its fixes hashed by vessel into K partition files; 2. each
        # partition's traffic (the real world's evidence is every vessel's); 3. each partition
        # audited whole, from the partition files of every input and every partition's traffic.
        # The simulated world (the chart is the world) takes no traffic: no stage 2.
        k = a.partitions
        world = option_values(options, "--world")
        simulated = bool(world) and world[-1] == "simulated"
        folders = [os.path.join(workdir, "input-%05d" % j) for j in range(len(tracks))]
        traffic = [] if simulated else [os.path.join(workdir, "traffic-%05d-of-%05d.bin" % (i, k)) for i in range(k)]
        inputs = [x for d in folders for x in ("--from-partitions", d)]
        stages.append([("read %s" % t, d, [shoal, "check"] + flat(options) + ["--partitions", str(k), "-o", d, "--", t])
                       for t, d in zip(tracks, folders)])
        if traffic:
            stages.append([("traffic %d/%d" % (i, k), traffic[i],
                            [shoal, "check"] + flat(options) + inputs + ["--shard", "%d/%d" % (i, k), "--traffic-only", "-o", traffic[i], "--"] + tracks)
                           for i in range(k)])
        stages.append([("partition %d/%d" % (i, k), parts[i],
                        [shoal, "check"] + flat(options) + inputs + ["--shard", "%d/%d" % (i, k)] + record +
                        [x for t in traffic for x in ("--traffic", t)] + ["-o", parts[i], "--"] + tracks)
                       for i in range(k)])

    if a.local is not None:
        cluster = LocalCluster(n_workers=a.local, threads_per_worker=1, processes=True, dashboard_address=None,
                               local_directory=workdir, silence_logs=40)
        client = Client(cluster)
    else:
        cluster = None
        try:
            client = Client(a.scheduler)
        except OSError as e:  # unreachable (distributed.comm.timeouts.connect, 30 s by default)
            raise ClusterError("cannot reach the Dask scheduler at %s (%s); no report written" % (a.scheduler, e)) from None
    failed = []
    futures = {}
    total = sum(len(tasks) for tasks in stages)
    done = 0
    try:
        grid_future = client.scatter(grid, broadcast=True) if grid is not None else None
        print("shoal.dask: %d tasks on %d workers" % (total, len(client.scheduler_info()["workers"])), file=sys.stderr)
        for stage, tasks in enumerate(stages):
            futures = {}
            for n, (name, out, cmd) in enumerate(tasks):
                f = client.submit(run_task, name, cmd, cwd, grid_future, out if len(stages) > 1 and stage == 0 else None,
                                  retries=a.retries, pure=False, key="shoal-check-%d-%d-%s" % (stage, n, os.getpid()))
                futures[f] = name
            for f in _completed(client, futures, a.worker_timeout, len(tasks)):
                done += 1
                try:
                    name, status, seconds, said = f.result()
                    print("shoal.dask: [%d/%d] %s done in %.1f s%s%s" % (done, total, name, seconds, " (groundings)" if status == 1 else "",
                                                                         (": " + said) if said else ""), file=sys.stderr)
                except Exception as e:  # noqa: BLE001 - reported by name, then the run fails
                    failed.append(futures[f])
                    print("shoal.dask: [%d/%d] %s FAILED after %d retries: %s" % (done, total, futures[f], a.retries, e), file=sys.stderr)
            if failed:  # the next stage needs every task of this one
                break
    finally:
        # On an interrupt or a failure too: the tasks cancelled, the local workers (and, with
        # them, their shoal checks: _die_with_parent) stopped before the work folder goes.
        try:
            if futures:
                client.cancel(list(futures))
            client.close(timeout=10)
        except Exception:  # noqa: BLE001 - a lost scheduler: nothing more to tell it
            pass
        if cluster is not None:
            cluster.close(timeout=20)
    if failed:
        print("shoal.dask: error: %d of %d tasks failed (%s); no report written" % (len(failed), total, ", ".join(failed)),
              file=sys.stderr)
        return 2
    # The pages and the picture: drawn on the grid the tasks used (the driver's cache of it).
    env = dict(os.environ)
    if grid is not None:
        env["SHOAL_CACHE_DIR"] = os.path.join(workdir, "grid-cache")
    p = subprocess.run([shoal, "merge"] + parts + ["-o", output] + a.pages, cwd=cwd, env=env, preexec_fn=_die_with_parent)
    return p.returncode


def _completed(client, futures, worker_timeout, total):
    """The futures as they complete, as distributed.as_completed gives them, watching the
    cluster meanwhile: ClusterFailed when it has had no worker for `worker_timeout` seconds
    with tasks left (before: the run waited for ever), or when the scheduler is lost."""
    from distributed import wait
    pending = set(futures)
    no_worker_since = None
    while pending:
        try:
            finished, pending = wait(pending, timeout=1, return_when="FIRST_COMPLETED")
        except (TimeoutError, OSError) as e:  # distributed raises the builtin TimeoutError (3.11: asyncio's is it too)
            if not isinstance(e, TimeoutError):
                raise ClusterFailed("lost the Dask scheduler (%s) with %d of %d tasks left; no report written" % (e, len(pending), total)) from None
            finished = set()
        except Exception as e:  # noqa: BLE001 - asyncio.TimeoutError on Python < 3.11, CommClosedError
            if type(e).__name__ == "CancelledError":  # the scheduler gave the tasks up: the workers holding their data are gone
                raise ClusterFailed("the Dask cluster gave up %d of %d tasks: its workers died or were lost, with the data the tasks need; "
                                    "no report written" % (len(pending), total)) from None
            if type(e).__name__ != "TimeoutError":
                raise ClusterFailed("lost the Dask scheduler (%s: %s) with %d of %d tasks left; no report written" %
                                    (type(e).__name__, e, len(pending), total)) from None
            finished = set()
        for f in finished:
            yield f
        if not pending:
            break
        try:
            workers = len(client.nthreads())
        except Exception as e:  # noqa: BLE001 - the scheduler went away
            raise ClusterFailed("lost the Dask scheduler (%s: %s) with %d of %d tasks left; no report written" %
                                (type(e).__name__, e, len(pending), total)) from None
        if workers:
            no_worker_since = None
        elif no_worker_since is None:
            no_worker_since = time.monotonic()
        elif time.monotonic() - no_worker_since >= worker_timeout:
            raise ClusterFailed("the Dask cluster has had no worker for %g s with %d of %d tasks left (its workers died or were lost); "
                                "no report written (--worker-timeout)" % (worker_timeout, len(pending), total))


if __name__ == "__main__":
    # Run as shoal.dask (not __main__), so the workers unpickle the task as shoal.dask.run_task.
    from shoal import dask as _module

    sys.exit(_module.main())
