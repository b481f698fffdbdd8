#!/usr/bin/env bash
# The Debian packages on a clean Debian 12, as a user (or deploy/docker's
# runtime stage) installs them: makes the four packages of build/ (cpack),
# makes a minimal bookworm root with debootstrap from Debian's mirror,
# installs the packages there with apt (which fetches their dependencies),
# and inside it: the system user haptic exists, the unit runs
# /usr/bin/haptic-server, haptic-server serves the demo scene from
# /usr/share/haptics, `hapticctl health` says SERVING, and the examples
# built against the installed SDK (C with pkg-config, C++ with
# find_package(HapticsClient)) and the Python example each feel the organ
# push back. Needs root (chroot) and the network; about 2 minutes, not
# part of the test suite. docs/sdk.md.
#   scripts/clean_install.sh [ROOT_DIR]   (kept and reused; default: a temporary folder, removed)
set -euo pipefail
cd "$(dirname "$0")/.."
[ "$(id -u)" -eq 0 ] || { echo "clean_install: needs root (debootstrap, chroot)" >&2; exit 2; }
command -v debootstrap >/dev/null || apt-get install -y -qq debootstrap >/dev/null
root=${1:-$(mktemp -d)}
keep=${1:+yes}
cleanup() {
  umount "$root/proc" 2>/dev/null || true
  [ -n "$keep" ] || rm -rf "$root"
}
trap cleanup EXIT

cmake --build build -j2 >/dev/null
rm -rf "$root/tmp/haptics" 2>/dev/null || true
debs=$(mktemp -d)
(cd build && cpack -G DEB -B "$debs" >"$debs/cpack.log" 2>&1) || { cat "$debs/cpack.log" >&2; exit 1; }
[ -x "$root/usr/bin/apt-get" ] ||
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian >/dev/null
mkdir -p "$root/tmp/haptics"
cp "$debs"/*.deb "$root/tmp/haptics/"
rm -rf "$debs"
cp -r examples "$root/tmp/haptics/examples"
cp /etc/resolv.conf "$root/etc/resolv.conf"
mount -t proc proc "$root/proc"

# shellcheck disable=SC2016 # expanded inside the chroot
chroot "$root" /bin/bash -euo pipefail -c '
export DEBIAN_FRONTEND=noninteractive
cd /tmp/haptics
apt-get update -qq
apt-get install -y -qq --reinstall --no-install-recommends ./*.deb >/dev/null
echo "installed: $(ls ./*.deb | xargs -n1 basename | tr "\n" " ")"
id haptic >/dev/null
grep -q "^ExecStart=/usr/bin/haptic-server " /lib/systemd/system/haptic-server.service
apt-get install -y -qq --no-install-recommends gcc g++ make cmake pkg-config >/dev/null
cc -std=c99 -Wall -Werror examples/device.c $(pkg-config --cflags --libs haptics-client) -o device_c
cmake -S examples -B examples-build >/dev/null
cmake --build examples-build >/dev/null

haptic-server --listen 127.0.0.1:0 --scene /usr/share/haptics/scenes/probe_on_torus.textproto 2>server.log &
server=$!
trap "kill $server 2>/dev/null || true" EXIT
port=""
for _ in $(seq 100); do
  port=$(sed -n "s/.*listening on port \([0-9]*\).*/\1/p" server.log)
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || { cat server.log >&2; exit 1; }
[ "$(hapticctl health --server 127.0.0.1:$port)" = SERVING ]
felt() {  # NAME COMMAND...: its force_z_n must be > 0
  local name=$1 out
  shift
  out=$("$@" "127.0.0.1:$port" | grep "^force_z_n=")
  echo "$name: $out"
  awk -F= "{ exit !(\$2 > 0) }" <<<"$out"
}
felt "device.c (pkg-config)" ./device_c
felt "device_loop (find_package)" ./examples-build/device_loop
felt "device.py" python3 examples/device.py
'
echo "clean_install: ok"
