# Sourced by the shell contract tests (tests/cli, tests/sim): a scratch directory $tmp removed on
# exit, `check NAME COMMAND...` counting what passes and fails (a failure shows the head of
# $tmp/e, where a test may keep the output it checked), and `check_done` to print the tally and
# fail the test on any failure.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
check() {
  local name=$1
  shift
  if "$@"; then
    pass=$((pass + 1))
  else
    fail=$((fail + 1))
    echo "FAIL: $name"
    sed 's/^/  | /' "$tmp/e" 2>/dev/null | head -5
  fi
}
check_done() {
  echo "$pass passed, $fail failed"
  [ "$fail" -eq 0 ]
}
