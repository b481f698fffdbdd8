#!/usr/bin/env bash
# Sets up, builds, and runs the service's main job as far as it exists today:
# a model read into the Haptic Data Structure, then a tool (a cube) driven
# down into an object step by step, with the contact reconstructed at each
# step. The gRPC server and its streaming client replace the local calls
# when the service lands.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j2 --target hapticctl
ctl=./build/bin/hapticctl
model=tests/data/cube.iv
echo "== the object, read into the HDS"
"$ctl" inspect "$model"
echo
echo "== a tool stepping down 0.004 m per step into it (continuous contact)"
for z in 1.006 1.002 0.998 0.994; do
  echo "-- tool at z = $z"
  "$ctl" contact "$model" "$model" --pose-moving "0.3,0.2,$z,0,0,0.2" \
    --direction 0,0,-0.004 --continuous
done
