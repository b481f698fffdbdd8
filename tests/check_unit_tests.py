#!/usr/bin/env python3
"""Every unit has a test file of its own (docs/architecture.md, "Side doors").

A unit is an X.cc with its X.h under common/, server/ or client/; its test is
tests/<same folder>/X_test.cc, or, for a hapticctl command (client/**/X_command),
tests/e2e/X_test.cc. Fails listing the units without one.

Usage: check_unit_tests.py [--repo DIR]   (default: the repository holding this file)
"""

import argparse
import pathlib
import sys

UNIT_ROOTS = ("common", "server", "client")

def units(repo):
    """Yields each unit as its path without the extension, e.g. 'common/sim/scene'."""
    for root in UNIT_ROOTS:
        for source in sorted((repo / root).rglob("*.cc")):
            if source.with_suffix(".h").is_file():
                yield source.relative_to(repo).with_suffix("").as_posix()


def has_test(repo, unit):
    folder, name = unit.rsplit("/", 1)
    if (repo / "tests" / folder / f"{name}_test.cc").is_file():
        return True
    return name.endswith("_command") and (repo / "tests" / "e2e" / f"{name}_test.cc").is_file()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repo", type=pathlib.Path,
                        default=pathlib.Path(__file__).resolve().parent.parent)
    repo = parser.parse_args().repo
    all_units = sorted(units(repo))
    missing = [unit for unit in all_units if not has_test(repo, unit)]
    for unit in missing:
        print(f"no test: {unit} (expected tests/{unit}_test.cc)")
    print(f"{len(all_units)} units, each with its test" if not missing
          else "check_unit_tests: FAILED")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
