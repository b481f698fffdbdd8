#!/usr/bin/env bash
# The latency study of docs/remote-haptics.md: a haptic-server with the
# demo scene on a free 127.0.0.1 port, and `hapticctl drive --operator`
# in both modes (local model on and off) at round trips of 0, 10, 30, 60
# and 100 ms, plus 30 ms with jitter and loss, for each operator given
# (default: press). Writes docs/remote-haptics/results.jsonl and the plot
# of the force at 60 ms, force-60ms.png; prints the table.
#   scripts/remote.sh [press|slide|tap ...]
set -euo pipefail
cd "$(dirname "$0")/.."
operators=("${@:-press}")
out=docs/remote-haptics
mkdir -p "$out"
cmake --build build -j2 --target hapticctl haptic-server >/dev/null

tmp=$(mktemp -d)
# shellcheck source=scripts/start_server.sh
. scripts/start_server.sh
trap 'kill "$server" 2>/dev/null || true; rm -rf "$log" "$tmp"' EXIT

drive() {  # operator mode latency jitter loss [trace]
  local trace=()
  [ -n "${6:-}" ] && trace=(--trace "$6")
  ./build/bin/hapticctl drive --server "127.0.0.1:$port" --scene "probe on torus" --tool probe \
    --operator "$1" --local-model "$2" --latency-ms "$3" --jitter-ms "$4" --loss "$5" \
    --seed 1 --duration 4 --json "${trace[@]}"
}

: >"$out/results.jsonl"
for op in "${operators[@]}"; do
  for mode in on off; do
    for rtt in 0 10 30 60 100; do
      trace=""
      [ "$rtt" = 60 ] && [ "$op" = press ] && trace="$tmp/trace-60ms-$mode.csv"
      drive "$op" "$mode" "$rtt" 0 0 "$trace" >>"$out/results.jsonl"
    done
    drive "$op" "$mode" 30 10 0.05 >>"$out/results.jsonl"
  done
done

if [ -f "$tmp/trace-60ms-on.csv" ]; then
  gnuplot <<GP
set terminal pngcairo size 900,420
set output "$out/force-60ms.png"
set datafile separator ","
set key top right
set xlabel "time (s)"
set ylabel "force on the hand, z (N)"
set title "press on the demo scene's organ, 60 ms round trip"
plot "$tmp/trace-60ms-off.csv" every ::1 using 1:4 with lines title "server forces as they arrive", \
     "$tmp/trace-60ms-on.csv" every ::1 using 1:4 with lines lw 2 title "local model on the device"
GP
fi

python3 - "$out/results.jsonl" <<'PY'
import json, sys
print("| operator | mode | round trip | jitter, loss | energy (J) | max step (N) | max force (N) | penetration p99 (mm) | force RMS error (N) | measured RTT p50 (ms) |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for line in open(sys.argv[1]):
    r = json.loads(line)
    print(f"| {r['operator']} | {r['mode']} | {r['latency_ms']:g} ms | {r['jitter_ms']:g} ms, {r['loss']:g} "
          f"| {r['energy_j']:.4f} | {r['max_force_step_n']:.3f} | {r['max_force_n']:.2f} "
          f"| {r['penetration_p99_m']*1e3:.2f} | {r['force_rms_error_n']:.3f} | {r['round_trip_p50_ms']:.0f} |")
PY
