#!/usr/bin/env bash
# packages_test.sh BUILD_DIR: `cpack -G DEB` of BUILD_DIR into a scratch
# folder (the packages install under /usr whatever prefix the build has),
# each package declaring its Debian dependencies and its files under /usr,
# /lib/systemd and /etc only; the unit naming /usr's paths; and lintian on
# them with warnings failing. Skipped (77) without lintian.
set -euo pipefail
build=$1
command -v lintian >/dev/null || { echo "lintian is missing: scripts/setup.sh installs it"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cpack --config "$build/CPackConfig.cmake" -G DEB -B "$work" >/dev/null
depends_on() {  # PACKAGE DEPENDENCY...: the package's Depends names each
  local deb depends
  deb=$(echo "$work/$1"_*.deb)
  depends=$(dpkg-deb -f "$deb" Depends)
  echo "$1: $depends"
  shift
  for d in "$@"; do
    echo "$depends" | grep -q "\b$d\b" || { echo "FAIL: no $d in it" >&2; return 1; }
  done
}
depends_on haptic-server adduser libgrpc++1.51 libfcl0.7 libhwy1
depends_on hapticctl libgrpc++1.51
depends_on libhaptics-client-dev libgrpc++1.51 libprotobuf32
depends_on python3-haptics python3 libhaptics-client-dev
for deb in "$work"/*.deb; do
  if dpkg-deb -c "$deb" | awk '{print $6}' | grep -v -E '^\./$|^\./(usr|etc)(/|$)|^\./lib/$|^\./lib/systemd(/|$)' | grep .; then
    echo "FAIL: $(basename "$deb") has files outside /usr, /lib/systemd and /etc" >&2
    exit 1
  fi
done
unit=$(dpkg-deb --fsys-tarfile "$work"/haptic-server_*.deb | tar -xO ./lib/systemd/system/haptic-server.service)
echo "$unit" | grep -q '^ExecStart=/usr/bin/haptic-server ' || { echo "FAIL: the unit runs no /usr/bin/haptic-server" >&2; exit 1; }
echo "$unit" | grep -q '^EnvironmentFile=-/etc/default/haptic-server$' || { echo "FAIL: the unit reads no /etc/default/haptic-server" >&2; exit 1; }
lintian --fail-on error,warning "$work"/*.deb
echo "ok"
