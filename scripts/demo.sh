#!/usr/bin/env bash
# Sets up, builds, and runs the service's main job as far as it exists today:
# the Haptic Data Structure import of the bundled models (the server and the
# tool-driving client arrive with the gRPC service; this script will start
# them then).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j2 --target hapticctl
for model in tests/data/cube.iv tests/data/cube.wrl tests/data/cube_binary.stl; do
  echo "== hapticctl inspect $model"
  ./build/bin/hapticctl inspect "$model"
done
