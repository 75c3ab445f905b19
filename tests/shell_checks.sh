# The scratch folder, counters and runners the shell tests share. Sourcing it
# makes $work and, on exit, kills the server whose pid a test put in
# $server_pid and removes $work. End with `report NAME`, whose status is the test's.

work=$(mktemp -d)
server_pid=
cleanup() {
  if [ -n "$server_pid" ]; then kill "$server_pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT

passed=0
failed=0
# Counters by assignment: ((n++)) returns 1 when n is 0, which set -e treats as failure.
pass() { passed=$((passed + 1)); }
fail() {
  failed=$((failed + 1))
  echo "FAIL: $*" >&2
}
# run COMMAND...: stdout in $work/out, stderr in $work/err, exit code in
# $status (without tripping set -e).
run() {
  status=0
  "$@" >"$work/out" 2>"$work/err" || status=$?
}
expect_status() {
  local want=$1 what=$2
  if [ "$status" -eq "$want" ]; then pass; else fail "$what: exit $status, want $want ($(cat "$work/err"))"; fi
}
report() {
  echo "$1: $passed passed, $failed failed"
  [ "$failed" -eq 0 ]
}
# start_scallopd NAME ARGS...: starts $scallopd ARGS in the background (ARGS must make it
# listen on port 0), its stdout through a FIFO and its log in $work/NAME.log; reads the address
# it prints into $address and its pid into $started_pid, then waits until `$scallop info`
# answers there. Needs $scallopd and $scallop.
start_scallopd() {
  local name=$1 line
  shift
  mkfifo "$work/$name.address"
  "$scallopd" "$@" >"$work/$name.address" 2>"$work/$name.log" &
  started_pid=$!
  read -r line <"$work/$name.address"
  address=${line#scallopd listening on }
  for _ in $(seq 100); do
    "$scallop" info --server "$address" >/dev/null 2>&1 && break
    sleep 0.1
  done
}
# wait_for_log FILE PATTERN [COUNT]: true once FILE holds at least COUNT (default 1) lines
# matching the grep PATTERN, false after 10 s. scallopd writes its call lines in batches,
# within a second of the call (warnings at once).
wait_for_log() {
  local file=$1 pattern=$2 count=${3:-1}
  for _ in $(seq 100); do
    [ "$(grep -c -- "$pattern" "$file")" -ge "$count" ] && return 0
    sleep 0.1
  done
  return 1
}
