# Sourced by the scripts that CI runs: `phase NAME COMMAND...` runs the
# command and prints how long it took ("phase NAME: M.M min"), so that
# .ci/run's output says where its minutes go.
phase() {
  local name=$1
  shift
  local start=$SECONDS
  "$@"
  local status=$?
  awk -v name="$name" -v s=$((SECONDS - start)) 'BEGIN { printf "phase %s: %.1f min\n", name, s / 60 }'
  return $status
}
