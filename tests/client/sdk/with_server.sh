#!/usr/bin/env bash
# with_server.sh HAPTIC_SERVER COMMAND...: runs COMMAND with HS_SERVER set
# to the address of a haptic-server of its own (the binary HAPTIC_SERVER,
# the demo scene, a free 127.0.0.1 port), stopped when COMMAND ends. For
# the SDK's C, Python and example tests.
set -euo pipefail
export HAPTIC_SERVER=$1
shift
cd "$(dirname "$0")/../../.."
. scripts/start_server.sh
HS_SERVER="127.0.0.1:$port" "$@"
