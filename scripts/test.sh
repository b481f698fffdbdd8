#!/usr/bin/env bash
# Sets up, configures, builds and runs every test. The README's test command
# and the one thing .ci/run calls.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/lib/phase.sh
. scripts/lib/phase.sh
phase setup bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
phase build cmake --build build -j2
phase test ctest --test-dir build --output-on-failure -j2 --timeout 300
