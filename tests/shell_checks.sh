# The counters and runners the shell tests share; source it after setting
# $work (a scratch folder). End with `report NAME`, whose status is the test's.

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
