#!/usr/bin/env bash
# Installs every Debian 12 package the project needs, then the npm packages
# of package-lock.json (three for web/viewer/, playwright-core for
# tests/web/). Idempotent: quiet and quick when everything is already there.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libfcl-dev libccd-dev
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler libabsl-dev libssl-dev openssl
  libassimp-dev libcoin-dev libseccomp-dev libboost-dev libsqlite3-dev libcurl4-openssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev librapidcheck-dev
  prometheus-cpp-dev libcli11-dev nlohmann-json3-dev libcgal-dev
  gnuplot-nox clang-14 libclang-rt-14-dev clang-format
  chromium nodejs npm yamllint python3-yaml ccache
  pybind11-dev python3-dev file lintian libhwy-dev
)

missing=()
for p in "${packages[@]}"; do
  if [ "$p" = npm ]; then
    # NodeSource's nodejs bundles npm and conflicts with Debian's npm
    # package, so any npm on the PATH counts.
    command -v npm >/dev/null || missing+=("$p")
    continue
  fi
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -ne 0 ]; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "setup: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# npm writes node_modules/.package-lock.json last: when it is missing or
# older than package-lock.json, node_modules is missing, partial or stale.
# Playwright never downloads a browser: the tests use /usr/bin/chromium.
if [ ! -f node_modules/.package-lock.json ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  echo "setup: npm ci" >&2
  PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --ignore-scripts --no-audit --no-fund --loglevel=error >/dev/null
fi
