#!/usr/bin/env bash
# The study of docs/remote-haptics.md over a real TCP link: a haptic-server
# with the demo scene on a free 127.0.0.1 port, and for each link below a
# `hapticctl relay` in front of it (one-way delay, jitter, 1 % of chunks
# held 100 ms: head-of-line stalls), through which `hapticctl drive
# --operator` runs with the local model on and off; the zero-latency
# reference of force_rms_error_n runs against the server itself. Writes
# docs/remote-haptics/relay-results.jsonl and the plot relay.png; prints
# the table.
#   scripts/relay.sh [press|slide|tap ...]                  (default: all three)
#   scripts/relay.sh --link ONE_WAY_MS JITTER_MS STALL_PROB STALL_MS [operators]
set -euo pipefail
cd "$(dirname "$0")/.."
# one-way ms, jitter ms, stall probability, stall ms
links=("0 0 0 0" "15 5 0.01 100" "50 10 0.01 100" "100 15 0.01 100" "150 20 0 0"
  "150 20 0.01 100")
out=docs/remote-haptics
results="$out/relay-results.jsonl"
if [ "${1:-}" = --link ]; then
  links=("$2 $3 $4 $5")
  shift 5
  results=/dev/null
fi
operators=("${@:-press slide tap}")
read -r -a operators <<<"${operators[*]}"
mkdir -p "$out"
cmake --build build -j2 --target hapticctl haptic-server >/dev/null

tmp=$(mktemp -d)
# shellcheck source=scripts/start_server.sh
. scripts/start_server.sh
relay=""
trap 'kill $relay "$server" 2>/dev/null || true; rm -rf "$log" "$tmp"' EXIT

start_relay() {  # one_way jitter stall_prob stall_ms
  ./build/bin/hapticctl relay --to "127.0.0.1:$port" --one-way-ms "$1" --jitter-ms "$2" \
    --stall-prob "$3" --stall-ms "$4" --seed 1 >"$tmp/relay.log" &
  relay=$!
  relay_port=""
  for _ in $(seq 100); do
    relay_port=$(sed -n 's/^relay: listening on port \([0-9]*\).*/\1/p' "$tmp/relay.log")
    [ -n "$relay_port" ] && return 0
    sleep 0.1
  done
  echo "the relay did not start" >&2
  cat "$tmp/relay.log" >&2
  exit 1
}

: >"$tmp/rows.jsonl"
for link in "${links[@]}"; do
  read -r one_way jitter stall_prob stall_ms <<<"$link"
  start_relay "$one_way" "$jitter" "$stall_prob" "$stall_ms"
  for op in "${operators[@]}"; do
    for mode in on off; do
      ./build/bin/hapticctl drive --server "127.0.0.1:$relay_port" \
        --reference-server "127.0.0.1:$port" --scene "probe on torus" --tool probe \
        --operator "$op" --local-model "$mode" --seed 1 --duration 4 --json |
        python3 -c 'import json, sys
r = json.loads(sys.stdin.read()); r.update(relay_one_way_ms=float(sys.argv[1]),
  relay_jitter_ms=float(sys.argv[2]), relay_stall_prob=float(sys.argv[3]),
  relay_stall_ms=float(sys.argv[4])); print(json.dumps(r))' \
          "$one_way" "$jitter" "$stall_prob" "$stall_ms" | tee -a "$tmp/rows.jsonl" >/dev/null
    done
  done
  kill -TERM "$relay"
  wait "$relay" || true
  relay=""
done
[ "$results" = /dev/null ] || cp "$tmp/rows.jsonl" "$results"

python3 - "$tmp/rows.jsonl" "$tmp" <<'PY'
import json, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
print("| operator | mode | one way, jitter | stalls | RTT p50 / p99 (ms) | energy (J) | penetration p99 (mm) | force RMS error (N) | force RMS (N) | max step (N) | past the sphere (ticks) |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for r in rows:
    stalls = f"{r['relay_stall_prob']*100:g} % x {r['relay_stall_ms']:g} ms" if r['relay_stall_prob'] else "none"
    print(f"| {r['operator']} | {r['mode']} | {r['relay_one_way_ms']:g} ms, {r['relay_jitter_ms']:g} ms | {stalls} "
          f"| {r['round_trip_p50_ms']:.0f} / {r['round_trip_p99_ms']:.0f} | {r['energy_j']:.4f} "
          f"| {r['penetration_p99_m']*1e3:.2f} | {r['force_rms_error_n']:.3f} | {r['reference_force_rms_n']:.3f} "
          f"| {r['max_force_step_n']:.3f} | {r['beyond_validity_ticks']} |")
# gnuplot data: one file per operator and mode, stalled links only (and 0 ms).
for r in rows:
    if r['relay_stall_prob'] or r['relay_one_way_ms'] == 0:
        with open(f"{sys.argv[2]}/{r['operator']}-{r['mode']}.dat", "a") as f:
            f.write(f"{r['round_trip_p50_ms']} {r['energy_j']} {r['penetration_p99_m']*1e3}\n")
PY

if [ "$results" != /dev/null ]; then
  plots=""
  for op in "${operators[@]}"; do
    for mode in local_model server_force; do
      [ -f "$tmp/$op-$mode.dat" ] || continue
      label="$op, ${mode/_/ }"
      style=$([ "$mode" = local_model ] && echo 'lw 2' || echo 'dt 2')
      plots+="${plots:+, }\"$tmp/$op-$mode.dat\" using 1:COL with linespoints $style title \"$label\""
    done
  done
  gnuplot <<GP
set terminal pngcairo size 1000,420
set output "$out/relay.png"
set multiplot layout 1,2 title "through hapticctl relay (jitter, 1 % of chunks held 100 ms)"
set xlabel "measured round trip p50 (ms)"
set key top left font ",8"
set ylabel "energy into the hand over 4 s (J)"
set logscale y
set yrange [1e-5:*]
plot ${plots//COL/(\$2 > 1e-5 ? \$2 : 1e-5)}
unset logscale y
set yrange [0:*]
set ylabel "penetration p99 (mm)"
plot ${plots//COL/3}
unset multiplot
GP
fi
