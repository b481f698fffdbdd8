#!/usr/bin/env bash
# Builds and runs the Table 1 benchmark (tests/bench/contact_bench.cc): the
# four fig. 8 cases through our contact query beside FCL's exhaustive collide,
# then the Table-1-style summary. Five repetitions, medians reported, because
# the machine is shared. Extra arguments go to Google Benchmark, e.g.
#   scripts/bench.sh --benchmark_filter=case4/
# BUILD_DIR picks the build tree (default: build).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build}"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j2 --target contact_bench
"$build/bin/contact_bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true "$@"
