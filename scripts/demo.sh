#!/usr/bin/env bash
# Sets up, builds, and runs the service: haptic-server on a free 127.0.0.1
# port with the bundled demo scene (a probe on an organ-like torus lying on
# a table), then `hapticctl drive` as the input device, playing a recorded
# path that presses the probe into the organ and slides it along; it prints
# each frame's contacts and force. Then the server is stopped (SIGTERM).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j2 --target hapticctl haptic-server

log=$(mktemp)
./build/bin/haptic-server --listen 127.0.0.1:0 --scene scenes/probe_on_torus.textproto \
  2>"$log" &
server=$!
trap 'kill "$server" 2>/dev/null || true; rm -f "$log"' EXIT
port=""
for _ in $(seq 300); do
  port=$(sed -n 's/.*listening on port \([0-9]*\).*/\1/p' "$log")
  [ -n "$port" ] && break
  kill -0 "$server" 2>/dev/null || { cat "$log" >&2; exit 1; }
  sleep 0.1
done
[ -n "$port" ] || { echo "demo: the server did not start" >&2; cat "$log" >&2; exit 1; }
echo "demo: haptic-server on 127.0.0.1:$port"

# 100 poses a second: the scene steps at 1 kHz, so every pose gets a frame.
./build/bin/hapticctl drive --server "127.0.0.1:$port" --scene "probe on torus" \
  --tool probe --path scenes/press_and_slide.csv --rate 100

kill -TERM "$server"
wait "$server"
echo "demo: haptic-server stopped"
