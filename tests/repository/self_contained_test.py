#!/usr/bin/env python3
"""Fails when a tracked file points at notes kept outside the repository.

A clone holds nothing beside it, so a path such as the parent folder's
shared notes leads nowhere: the method is described in docs/algorithm.md
and the paper is cited by its title. Every file `git ls-files` lists is
read, but node_modules and package-lock.json (third-party text).

Usage: self_contained_test.py --repo DIR
Exit 77 (skipped) when DIR is not a git work tree.
"""

import argparse
import pathlib
import subprocess
import sys

# Split so that this file does not hold what it looks for.
FORBIDDEN = (
    "../" "shared/",
    "shared/" "ALGORITHM",
    "shared/" "DESIGN",
    "shared/" "seed",
    "ALGORITHM" ".md",
    "DESIGN" ".md",
)
SKIPPED_NAMES = ("package-lock.json",)
SKIPPED_FOLDERS = ("node_modules",)


def tracked_files(repo):
    listing = subprocess.run(["git", "-C", str(repo), "ls-files", "-z"], capture_output=True,
                             check=False)
    if listing.returncode != 0:
        return None
    names = [n for n in listing.stdout.decode("utf-8").split("\0") if n]
    return [n for n in names
            if pathlib.PurePosixPath(n).name not in SKIPPED_NAMES
            and not any(part in SKIPPED_FOLDERS for part in pathlib.PurePosixPath(n).parts)]


def offending_lines(text):
    """(line number, the forbidden patterns it holds) of each line of `text`
    that holds any."""
    found = []
    for number, line in enumerate(text.splitlines(), start=1):
        patterns = [pattern for pattern in FORBIDDEN if pattern in line]
        if patterns:
            found.append((number, patterns))
    return found


def self_check():
    """The matcher on lines whose answers are known; a list of failures."""
    cases = {
        "see ../" "shared/notes.md\nfine\n": [(1, ["../" "shared/"])],
        "docs/algorithm.md and a shared/ scratch folder\n": [],
        "x\n// as shared/" "ALGORITHM" ".md says\n": [(2, ["shared/" "ALGORITHM", "ALGORITHM" ".md"])],
    }
    return [f"self-check: expected {expected}, got {offending_lines(text)} on {text!r}"
            for text, expected in cases.items() if offending_lines(text) != expected]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repo", required=True, type=pathlib.Path)
    args = parser.parse_args()
    failures = self_check()
    names = tracked_files(args.repo)
    if names is None:
        print(f"{args.repo} is not a git work tree: nothing to check")
        return 77
    for name in names:
        path = args.repo / name
        if not path.is_file():
            continue  # deleted in the work tree, or a submodule
        text = path.read_bytes().decode("utf-8", errors="replace")
        for number, patterns in offending_lines(text):
            failures.append(f"{name}:{number}: {', '.join(patterns)}: points outside the repository "
                            "(use docs/algorithm.md, or the paper's title)")
    for failure in failures:
        print(failure)
    print(f"{len(names)} tracked files read, {len(failures)} problems")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
