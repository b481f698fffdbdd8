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

# shellcheck source=scripts/start_server.sh
. scripts/start_server.sh
echo "demo: haptic-server on 127.0.0.1:$port"

# 100 poses a second: the scene steps at 1 kHz, so every pose gets a frame.
./build/bin/hapticctl drive --server "127.0.0.1:$port" --scene "probe on torus" \
  --tool probe --path scenes/press_and_slide.csv --rate 100

kill -TERM "$server"
wait "$server"
echo "demo: haptic-server stopped"
