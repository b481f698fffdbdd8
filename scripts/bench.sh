#!/usr/bin/env bash
# Builds and runs the Table 1 benchmark (tests/bench/contact_bench.cc): the
# four fig. 8 cases through our contact query beside FCL's exhaustive collide,
# then the Table-1-style summary. Five repetitions, medians reported, because
# the machine is shared. Extra arguments go to Google Benchmark, e.g.
#   scripts/bench.sh --benchmark_filter=case4/
#
# The speed check (docs/benchmarks.md): with --check first, runs the
# representative step and contact benchmarks (step_bench, contact_bench;
# three repetitions, medians), each figure as a ratio to FCL's contact query
# on Table 1 #4 timed in the same run, and fails naming each scene's step
# p99 or query whose ratio grew by more than 20 % against the newest record
# in docs/benchmarks/ in that run and again in a second run made then
# (each benchmark judged by its better run: a busy moment of the machine
# slows one run, slower code both). With --record first, the same run
# writes a new record there instead. Extra arguments then go to both
# benchmarks.
# BUILD_DIR picks the build tree (default: build).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD_DIR:-build}"
mode=""
case "${1:-}" in
  --check | --record) mode="$1"; shift ;;
esac
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
if [[ -z "$mode" ]]; then
  cmake --build "$build" -j2 --target contact_bench
  exec "$build/bin/contact_bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true "$@"
fi

# Every demo scene on one thread, with every effect and with a haptic
# device's needs; linked_rings (the hardest) also on two threads; the two
# large Table 1 cases, alone and along their coherent sequences.
step_filter='^(Yardstick/.*|Step/[a-z_]+/(all_effects|force_only)/threads:1|Step/linked_rings/all_effects/threads:2)$'
contact_filter='^(Table1/case[34]/(pairs|sweep3d|paper2d|fcl_contacts)|Coherent/case[34]/(sweep3d|paper2d)/iterations:[0-9]+)$'
cmake --build "$build" -j2 --target step_bench contact_bench
out="$build/bench_check"
commit="$(git rev-parse --short HEAD)"
[[ -z "$(git status --porcelain --untracked-files=no)" ]] || commit+="+changes"
# One run of both benchmarks into directory $1, its record written into
# directory $2; prints the record's path, or stops the script when the
# record refuses the run (the machine's speed changed during it), having
# said why.
run_both() {
  local dir="$1" records="$2"
  mkdir -p "$dir"
  local runs=(--benchmark_repetitions=3 --benchmark_report_aggregates_only=true
              --benchmark_min_time=0.2 --benchmark_out_format=json)
  "$build/bin/step_bench" --benchmark_filter="$step_filter" "${runs[@]}" \
    --benchmark_out="$dir/step.json" "${args[@]}" >&2
  "$build/bin/contact_bench" --benchmark_filter="$contact_filter" "${runs[@]}" \
    --benchmark_out="$dir/contact.json" "${args[@]}" >&2
  python3 tests/bench/bench_ratios.py record "$dir/step.json" "$dir/contact.json" \
    --commit "$commit" --command "scripts/bench.sh $mode${args[*]:+ ${args[*]}}" --out "$records"
}
args=("$@")
rm -rf "$out"
if [[ "$mode" == --record ]]; then
  run_both "$out" docs/benchmarks
  exit
fi
first="$(run_both "$out/1" "$out/1")"
python3 tests/bench/bench_ratios.py compare docs/benchmarks "$first" && exit
echo "A second run, to tell slower code from a busy machine:"
second="$(run_both "$out/2" "$out/2")"
python3 tests/bench/bench_ratios.py compare docs/benchmarks "$first" "$second"
