#!/usr/bin/env bash
# Sets up, builds, and runs the service's main job as far as it exists today:
# the bundled demo scene (a probe on an organ-like torus lying on a table)
# stepped at 1 kHz while a recorded device path drives the probe into the
# organ and along it, printing each step's contacts and force, then the
# per-stage counters. The gRPC server and a streaming client replace this
# offline run when the service lands.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j2 --target hapticctl
./build/bin/hapticctl simulate scenes/probe_on_torus.textproto \
  --tool-path scenes/press_and_slide.csv --steps 60
