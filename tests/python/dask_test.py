"""python3 -m shoal.dask against shoal check: the same report, byte for byte, with tasks
killed and retried, and failures named. Run by ctest with /usr/bin/python3:

    dask_test.py SHOAL_BINARY SOURCE_ROOT CASE    (CASE: partitions, daily, per_file, shards, gpkg, killed, failing, ...)
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

shoal, root, case = sys.argv[1], sys.argv[2], sys.argv[3]
cases = os.path.join(root, "tests", "data", "tracks", "ais_cases")
coast = ["--coast", os.path.join(root, "examples", "data", "gof_helsinki_land.geojson"), "--dims", "100,20,8,8"]
tmp = tempfile.mkdtemp(prefix="shoal-dask-test-")
env = dict(os.environ, SHOAL_CACHE_DIR=os.path.join(tmp, "cache"),
           PYTHONPATH=os.path.join(root, "python") + os.pathsep + os.environ.get("PYTHONPATH", ""))
failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAILED: " + what, file=sys.stderr)


def run(cmd):
    p = subprocess.run(cmd, env=env, cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=240)
    return p.returncode, p.stdout, p.stderr


def read(path):
    with open(path, "rb") as f:
        return f.read()


files = [os.path.join(cases, f) for f in ("aground_at_speed.csv", "jump_and_null_island.csv", "berthing_sideways.csv",
                                          "passes_clear.csv", "moored_then_leaves.csv")]
single = os.path.join(tmp, "single.geojson")
status, _, err = run([shoal, "check"] + coast + files + ["-o", single, "--no-progress"])
expect(status == 1, "single run exit 1 (a grounding): %d %s" % (status, err))


def dask(args, out, shoal_exe=shoal):
    return run(["/usr/bin/python3", "-m", "shoal.dask", "--local", "2", "--shoal", shoal_exe] + args +
               ["check"] + coast + files + ["-o", out])


# Each input read by exactly one task: the task log's "read INPUT done ...: INPUT: N files, B bytes read".
def reads_in_log(err):
    return [line.split(" read ", 1)[1].split(" done in ")[0] for line in err.splitlines() if "] read " in line and " done in " in line]


def split_days(names, folder, bad_row_day=1):
    """Three 'daily' files from the cases: each vessel's rows cut in thirds by time, a third to a
    day (as a day's end cuts a voyage); day `bad_row_day` holds a bad row (its line in the problems)."""
    header, rows = None, []
    for n in names:
        with open(os.path.join(cases, n)) as f:
            lines = f.read().splitlines()
        header = lines[0]
        body = lines[1:]
        for i, line in enumerate(body):
            rows.append((3 * i // len(body), line))
    os.makedirs(folder)
    days = []
    for d in range(3):
        path = os.path.join(folder, "aisdk-2024-05-%02d.csv" % (7 + d))
        with open(path, "w") as f:
            f.write(header + "\n")
            day = [line for k, line in rows if k == d]
            for i, line in enumerate(day):
                f.write(line + "\n")
                if d == bad_row_day and i == 10:
                    f.write("230990007,2024-05-07T25:61:00,60.1,25.2,12.0,75.0,75,BAD TIME,,,70,0,120,16,7.0,70,A\n")
        days.append(path)
    return days


try:
    if case in ("partitions", "per_file", "shards"):
        out = os.path.join(tmp, "dask.geojson")
        status, _, err = dask({"shards": ["--shards", "3"], "per_file": ["--per-file"], "partitions": []}[case], out)
        expect(status == 1, "dask exit 1 as check's: %d\n%s" % (status, err))
        expect(os.path.exists(out) and read(out) == read(single), "dask report == shoal check report, byte for byte")
        expect(os.path.exists(os.path.join(tmp, "dask.qml")), "the QGIS style beside it")
        expect({"per_file": "[5/5]", "shards": "[3/3]", "partitions": "[13/13]"}[case] in err, "progress on stderr: " + err)
        if case == "partitions":  # the default: 5 reads, 4 partitions' traffic, 4 partitions audited
            expect(sorted(reads_in_log(err)) == sorted(files), "each input read by one task: %s" % reads_in_log(err))
        expect(not [n for n in os.listdir(tmp) if n.startswith(".shoal-dask-")], "no work folder left behind")
    elif case == "daily":
        # Vessels spanning daily files, the normal case: three days, every vessel in all three,
        # a bad row in the second day. The default mode (read once, shuffled by vessel) gives
        # one run's report byte for byte, GeoJSON and GeoPackage, its problems those of one run.
        days = split_days(["aground_at_speed.csv", "jump_and_null_island.csv", "berthing_sideways.csv", "passes_clear.csv",
                           "moored_then_leaves.csv", "pilot_berthing.csv", "ferry_hourly.csv"], os.path.join(tmp, "days"))
        for ext in ("geojson", "gpkg"):
            for d in ("single-" + ext, "dask-" + ext):
                os.makedirs(os.path.join(tmp, d))
            one, out = os.path.join(tmp, "single-" + ext, "week." + ext), os.path.join(tmp, "dask-" + ext, "week." + ext)
            status, _, err1 = run([shoal, "check"] + coast + days + ["-o", one, "--no-progress"])
            expect(status == 1, "single run over the days exit 1: %d %s" % (status, err1))
            expect("is in 3 files" in err1, "vessels span the three days: " + err1)
            status, _, err = run(["/usr/bin/python3", "-m", "shoal.dask", "--local", "2", "--shoal", shoal, "--partitions", "3", "check"] + coast +
                                 days + ["-o", out])
            expect(status == 1, "dask over the days exit 1 as check's (%s): %d\n%s" % (ext, status, err))
            expect(os.path.exists(out) and read(out) == read(one), "dask %s over daily files == shoal check's, byte for byte" % ext)
            expect(sorted(reads_in_log(err)) == sorted(days), "each day read by exactly one task (%s): %s" % (ext, reads_in_log(err)))
            expect("[9/9]" in err, "3 reads, 3 traffic, 3 partitions: " + err)
            if ext == "geojson":
                # The simulated world (the chart is the world) needs no traffic: no traffic stage.
                sim_one, sim_out = os.path.join(tmp, "single-" + ext, "sim." + ext), os.path.join(tmp, "dask-" + ext, "sim." + ext)
                status, _, err1 = run([shoal, "check", "--world", "simulated"] + coast + days + ["-o", sim_one, "--no-progress"])
                expect(status == 1, "single simulated run exit 1: %d %s" % (status, err1))
                status, _, err = run(["/usr/bin/python3", "-m", "shoal.dask", "--local", "2", "--shoal", shoal, "--partitions", "3", "check",
                                      "--world", "simulated"] + coast + days + ["-o", sim_out])
                expect(status == 1 and read(sim_out) == read(sim_one), "dask simulated == shoal check's, byte for byte: %d\n%s" % (status, err))
                expect("[6/6]" in err and "traffic 0/" not in err, "3 reads and 3 partitions, no traffic stage: " + err)
            if ext == "geojson":
                with open(out) as f:
                    problems = json.load(f)["shoal"]["problems"]
                bad = [p for p in problems if "BAD TIME" in json.dumps(p) or "25:61" in json.dumps(p)]
                expect(len(bad) == 1 and days[1] in json.dumps(bad[0]), "the bad row kept with its day file and line: %s" % problems)
        # The partition steps by hand: a folder of another input, or of another count, is refused
        # naming it; an existing folder is never replaced; two inputs to one read are refused.
        pdir = os.path.join(tmp, "parts")
        os.makedirs(pdir)
        folders = []
        for j, d in enumerate(days):
            folders.append(os.path.join(pdir, "in-%d" % j))
            status, _, err = run([shoal, "check"] + coast + ["--partitions", "2", "-o", folders[-1], "--", d])
            expect(status == 0 and "bytes read" in err, "check --partitions exit 0: %d %s" % (status, err))
        status, _, err = run([shoal, "check"] + coast + ["--partitions", "2", "-o", folders[0], "--", days[0]])
        expect(status == 2 and "exists: partitions are written to a new folder, nothing replaced" in err, "an existing folder kept: " + err)
        status, _, err = run([shoal, "check"] + coast + ["--partitions", "2", "-o", os.path.join(pdir, "two"), "--"] + days[:2])
        expect(status == 2 and "one TRACK input" in err, "two inputs to one read refused: " + err)
        swapped = [x for f in (folders[1], folders[0], folders[2]) for x in ("--from-partitions", f)]
        status, _, err = run([shoal, "check"] + coast + swapped + ["--shard", "0/2", "--traffic-only", "-o", os.path.join(pdir, "t0"), "--"] + days)
        expect(status == 2 and "the partitions of '%s', not of '%s'" % (days[1], days[0]) in err, "inputs out of order refused: " + err)
        given = [x for f in folders for x in ("--from-partitions", f)]
        status, _, err = run([shoal, "check"] + coast + given + ["--shard", "0/3", "--traffic-only", "-o", os.path.join(pdir, "t0"), "--"] + days)
        expect(status == 2 and "written in 2 partitions, not 3" in err, "another count refused: " + err)
        status, _, err = run([shoal, "check"] + coast + given + ["--shard", "0/2", "-o", os.path.join(pdir, "p0.geojson"), "--"] + days)
        expect(status == 2 and "needs --traffic" in err, "the real world without the traffic refused: " + err)
        # The per-file mode refuses the same days at the merge (one run merges the vessels).
        status, _, err = run(["/usr/bin/python3", "-m", "shoal.dask", "--local", "2", "--shoal", shoal, "--per-file", "check"] + coast + days +
                             ["-o", os.path.join(tmp, "per-file.geojson")])
        expect(status == 2 and "has tracks in" in err, "--per-file over days refused at the merge: %d %s" % (status, err))
    elif case == "gpkg":
        # -o REPORT.gpkg: GeoPackage parts, merged into the GeoPackage one check writes (the
        # same file name: its QGIS project names the file).
        for d in ("single-gpkg", "dask-gpkg"):
            os.makedirs(os.path.join(tmp, d))
        single_gpkg, out = os.path.join(tmp, "single-gpkg", "report.gpkg"), os.path.join(tmp, "dask-gpkg", "report.gpkg")
        status, _, err = run([shoal, "check"] + coast + files + ["-o", single_gpkg, "--no-progress"])
        expect(status == 1, "single run to .gpkg exit 1: %d %s" % (status, err))
        status, _, err = dask(["--shards", "3"], out)
        expect(status == 1, "dask to .gpkg exit 1 as check's: %d\n%s" % (status, err))
        expect(os.path.exists(out) and read(out) == read(single_gpkg), "dask GeoPackage == shoal check's, byte for byte")
    elif case == "killed":
        # A real process death: the wrapper SIGKILLs itself the first time it runs each part.
        wrapper = os.path.join(tmp, "dies-once.sh")
        with open(wrapper, "w") as f:
            f.write('#!/bin/sh\n'
                    'if [ "$1" = check ]; then\n'
                    '  prev=; for a; do [ "$prev" = -o ] && out=$a; prev=$a; done\n'
                    '  marker="%s/killed-$(basename "$out")"\n'
                    '  if [ -n "$out" ] && [ ! -e "$marker" ]; then : > "$marker"; kill -9 $$; fi\n'
                    'fi\n'
                    'exec "%s" "$@"\n' % (tmp, shoal))
        os.chmod(wrapper, 0o755)
        out = os.path.join(tmp, "killed.geojson")
        status, _, err = dask(["--retries", "2"], out, wrapper)
        killed = [n for n in os.listdir(tmp) if n.startswith("killed-")]
        expect(len(killed) == len(files) + 4 + 4, "every task (5 reads, 4 traffic, 4 partitions) was killed once: %s" % killed)
        expect(status == 1, "exit 1 after retries: %d\n%s" % (status, err))
        expect(os.path.exists(out) and read(out) == read(single), "the report of killed-and-retried tasks == shoal check's")
    elif case == "failing":
        # A task that always dies is named, the exit status is 2, and no report is written.
        wrapper = os.path.join(tmp, "always-dies.sh")
        with open(wrapper, "w") as f:
            f.write('#!/bin/sh\ncase "$*" in *jump_and_null_island*) kill -9 $$;; esac\nexec "%s" "$@"\n' % shoal)
        os.chmod(wrapper, 0o755)
        out = os.path.join(tmp, "failing.geojson")
        status, _, err = dask(["--retries", "1"], out, wrapper)
        expect(status == 2, "exit 2 when a task fails after its retries: %d" % status)
        expect("read %s FAILED after 1 retries" % os.path.join(cases, "jump_and_null_island.csv") in err, "the failed task named: " + err)
        expect("traffic 0/" not in err, "no later stage started without every input read: " + err)
        expect("killed by signal 9" in err, "how it failed: " + err)
        expect(not os.path.exists(out), "no report written")
        # One run per file, a vessel in two files: merge refuses (one run would merge the tracks).
        half = os.path.join(tmp, "again.csv")
        shutil.copy(os.path.join(cases, "passes_clear.csv"), half)
        files.append(half)
        status, _, err = dask(["--per-file"], out)
        expect(status == 2 and "vessel 230990007 has tracks in" in err, "--per-file: a vessel spanning files is refused: %d %s" % (status, err))
        status, _, err = dask([], out)
        expect(status in (0, 1), "the default (partitions by vessel) takes a vessel spanning files: %d %s" % (status, err))
        status, _, err = dask(["--shards", "2"], out)
        expect(status in (0, 1), "with --shards it is one run: %d %s" % (status, err))
    elif case == "hostile":
        # --parts-dir holding a file of the user's at a part's name: never replaced, exit 2, one line.
        mine = os.path.join(tmp, "mine")
        os.makedirs(mine)
        with open(os.path.join(mine, "partition-00000-of-00004.geojson"), "w") as f:
            f.write("my own notes\n")
        out = os.path.join(tmp, "hostile.geojson")
        status, _, err = dask(["--parts-dir", mine], out)
        expect(status == 2, "exit 2 when a part would replace a user's file: %d\n%s" % (status, err))
        expect("partition-00000-of-00004.geojson' is there and was not written by shoal.dask: not replaced" in err, "the file named: " + err)
        expect(read(os.path.join(mine, "partition-00000-of-00004.geojson")) == b"my own notes\n", "the user's file as it was")
        expect(not os.path.exists(out), "no report written")
        # --debrief-record: the driver's to give (with --debrief or --plot, the merge makes the
        # pages from the tasks' records); refused before any work, one line.
        status, _, err = run(["/usr/bin/python3", "-m", "shoal.dask", "--local", "1", "--shoal", shoal, "check"] + coast + files +
                             ["--debrief-record", "-o", out])
        expect(status == 2, "exit 2 for --debrief-record: %d\n%s" % (status, err))
        expect(err.count("\n") == 1 and err.startswith("shoal.dask: usage error: check option --debrief-record: the driver sets it itself"),
               "one line saying why: " + err)
        expect(not os.path.exists(out), "no report")
        expect(not [n for n in os.listdir(tmp) if n.startswith(".shoal-dask-")], "no work folder left behind")
        # Its own parts of an earlier run it replaces without a word.
        own = os.path.join(tmp, "own")
        for attempt in (1, 2):
            status, _, err = dask(["--parts-dir", own], out)
            expect(status == 1, "run %d into its own --parts-dir: %d\n%s" % (attempt, status, err))
            expect(os.path.exists(out) and read(out) == read(single), "run %d: the report == shoal check's" % attempt)
        # The scheduler unreachable: one line and exit 2 (before: a 57-line traceback, exit 1).
        env["DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT"] = "2s"
        os.remove(out)
        status, _, err = run(["/usr/bin/python3", "-m", "shoal.dask", "--scheduler", "tcp://127.0.0.1:1", "--shoal", shoal, "check"] + coast +
                             files + ["-o", out])
        expect(status == 2, "exit 2 when the scheduler cannot be reached: %d\n%s" % (status, err))
        expect("Traceback" not in err, "no traceback: " + err)
        expect(err.count("\n") == 1 and err.startswith("shoal.dask: error: cannot reach the Dask scheduler at tcp://127.0.0.1:1 ("),
               "one line naming the scheduler: " + err)
        expect(not os.path.exists(out), "no report written")
        expect(not [n for n in os.listdir(tmp) if n.startswith(".shoal-dask-")], "no work folder left behind")
    elif case == "debrief":
        # --debrief and --plot: each task writes its debrief record beside its part, the merge
        # makes the pages and the picture, those of one shoal check (before: refused, and before
        # that every task wrote the same pages over the others'). The default mode (partitions:
        # the run's one page spans every partition), and an exercise in --shards.
        for mode, extra in (([], []), (["--shards", "2"], ["--encounters"])):
            name = "partitions" if not mode else "shards"
            one_dir, dask_dir = os.path.join(tmp, "one-" + name), os.path.join(tmp, "dask-" + name)
            os.makedirs(one_dir)
            os.makedirs(dask_dir)
            status, _, err = run([shoal, "check"] + coast + extra + files + ["-o", os.path.join(one_dir, "r.geojson"), "--no-progress",
                                                                             "--debrief", os.path.join(one_dir, "pages"), "--plot",
                                                                             os.path.join(one_dir, "r.svg")])
            expect(status == 1, "single run with --debrief --plot (%s): %d %s" % (name, status, err))
            out = os.path.join(dask_dir, "r.geojson")
            status, _, err = run(["/usr/bin/python3", "-m", "shoal.dask", "--local", "2", "--shoal", shoal] + mode + ["check"] + coast + extra +
                                 files + ["--debrief", os.path.join(dask_dir, "pages"), "--plot", os.path.join(dask_dir, "r.svg"), "-o", out])
            expect(status == 1, "dask with --debrief --plot (%s): exit 1 as check's: %d\n%s" % (name, status, err))
            expect(os.path.exists(out) and read(out) == read(os.path.join(one_dir, "r.geojson")), "the report == check's (%s)" % name)
            pages = sorted(os.listdir(os.path.join(one_dir, "pages")))
            expect(pages == ["run.html"], "one page: %s" % pages)
            for page in pages:
                mine = os.path.join(dask_dir, "pages", page)
                expect(os.path.exists(mine) and read(mine) == read(os.path.join(one_dir, "pages", page)), "page %s == check's (%s)" % (page, name))
            expect(os.path.exists(os.path.join(dask_dir, "r.svg")) and read(os.path.join(dask_dir, "r.svg")) == read(os.path.join(one_dir, "r.svg")),
                   "the picture == check's (%s)" % name)
            expect(not [n for n in os.listdir(tmp) if n.startswith(".shoal-dask-")], "no work folder (parts, records) left behind")
            expect(not [n for n in os.listdir(dask_dir) if n.endswith(".debrief.cbor")], "no record beside the report")
        # --parts-dir: the records stay with the parts, and a second run replaces its own.
        keep = os.path.join(tmp, "keep")
        for attempt in (1, 2):
            out = os.path.join(tmp, "kept.geojson")
            status, _, err = run(["/usr/bin/python3", "-m", "shoal.dask", "--local", "2", "--shoal", shoal, "--shards", "2", "--parts-dir", keep,
                                  "check"] + coast + files + ["--plot", os.path.join(tmp, "kept.svg"), "-o", out])
            expect(status == 1, "run %d into --parts-dir with --plot: %d\n%s" % (attempt, status, err))
            expect(sorted(n for n in os.listdir(keep) if n.endswith(".debrief.cbor")) ==
                   ["part-%05d-of-00002.geojson.debrief.cbor" % i for i in range(2)], "run %d: a record beside each part: %s" % (attempt, os.listdir(keep)))
            expect(read(os.path.join(tmp, "kept.svg")) == read(os.path.join(tmp, "one-partitions", "r.svg")), "run %d: the picture == check's" % attempt)
    elif case in ("signal", "lost_worker"):
        # Tasks that run long (the wrapper records its pid, then becomes a sleep): the driver is
        # sent SIGTERM (signal), or its only worker dies mid-task (lost_worker). Before: SIGTERM
        # left the running checks as orphans and .shoal-dask-* folders beside the report; a lost
        # worker made the driver wait for ever.
        pids = os.path.join(tmp, "pids")
        wrapper = os.path.join(tmp, "slow.sh")
        with open(wrapper, "w") as f:
            f.write('#!/bin/sh\ncase "$1 $2" in "check --list-options") ;; check*) echo $$ >> "%s"; exec sleep 120;; esac\nexec "%s" "$@"\n' % (pids, shoal))
        os.chmod(wrapper, 0o755)
        out = os.path.join(tmp, case + ".geojson")
        procs = []

        def started(timeout=90):
            t0 = time.monotonic()
            while time.monotonic() - t0 < timeout:
                if os.path.exists(pids) and open(pids).read().strip():
                    return [int(x) for x in open(pids).read().split()]
                time.sleep(0.2)
            return []

        def alive(pid):
            try:
                os.kill(pid, 0)
                return True
            except ProcessLookupError:
                return False

        try:
            if case == "signal":
                driver = subprocess.Popen(["/usr/bin/python3", "-m", "shoal.dask", "--local", "1", "--shoal", wrapper, "check"] + coast + files +
                                          ["-o", out], env=env, cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                procs.append(driver)
                running = started()
                expect(running, "a task started")
                driver.send_signal(signal.SIGTERM)
            else:
                sched_file = os.path.join(tmp, "scheduler.json")
                procs.append(subprocess.Popen(["/usr/bin/python3", "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0",
                                               "--scheduler-file", sched_file, "--no-dashboard"], env=env, cwd=tmp,
                                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
                t0 = time.monotonic()
                while not os.path.exists(sched_file) and time.monotonic() - t0 < 60:
                    time.sleep(0.2)
                time.sleep(0.5)
                with open(sched_file) as f:
                    address = json.load(f)["address"]
                worker = subprocess.Popen(["/usr/bin/python3", "-m", "distributed.cli.dask_worker", "--scheduler-file", sched_file, "--nthreads", "1",
                                           "--no-nanny", "--no-dashboard"], env=env, cwd=tmp, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                procs.append(worker)
                driver = subprocess.Popen(["/usr/bin/python3", "-m", "shoal.dask", "--scheduler", address, "--worker-timeout", "5", "--shoal", wrapper,
                                           "check"] + coast + files + ["-o", out], env=env, cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                          text=True)
                procs.append(driver)
                running = started()
                expect(running, "a task started")
                worker.kill()  # the only worker, mid-task
            try:
                _, err = driver.communicate(timeout=60)
            except subprocess.TimeoutExpired:
                driver.kill()
                _, err = driver.communicate()
                expect(False, "the driver ended within 60 s: " + err)
            lines = err.strip().splitlines()
            if case == "signal":
                expect(driver.returncode == 143, "exit 143 under SIGTERM: %s\n%s" % (driver.returncode, err))
                expect(lines and lines[-1] == "shoal.dask: interrupted (SIGTERM): tasks stopped, no report written", "one line: " + err)
            else:
                expect(driver.returncode == 3, "exit 3 when the only worker is lost: %s\n%s" % (driver.returncode, err))
                expect(lines and lines[-1].startswith("shoal.dask: error: the Dask cluster "), "one line: " + err)
            expect("Traceback" not in err, "no traceback: " + err)
            expect(not os.path.exists(out), "no report written")
            time.sleep(2)
            expect(not [p for p in running if alive(p)], "no task left running: %s" % [p for p in running if alive(p)])
            expect(not [n for n in os.listdir(tmp) if n.startswith(".shoal-dask-")], "no work folder left behind: %s" % os.listdir(tmp))
        finally:
            for p in procs:
                if p.poll() is None:
                    p.kill()
                    p.wait()
    else:
        expect(False, "unknown case " + case)
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(1 if failures else 0)
