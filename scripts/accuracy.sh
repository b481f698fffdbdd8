#!/usr/bin/env bash
# Builds and runs the accuracy-vs-time sweep (tests/bench/accuracy_bench.cc
# and the files beside it),
# writes its table and data to docs/accuracy/ and draws the plots there
# with gnuplot. Extra arguments go to Google Benchmark, e.g.
#   scripts/accuracy.sh --benchmark_filter=Tunnelling
# BUILD_DIR picks the build tree (default: build).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build}"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j2 --target accuracy_bench
"$build/bin/accuracy_bench" --out=docs/accuracy --benchmark_min_time=0.2 "$@"
(cd docs/accuracy && gnuplot plots.gp)
echo "table: docs/accuracy/accuracy.md; plots: docs/accuracy/*.png"
