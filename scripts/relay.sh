#!/usr/bin/env bash
# A remote device over a real TCP link (docs/remote-haptics.md): a
# haptic-server with the demo scene on a free 127.0.0.1 port,
# `hapticctl relay` in front of it, and `hapticctl drive --operator press`
# through the relay with the local model on and off (no simulated link on
# top); one JSON line each, then the relay's counters.
#   scripts/relay.sh [ONE_WAY_MS JITTER_MS STALL_PROB STALL_MS]   (default 20 5 0.01 30)
set -euo pipefail
cd "$(dirname "$0")/.."
one_way=${1:-20} jitter=${2:-5} stall_prob=${3:-0.01} stall_ms=${4:-30}
cmake --build build -j1 --target hapticctl haptic-server >/dev/null

# shellcheck source=scripts/start_server.sh
. scripts/start_server.sh
relay_log=$(mktemp)
./build/bin/hapticctl relay --to "127.0.0.1:$port" --one-way-ms "$one_way" \
  --jitter-ms "$jitter" --stall-prob "$stall_prob" --stall-ms "$stall_ms" --seed 1 \
  >"$relay_log" &
relay=$!
trap 'kill "$relay" "$server" 2>/dev/null || true; rm -f "$log" "$relay_log"' EXIT
relay_port=""
for _ in $(seq 100); do
  relay_port=$(sed -n 's/^relay: listening on port \([0-9]*\).*/\1/p' "$relay_log")
  [ -n "$relay_port" ] && break
  sleep 0.1
done
[ -n "$relay_port" ] || { echo "the relay did not start" >&2; cat "$relay_log" >&2; exit 1; }

for mode in on off; do
  ./build/bin/hapticctl drive --server "127.0.0.1:$relay_port" --scene "probe on torus" \
    --tool probe --operator press --local-model "$mode" --seed 1 --duration 4 --json
done
kill -TERM "$relay"
wait "$relay" || true
tail -1 "$relay_log"
