#!/usr/bin/env bash
# packages_test.sh BUILD_DIR PREFIX: `cpack -G DEB` of BUILD_DIR into a
# scratch folder, each package declaring its Debian dependencies, and
# lintian on them with warnings failing. The packages are made from a
# build configured with -DCMAKE_INSTALL_PREFIX=/usr (docs/sdk.md):
# skipped (77) for another PREFIX, or without lintian.
set -euo pipefail
build=$1
prefix=$2
if [ "$prefix" != /usr ]; then
  echo "the packages come from a build for /usr (-DCMAKE_INSTALL_PREFIX=/usr); this one is for $prefix"
  exit 77
fi
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
depends_on haptic-server adduser libgrpc++1.51 libfcl0.7
depends_on hapticctl libgrpc++1.51
depends_on libhaptics-client-dev libgrpc++1.51 libprotobuf32
depends_on python3-haptics python3 libhaptics-client-dev
lintian --fail-on error,warning "$work"/*.deb
echo "ok"
