#!/usr/bin/python3
"""What each set of scripts/install-deps.sh pulls on a bare Debian 12, without a fresh machine.

    /usr/bin/python3 scripts/count-deps.py [--check-build BUILD_DIR]

A bare system is a dpkg status holding every `Priority: required` package of the apt index and
apt, with their dependencies (what `debootstrap --variant=minbase` lays); each set is then
simulated with `apt-get install -s --no-install-recommends` against that status (apt's own
resolver, nothing installed), and the download and installed sizes summed from the index's
`Size` and `Installed-Size`. Needs `apt-get update` first; the figures are those of the index
of that day.

--check-build BUILD_DIR: every header the build compiled (`ninja -t deps`) and every library its
`cli/shoal` loads (`ldd`) must belong to a package of the `--build` set or of the bare system
(dpkg's file lists, as `dpkg -S`): the build needs nothing more than `install-deps.sh --build`.
"""
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def index():
    """{name: [(version, fields, stanza)]} of the apt index."""
    text = subprocess.run(["apt-cache", "dumpavail"], capture_output=True, text=True, check=True).stdout
    out = {}
    for stanza in text.split("\n\n"):
        fields = {}
        for line in stanza.splitlines():
            if line and not line[0].isspace() and ":" in line:
                k, v = line.split(":", 1)
                fields[k] = v.strip()
        if "Package" in fields:
            out.setdefault(fields["Package"], []).append((fields.get("Version"), fields, stanza))
    return out


def simulate(status, packages):
    """[(name, version)] apt would install on the system `status` describes."""
    p = subprocess.run(["apt-get", "-o", "Dir::State::status=" + status, "-o", "Debug::NoLocking=1", "install", "-s",
                        "--no-install-recommends", *packages], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("apt-get -s failed:\n" + p.stdout + p.stderr)
    return [(m.group(1).split(":")[0], m.group(2)) for m in re.finditer(r"^Inst (\S+) \((\S+)", p.stdout, re.M)]


def write_status(path, installs, idx):
    with open(path, "w") as out:
        for name, version in installs:
            stanza = next(s for v, f, s in idx[name] if v == version)
            lines = [l for l in stanza.splitlines() if not re.match(r"(Filename|Size|MD5sum|SHA256|Description-md5):", l)]
            lines.insert(1, "Status: install ok installed")
            out.write("\n".join(lines) + "\n\n")


def install_set(option):
    out = subprocess.run([os.path.join(HERE, "install-deps.sh"), option, "--list"], capture_output=True, text=True, check=True)
    return out.stdout.split()


def main():
    idx = index()
    with tempfile.TemporaryDirectory() as tmp:
        empty = os.path.join(tmp, "empty")
        open(empty, "w").close()
        required = sorted(n for n, vs in idx.items() if any(f.get("Priority") == "required" for _, f, _ in vs))
        base = simulate(empty, required + ["apt"])
        status = os.path.join(tmp, "status")
        write_status(status, base, idx)
        print("bare system: %d packages (Priority required and apt, with their dependencies)" % len(base))
        sets = {}
        for option in ("--build", "--tests"):
            named = install_set(option)
            inst = simulate(status, named)
            sets[option] = {n for n, _ in inst}
            size = sum(int(next(f for v, f, _ in idx[n] if v == ver)["Size"]) for n, ver in inst)
            isize = sum(int(next(f for v, f, _ in idx[n] if v == ver)["Installed-Size"]) * 1024 for n, ver in inst)
            print("install-deps.sh %-7s %2d named, %3d installed, download %4d MiB, installed %5d MiB"
                  % (option, len(named), len(inst), size / 2**20, isize / 2**20))
    if len(sys.argv) == 3 and sys.argv[1] == "--check-build":
        build = sys.argv[2]
        deps = subprocess.run(["ninja", "-C", build, "-t", "deps"], capture_output=True, text=True, check=True).stdout
        files = {l.strip() for l in deps.splitlines() if l.startswith("    ") and l.strip().startswith("/usr/")}
        ldd = subprocess.run(["ldd", os.path.join(build, "cli", "shoal")], capture_output=True, text=True, check=True).stdout
        files |= {m.group(1) for m in re.finditer(r"=> (/\S+)", ldd)}
        # dpkg's own lists of the files each installed package owns (what `dpkg -S` reads), read once.
        owner_of = {}
        info = "/var/lib/dpkg/info"
        for name in os.listdir(info):
            if name.endswith(".list"):
                pkg = name[:-5].split(":")[0]
                with open(os.path.join(info, name), encoding="utf-8", errors="replace") as f:
                    for line in f:
                        owner_of.setdefault(line.rstrip("\n"), set()).add(pkg)
        owners = {}
        for f in sorted(files):
            # As given, resolved, or through /usr-merged /lib: the path a package lists.
            candidates = [f, os.path.realpath(f), os.path.normpath(f)]
            candidates += [c[4:] for c in candidates if c.startswith("/usr/lib/") or c.startswith("/usr/bin/")]
            pkgs = set().union(*(owner_of.get(c, set()) for c in candidates))
            if not pkgs:
                sys.exit("no package owns %s" % f)
            for pkg in pkgs:
                owners.setdefault(pkg, f)
        allowed = sets["--build"] | {n for n, _ in base}
        outside = {p: f for p, f in owners.items() if p not in allowed}
        print("build %s: %d files from %d packages; outside the --build set and the bare system: %s"
              % (build, len(files), len(owners), ", ".join("%s (%s)" % kv for kv in sorted(outside.items())) or "none"))
        if outside:
            sys.exit(1)


if __name__ == "__main__":
    main()
