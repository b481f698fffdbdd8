#!/usr/bin/env python3
"""The runtime stage of deploy/docker/Dockerfile installs exactly the library
packages the built binaries load.

Usage: docker_runtime_libs_test.py --dockerfile FILE BINARY...

1. ldd of each binary gives the files it loads; dpkg -S names each file's
   Debian package.
2. Every such package must be in the Dockerfile's runtime apt-get install
   list, or in debian:12-slim, or pulled in by a listed package's
   dependencies (apt-cache depends --recurse, no recommends, suggests,
   conflicts, breaks, replaces or enhances).
3. Every listed package must hold a file some binary loads (no stale
   entries). The project's own packages (*.deb files) are not counted.

debian:12-slim is modelled as debootstrap's minbase: the packages of
Priority required or Essential (dpkg-query), apt, and their dependencies.
Priority alone is not enough: on Debian 12, libc6, libstdc++6 and zlib1g
are of Priority optional, and come in as dependencies of required ones.
"""

import argparse
import os
import re
import subprocess
import sys

APT_DEPENDS = ["apt-cache", "depends", "--recurse", "--no-recommends", "--no-suggests",
               "--no-conflicts", "--no-breaks", "--no-replaces", "--no-enhances"]


def run(args):
    return subprocess.run(args, check=False, capture_output=True, text=True)


def runtime_packages(dockerfile):
    """The packages of the apt-get install of the last stage (after the last FROM)."""
    text = open(dockerfile, encoding="utf-8").read()
    # Join continued lines, drop comments.
    lines = [l for l in text.splitlines() if not l.lstrip().startswith("#")]
    joined = re.sub(r"\\\n", " ", "\n".join(lines))
    stages = re.split(r"(?im)^FROM\s", joined)
    runtime = stages[-1]
    base = runtime.split(None, 1)[0]
    packages, flags = [], []
    for command in re.findall(r"(?m)^RUN\s+(.*)$", runtime):
        for part in re.split(r"&&|;", command):
            words = part.split()
            if words[:2] != ["apt-get", "install"]:
                continue
            for word in words[2:]:
                if word.endswith(".deb"):
                    continue  # the project's own packages: their dependencies go with them
                (flags if word.startswith("-") else packages).append(word)
    return base, packages, flags, runtime


def loaded_files(binary):
    """Resolved paths of the shared libraries ldd says `binary` loads."""
    result = run(["ldd", binary])
    if result.returncode != 0:
        sys.exit(f"ldd {binary} failed: {result.stderr.strip()}")
    files = []
    for line in result.stdout.splitlines():
        m = re.search(r"=>\s+(/\S+)", line)
        if m:
            files.append(m.group(1))
        elif line.strip().startswith("/"):  # the dynamic loader itself
            files.append(line.split()[0])
        elif "not found" in line:
            sys.exit(f"{binary}: ldd cannot find {line.strip()}")
    return files


def path_variants(path):
    """The names dpkg may know a file by: merged /usr makes /lib and /usr/lib
    one folder, and a library is often a symbolic link to its versioned file."""
    variants = []
    for p in (path, os.path.realpath(path)):
        for q in (p, re.sub(r"^/usr/", "/", p), "/usr" + p if not p.startswith("/usr/") else p):
            if q not in variants:
                variants.append(q)
    return variants


def packages_of(paths):
    """{path: its package, or None} through one dpkg-query -S of every name each
    path may have."""
    variants = {path: path_variants(path) for path in paths}
    names = sorted({v for vs in variants.values() for v in vs})
    # Exit status 1 when some name is not found: expected, most variants are not.
    result = run(["dpkg-query", "-S"] + names)
    owner = {}
    for line in result.stdout.splitlines():
        if line.startswith("diversion ") or ": " not in line:
            continue
        # "pkg:arch: /path" or "pkg1, pkg2: /path"
        packages, path = line.rsplit(": ", 1)
        owner.setdefault(path, packages.split(",")[0].strip().split(":")[0])
    return {path: next((owner[v] for v in vs if v in owner), None) for path, vs in variants.items()}


def closure(packages):
    """The packages apt would install for `packages` (an over-approximation:
    every alternative of an "a | b" dependency is counted)."""
    if not packages:
        return set()
    result = run(APT_DEPENDS + sorted(packages))
    if result.returncode != 0:
        sys.exit(f"apt-cache depends failed: {result.stderr.strip()}")
    return {l.strip().split(":")[0] for l in result.stdout.splitlines()
            if l and not l[0].isspace() and not l.startswith("<")}


def slim_packages():
    result = run(["dpkg-query", "-W", "-f=${Package}\t${Priority}\t${Essential}\n"])
    base = {"apt"}
    for line in result.stdout.splitlines():
        name, priority, essential = (line.split("\t") + ["", ""])[:3]
        if priority == "required" or essential == "yes":
            base.add(name)
    return closure(base)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--dockerfile", required=True)
    parser.add_argument("binaries", nargs="+")
    args = parser.parse_args()
    errors = []
    where = f"{args.dockerfile} (runtime stage)"

    base, listed, flags, runtime = runtime_packages(args.dockerfile)
    if base != "debian:12-slim":
        errors.append(f"{where}: FROM {base}, expected debian:12-slim")
    if not listed:
        sys.exit(f"FAIL: {where}: no apt-get install list found")
    if "--no-install-recommends" not in flags:
        errors.append(f"{where}: apt-get install without --no-install-recommends")
    if "rm -rf /var/lib/apt/lists/*" not in runtime:
        errors.append(f"{where}: the apt lists are not removed (rm -rf /var/lib/apt/lists/*)")
    if len(set(listed)) != len(listed):
        errors.append(f"{where}: a package is listed twice: {sorted(listed)}")

    # Package -> the loaded files it holds, and which binary loads them.
    needed = {}
    loads = {}
    for binary in args.binaries:
        if not os.path.exists(binary):
            sys.exit(f"FAIL: {binary} is not built (cmake --build build)")
        loads[binary] = loaded_files(binary)
    owners = packages_of({path for files in loads.values() for path in files})
    for binary, files in loads.items():
        for path in files:
            package = owners[path]
            if package is None:
                errors.append(f"{os.path.basename(binary)} loads {path}, which no Debian package holds")
                continue
            needed.setdefault(package, set()).add(f"{os.path.basename(path)} ({os.path.basename(binary)})")

    slim = slim_packages()
    provided = closure(set(listed))
    for package in sorted(needed):
        if package in listed or package in slim or package in provided:
            continue
        errors.append(f"missing from {where}: {package}, which holds "
                      + ", ".join(sorted(needed[package])))
    for package in listed:
        if package not in needed:
            errors.append(f"stale in {where}: {package} holds no library the binaries load")

    if errors:
        print("FAIL:\n  " + "\n  ".join(errors))
        return 1
    print(f"ok: {len(listed)} listed packages; the binaries load files of {len(needed)} packages, "
          f"{len(set(needed) & slim)} of them in debian:12-slim, the rest listed or pulled in by the list")
    return 0


if __name__ == "__main__":
    sys.exit(main())
