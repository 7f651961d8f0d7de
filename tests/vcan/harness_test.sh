#!/usr/bin/env bash
# The harness's own checks (tests/vcan/harness.sh).
#   harness_test.sh local WORKDIR TSE_SIM  bad input refused before anything is set up; then the
#       vcan0 path, with 'id' and 'ip' stood in for (this kernel has no vcan): data files in the
#       scenario's directory, its exit status, a hang stopped with all it started and reported
#   harness_test.sh vm WORKDIR TSE_SIM     the same hang in the VM, with a 20 s limit (about 30 s)
set -u
mode=$1
work=$2
sim=$3
here=$(dirname "$(readlink -f "$0")")
harness="$here/harness.sh"
pass=0
fail=0
check() { if eval "$2"; then pass=$((pass + 1)); echo "ok: $1"; else fail=$((fail + 1)); echo "FAIL: $1"; fi; }

# (WORKDIR/vm, the VM path's work directory, keeps the kernel it unpacked between runs.)
rm -rf "$work/in" "$work/other" "$work/shim" "$work/hang" "$work/ends" "$work/w" "$work/ip.log"
mkdir -p "$work/in" "$work/other"
token="token-$$-$RANDOM"
echo "$token" >"$work/in/token.txt"
echo "speed = 0.25" >"$work/in/params.txt"
echo "another" >"$work/other/token.txt"
line=$(grep -n '^sleep 1000$' "$here/hang.sh" | cut -d: -f1)

# Output checks shared by both paths: $out, $rc of a hang.sh run with HARNESS_TIMEOUT=$1.
check_hang() {
  local limit_s=$1
  check "exit status 124 after the time-out (got $rc)" '[ "$rc" -eq 124 ]'
  check "the --file data file arrived in the scenario's directory" 'grep -qx "data: $token" "$out"'
  check "the HARNESS_FILES data file arrived too" 'grep -qx "params: speed = 0.25" "$out"'
  check "the binary is on the scenario's PATH" 'grep -qx "binary: on PATH" "$out"'
  check "the scenario's stderr comes through" 'grep -qx "a line on stderr" "$out"'
  check "the time-out names the hanging command and line" \
    'grep -qxF "harness: the scenario timed out after $limit_s s; it was running: sleep 1000 (scenario line $line)" "$out"'
  check "the scenario did not go on" '! grep -q "not reached" "$out"'
  check "no trace lines in the output" '! grep -qE "^\+[0-9]+ [0-9]+: " "$out"'
}

if [ "$mode" = local ]; then
  # refused: exit 2, a message naming the culprit, and nothing set up (no work directory made)
  refused() { # NAME EXPECTED-MESSAGE COMMAND...
    local name=$1 msg=$2
    shift 2
    rm -rf "$work/w"
    "$@" >"$work/refused.out" 2>&1
    local r=$?
    check "$name: refused with exit 2 (got $r) and '$msg'" \
      '[ $r -eq 2 ] && grep -qF -e "$msg" "$work/refused.out" && [ ! -e "$work/w" ]'
  }
  ok_args=("$here/hang.sh" "$work/w" "$sim")
  refused "missing --file" "data file not found: $work/in/nope.csv" \
    bash "$harness" --file "$work/in/token.txt" --file "$work/in/nope.csv" "${ok_args[@]}"
  refused "missing HARNESS_FILES entry" "data file not found: $work/in/gone.txt" \
    env HARNESS_FILES="$work/in/params.txt $work/in/gone.txt" bash "$harness" "${ok_args[@]}"
  refused "a directory as a data file" "data file is not a regular file: $work/other" \
    bash "$harness" --file "$work/other" "${ok_args[@]}"
  refused "two data files of one name" "two data files named token.txt" \
    bash "$harness" --file "$work/in/token.txt" --file "$work/other/token.txt" "${ok_args[@]}"
  refused "--file without a path" "--file needs a PATH" bash "$harness" --file
  refused "an unknown option" "unknown option '--files'" bash "$harness" --files x "${ok_args[@]}"
  refused "HARNESS_TIMEOUT not a number" "HARNESS_TIMEOUT must be a whole number of seconds, not '2m'" \
    env HARNESS_TIMEOUT=2m bash "$harness" "${ok_args[@]}"
  refused "HARNESS_TIMEOUT zero" "HARNESS_TIMEOUT must be between 1 and 999999 seconds, not '0'" \
    env HARNESS_TIMEOUT=0 bash "$harness" "${ok_args[@]}"
  refused "missing scenario" "scenario not found: $work/in/none.sh" \
    bash "$harness" "$work/in/none.sh" "$work/w" "$sim"
  refused "missing binary" "binary not found: $work/in/tse-nope" \
    bash "$harness" "$here/hang.sh" "$work/w" "$sim" "$work/in/tse-nope"
  refused "no work directory" "usage: harness.sh" bash "$harness" "$here/hang.sh"

  # The vcan0 path, with root and vcan0 stood in for: the scenarios here use no CAN.
  mkdir -p "$work/shim"
  printf '#!/bin/sh\n[ "$1" = -u ] && echo 0 || exec /usr/bin/id "$@"\n' >"$work/shim/id"
  printf '#!/bin/sh\necho "$*" >>"%s/ip.log"\n' "$work" >"$work/shim/ip"
  chmod +x "$work/shim/id" "$work/shim/ip"
  gone() { ! pgrep -g "$(cat "$1" 2>/dev/null || echo 0)" >/dev/null; } # nothing left in the group

  out="$work/hang.out"
  PATH="$work/shim:$PATH" HARNESS_TIMEOUT=3 HARNESS_FILES="$work/in/params.txt" \
    bash "$harness" --file "$work/in/token.txt" "$here/hang.sh" "$work/hang" "$sim" >"$out" 2>&1
  rc=$?
  sed 's/^/  | /' "$out"
  check "the vcan0 path was taken" 'grep -qx "harness: vcan0 on this kernel" "$out"'
  check_hang 3
  check "the data files are in WORKDIR/run" '[ -f "$work/hang/run/token.txt" ] && [ -f "$work/hang/run/params.txt" ]'
  check "the hung scenario and its background job are gone" 'gone "$work/hang/run/scenario.pid"'
  check "vcan0 made, brought up and deleted" \
    '[ "$(cat "$work/ip.log")" = "$(printf "link add dev vcan0 type vcan\nlink set vcan0 up\nlink del vcan0")" ]'

  # A scenario that ends by itself: its status, no time-out report, what it left running ended.
  cat >"$work/in/ends.sh" <<'SCENARIO'
echo $$ >scenario.pid
sleep 300 &
echo "files here: $(ls | tr '\n' ' ')"
exit 3
SCENARIO
  out="$work/ends.out"
  PATH="$work/shim:$PATH" bash "$harness" --file="$work/in/params.txt" "$work/in/ends.sh" "$work/ends" >"$out" 2>&1
  rc=$?
  sed 's/^/  | /' "$out"
  check "the scenario's own exit status 3 (got $rc)" '[ "$rc" -eq 3 ]'
  check "its output, run in a fresh directory with the data file" 'grep -qx "files here: params.txt scenario.pid " "$out"'
  check "no time-out report" '! grep -q "timed out" "$out"'
  check "its background job ended with it" 'gone "$work/ends/run/scenario.pid"'
elif [ "$mode" = vm ]; then
  out="$work/hang.out"
  t0=$(date +%s)
  HARNESS_TIMEOUT=20 HARNESS_FILES="$work/in/params.txt" \
    bash "$harness" --file "$work/in/token.txt" "$here/hang.sh" "$work/vm" "$sim" >"$out" 2>&1
  rc=$?
  t1=$(date +%s)
  sed 's/^/  | /' "$out"
  check "the VM path was taken" 'grep -q "booting a Debian kernel under QEMU" "$out"'
  check_hang 20
  echo "figure: harness run with a 20 s scenario limit: $((t1 - t0)) s"
else
  echo "usage: harness_test.sh local|vm WORKDIR TSE_SIM" >&2
  exit 2
fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
