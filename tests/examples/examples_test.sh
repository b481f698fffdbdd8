#!/usr/bin/env bash
# examples_test.sh BUILD_DIR PYTHON3: installs BUILD_DIR into a temporary
# prefix, builds examples/ against it twice (find_package(HapticsClient),
# and pkg-config haptics-client), and runs each example (C++, C, Python
# device and viewer) against the haptic-server at $HS_SERVER
# (tests/client/sdk/with_server.sh): each device must feel the organ push
# back (force up > 0), the viewer must print contacts.
set -euo pipefail
build=$1
python=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" >/dev/null
# lib, or lib/<multiarch> when the build is for /usr.
libdir=$(dirname "$(dirname "$(find "$prefix" -name haptics-client.pc)")")

echo "== find_package(HapticsClient)"
cmake -S examples -B "$work/cmake" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/cmake" >/dev/null

echo "== pkg-config haptics-client"
export PKG_CONFIG_PATH=$libdir/pkgconfig
flags=$(pkg-config --cflags --libs haptics-client)
rpath="-Wl,-rpath,$(pkg-config --variable=libdir haptics-client)"
mkdir -p "$work/pc"
# shellcheck disable=SC2086
cc -std=c99 -Wall -Wextra -Werror examples/device.c $flags $rpath -o "$work/pc/device_c"
# shellcheck disable=SC2086
c++ -std=c++17 -Wall -Wextra -Werror examples/device_loop.cpp $flags $rpath -o "$work/pc/device_loop"

felt() {  # NAME COMMAND...: runs it, checks its force_z_n > 0
  local name=$1
  shift
  local out
  out=$("$@")
  echo "$out" | sed "s/^/  $name: /"
  echo "$out" | awk -F= '/^force_z_n=/ { ok = ($2 > 0) } END { exit ok ? 0 : 1 }' \
    || { echo "FAIL: $name felt no force" >&2; return 1; }
}

export PYTHONPATH=$prefix/lib/python3/dist-packages
# Built for /usr, the extension looks for the library in the system's
# folders only.
export LD_LIBRARY_PATH=$libdir
felt "device_loop (cmake)" "$work/cmake/device_loop" "$HS_SERVER"
felt "device.c (cmake)" "$work/cmake/device_c" "$HS_SERVER"
felt "device_loop (pkg-config)" "$work/pc/device_loop" "$HS_SERVER"
felt "device.c (pkg-config)" "$work/pc/device_c" "$HS_SERVER"
felt "device.py" "$python" examples/device.py "$HS_SERVER"

echo "== viewer.py while device.py presses"
"$python" examples/device.py "$HS_SERVER" >/dev/null &
device=$!
viewer=$("$python" examples/viewer.py "$HS_SERVER" --duration 10 --contacts 3)
wait "$device"
echo "$viewer" | head -3 | sed 's/^/  viewer.py: /'
echo "$viewer" | grep -q "probe touches organ" || { echo "FAIL: viewer.py printed no contact" >&2; exit 1; }
echo "ok"
