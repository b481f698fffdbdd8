#!/usr/bin/env bash
# The checks past the default suite, bounded in time (.ci/run runs them
# after scripts/test.sh):
#  1. the engine's tests (label `engine`: those of common/, server/, the
#     SDK's and the haptic loop's units; tests/CMakeLists.txt) built with
#     clang-14 under ASan and UBSan. hapticctl's commands and the end-to-end
#     tests run in the default suite only: two full builds of the suite do
#     not fit CI's time on two cores;
#  2. each libFuzzer target (tests/fuzz, built in the same tree) for
#     FUZZ_SECONDS (default 60) from its seed corpus;
#  3. the tests of the project's own threads under ThreadSanitizer, unless
#     TSAN=0.
# Suppressions (scripts/sanitizers/) cover uninstrumented Debian libraries
# only, each with its reason.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/lib/phase.sh
. scripts/lib/phase.sh
bash scripts/setup.sh
fuzz_seconds=${FUZZ_SECONDS:-60}
here=$(pwd)

# Only what runs here: the timing benchmarks are neither built nor run.
# -O1, as the sanitizers' documentation advises: reports stay exact and
# the build is quicker. No precompiled headers: clang's hold the build
# folder's absolute path, so every file that used one would miss ccache
# in another clone; without them, a clone finds what an earlier build of
# the same sources left there.
sanitizer_flags="-O1 -g1 -DNDEBUG"
clang_build=(-G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_C_COMPILER=clang-14
             -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$sanitizer_flags" -DCMAKE_C_FLAGS_RELWITHDEBINFO="$sanitizer_flags"
             -DCMAKE_DISABLE_PRECOMPILE_HEADERS=ON)
cmake -S . -B build-asan "${clang_build[@]}" -DHS_SANITIZE=address,undefined -DHS_FUZZ=ON \
  -DHS_TIMING_BENCHMARKS=OFF >/dev/null
phase "asan build" cmake --build build-asan -j2 --target engine_tests import_fuzzer requests_fuzzer contact_fuzzer \
  kernels_fuzzer
export ASAN_OPTIONS="detect_leaks=1:suppressions=$here/scripts/sanitizers/asan.supp"
export LSAN_OPTIONS="suppressions=$here/scripts/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Timing benchmarks say nothing under a sanitizer's slowdown, and the
# allocation counts (a replaced global operator new) nothing under ASan's
# own allocator. The pair tests over every kind of FCL bounding volume run
# one kind (OBB) here: the others run the same code of ours through
# another of FCL's volumes, and FCL is not instrumented.
phase "asan tests" ctest --test-dir build-asan --output-on-failure -j2 --timeout 600 -L engine \
  -E "allocation|(AllBvTypes|AllVolumes)/.*/(aabb|rss|kios|obbrss)( |$)"

# Model import runs in fork mode and lets crashes go on: a crash inside
# assimp or Coin3D is theirs, and the haptic-import worker contains it
# (docs/security.md lists those found). Any other crash, leak or undefined
# behaviour fails the run.
fuzz() {
for target in import requests contact kernels; do
  corpus=build-asan/fuzz/corpus-$target
  log=build-asan/fuzz/$target.log
  mkdir -p "$corpus"
  rm -f build-asan/fuzz/$target-*-*
  fork=()
  [ "$target" = import ] && fork=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  status=0
  build-asan/fuzz/${target}_fuzzer "${fork[@]}" -max_total_time="$fuzz_seconds" -max_len=4096 \
    -timeout=20 -rss_limit_mb=4096 -print_final_stats=1 \
    -artifact_prefix="build-asan/fuzz/$target-" "$corpus" "tests/fuzz/corpus/$target" \
    >"$log" 2>&1 || status=$?
  { grep -E "^stat::number_of_executed_units|^#[0-9]+: cov" "$log" || true; } | tail -1 |
    sed "s/^/fuzz $target: /"
  # Each input kept (crash, leak, out of memory, timeout), run again alone:
  # the first frame in a library or in the project's code says whose it is.
  for artifact in build-asan/fuzz/$target-*-*; do
    [ -e "$artifact" ] || continue
    where=$(timeout 120 build-asan/fuzz/${target}_fuzzer -rss_limit_mb=4096 -timeout=20 "$artifact" 2>&1 |
      grep -m1 -oE "(libassimp\.so|libCoin\.so|/common/[^ ]*|/server/[^ ]*|/client/[^ ]*)" || true)
    echo "fuzz $target: $artifact: first frame in ${where:-(none)}"
    if ! grep -qE "^(libassimp|libCoin)" <<<"$where"; then
      echo "fuzz $target: an input that fails in the project's code" >&2
      exit 1
    fi
  done
  if [ "$status" -ne 0 ] && [ "$target" != import ]; then
    tail -40 "$log" >&2
    exit 1
  fi
done
}
phase fuzz fuzz

[ "${TSAN:-1}" = 1 ] || exit 0

cmake -S . -B build-tsan "${clang_build[@]}" -DHS_SANITIZE=thread >/dev/null
# The tests whose threads are the project's own: the scene runner and its
# parts, the worker pool and a scene stepped on it, the registries, the
# session recorder, the Agones lifecycle. Tests through gRPC are left out: Debian's gRPC and
# Abseil are not instrumented, so TSan sees their threads'
# synchronization as races.
tsan_tests=(scene_runner_test frame_outbox_test frame_fan_out_test frame_pump_test stream_registry_test
            worker_pool_test tool_stage_test scene_registry_test caller_quotas_test
            session_recorder_test agones_lifecycle_test)
phase "tsan build" cmake --build build-tsan -j2 --target "${tsan_tests[@]}"
export TSAN_OPTIONS="suppressions=$here/scripts/sanitizers/tsan.supp:halt_on_error=1:second_deadlock_stack=1"
# Death tests fork a child that aborts on purpose; under TSan a fork of a
# threaded process is reported as such, so they run in the other builds only.
tsan() {
  for test in "${tsan_tests[@]}"; do build-tsan/tests/$test --gtest_filter='-*DeathTest*'; done
}
phase "tsan tests" tsan
