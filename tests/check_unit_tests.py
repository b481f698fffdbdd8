#!/usr/bin/env python3
"""Every unit has a test file of its own (docs/architecture.md, "Side doors").

A unit is an X.cc with its X.h under common/, server/ or client/; its test is
tests/<same folder>/X_test.cc, or, for a hapticctl command (client/**/X_command),
tests/e2e/X_test.cc. Fails listing the units without one. PENDING names the
units still without a test: it may only shrink, so a unit that gains a test or
goes away must leave it too (the check fails on a stale entry).

Usage: check_unit_tests.py [--repo DIR]   (default: the repository holding this file)
"""

import argparse
import pathlib
import sys

UNIT_ROOTS = ("common", "server", "client")

# Units still without a test file of their own. Remove a line when its test lands.
PENDING = {
    # Being reworked: their tests come with the rework.
    "client/viewer/page_device",
    "client/viewer/scene_link",
    "client/viewer/view_command",
    "client/viewer/view_server",
    "client/loadtest/echo_baseline",
    "client/remote/hand_operator",
    "client/remote/remote_drive",
    "client/training/report",
    "client/training/score_output",
    "common/training/step_scoring",
    # Not yet tested on their own.
    "client/channel",
    "client/contact_json",
    "client/delete_model_command",
    "client/device_path",
    "client/json_text",
    "client/pose_args",
    "client/recording_command",
    "client/server_call",
    "common/api/exercise_file",
    "common/api/local_model_convert",
    "common/api/proto_file",
    "common/api/scene_geometry",
    "common/collision/faces_in_box",
    "common/model/assimp_reader",
    "common/model/coin_lock",
    "common/model/coin_reader",
    "common/recording/recorded_step",
    "common/recording/recording_summary",
    "common/recording/replay",
    "common/recording/session_reader",
    "common/sandbox/import_codec",
    "server/agones/agones_sdk",
    "server/agones/server_activity",
    "server/raw_message",
    "server/recording/recording_folder",
    "server/snapshot_pool",
    "server/state/durable_file",
}


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
    all_units = set(units(repo))
    untested = {unit for unit in all_units if not has_test(repo, unit)}
    missing = sorted(untested - PENDING)
    stale = sorted(PENDING - untested)
    for unit in missing:
        print(f"no test: {unit} (expected tests/{unit}_test.cc)")
    for unit in stale:
        reason = "has a test now" if unit in all_units else "is no unit"
        print(f"stale PENDING entry: {unit} {reason}; remove it from {__file__}")
    print(f"{len(all_units)} units, {len(untested)} without a test, all pending"
          if not missing and not stale else "check_unit_tests: FAILED")
    return 1 if missing or stale else 0


if __name__ == "__main__":
    sys.exit(main())
