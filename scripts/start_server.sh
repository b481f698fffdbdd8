# Sourced by scripts/demo.sh and scripts/remote.sh: starts haptic-server
# with the demo scene on a free 127.0.0.1 port in the background, stops it
# (and removes $log) on exit, and sets $server (its pid) and $port.
# HAPTIC_SERVER names another binary than ./build/bin/haptic-server.
log=$(mktemp)
"${HAPTIC_SERVER:-./build/bin/haptic-server}" --listen 127.0.0.1:0 --scene scenes/probe_on_torus.textproto \
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
[ -n "$port" ] || { echo "the server did not start" >&2; cat "$log" >&2; exit 1; }
