#!/usr/bin/env bash
# The harness's own checks (tests/vcan/harness.sh).
#   harness_test.sh local WORKDIR TSE_SIM  bad input refused before anything is set up; then the
#       vcan0 path, with 'id' and 'ip' stood in for (this kernel has no vcan): data files in the
#       scenario's directory, its exit status, a hang stopped with all it started and reported;
#       --python: Debian's python3 with two trees of the test's on PYTHONPATH, python-can (on its
#       'virtual' bus, standing in for vcan0 as the shims do) and pytest, nothing written
#   harness_test.sh vm WORKDIR TSE_SIM     the same hang in the VM, with a 20 s limit (about 30 s);
#       --python there: a frame sent and received on vcan0 by python-can over SocketCAN and seen
#       by candump, pytest's '1 passed' (about 45 s)
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
rm -rf "$work/in" "$work/other" "$work/shim" "$work/hang" "$work/ends" "$work/w" "$work/ip.log" \
  "$work/pkg" "$work/pkg_env" "$work/py"
mkdir -p "$work/in" "$work/other" "$work/other/pkg" "$work/pkg" "$work/pkg_env"
token="token-$$-$RANDOM"
echo "$token" >"$work/in/token.txt"
echo "speed = 0.25" >"$work/in/params.txt"
echo "another" >"$work/other/token.txt"
line=$(grep -n '^sleep 1000$' "$here/hang.sh" | cut -d: -f1)

# --python: two trees (one by --python, one by HARNESS_PYTHON), a pytest file and a python-can
# snippet as data files, and a scenario that runs them.  The bus comes from bus.txt: 'socketcan'
# in the VM, python-can's in-process 'virtual' bus where vcan0 is stood in for.
printf 'def answer():\n    return 42\n' >"$work/pkg/probe.py"
printf 'def answer():\n    return "%s"\n' "$token" >"$work/pkg_env/probe_env.py"
cat >"$work/in/test_probe.py" <<'PY'
import probe


def test_answer():
    assert probe.answer() == 42
PY
cat >"$work/in/bus_probe.py" <<'PY'
import sys

import can

iface = sys.argv[1]
tx = can.Bus(channel="vcan0", interface=iface)
rx = can.Bus(channel="vcan0", interface=iface)
tx.send(can.Message(arbitration_id=0x123, data=[0xDE, 0xAD, 0xBE, 0xEF], is_extended_id=False))
m = rx.recv(timeout=5)
print("received over %s: %s" % (iface, "nothing" if m is None else "%03X#%s" % (m.arbitration_id, m.data.hex().upper())))
tx.shutdown()
rx.shutdown()
PY
cat >"$work/in/py.sh" <<'SCENARIO'
iface=$(cat bus.txt)
echo "env: PYTHONDONTWRITEBYTECODE=${PYTHONDONTWRITEBYTECODE:-unset} PY_COLORS=${PY_COLORS:-unset}"
python3 -c 'import sys, can, probe, probe_env
print("prefix:", sys.prefix)
print("path:", " ".join(sys.path))
print("can from:", can.__file__)
print("probes:", probe.answer(), probe_env.answer())'
if [ "$iface" = socketcan ]; then
  candump -n 1 vcan0 >dump.log &
  dump=$!
  sleep 1
fi
python3 bus_probe.py "$iface"
if [ "$iface" = socketcan ]; then
  sleep 0.5
  kill $dump 2>/dev/null
  echo "candump:$(cat dump.log)"
fi
python3 -m pytest -q -p no:cacheprovider test_probe.py
echo "pytest: exit $?"
python3 -c 'import os, sys
print("written:", sorted(os.path.join(r, n) for d in sys.path[1:3] + ["."] for r, ds, fs in os.walk(d)
                         for n in ds + fs if n in ("__pycache__", ".pytest_cache")))'
SCENARIO
py_files=(--file "$work/in/test_probe.py" --file "$work/in/bus_probe.py" --file "$work/in/bus.txt")

# Output checks shared by both paths: $out, $rc of a py.sh run, the trees at $1 and $2.
check_python() {
  local dir=$1 dir_env=$2
  check "the scenario ended with 0 (got $rc)" '[ "$rc" -eq 0 ]'
  check "a figure for python3's start" 'grep -qE "^figure: (VM )?python3 -c .import can, pytest.: [0-9.]+ s$" "$out"'
  check "PYTHONDONTWRITEBYTECODE=1, PY_COLORS=0" 'grep -qx "env: PYTHONDONTWRITEBYTECODE=1 PY_COLORS=0" "$out"'
  check "Debian's python3: sys.prefix /usr" 'grep -qx "prefix: /usr" "$out"'
  check "PYTHONPATH: the HARNESS_PYTHON tree, then the --python one, then the standard library" \
    'grep -qE "^path:  $dir_env $dir /usr/lib/python311.zip /usr/lib/python3.11 /usr/lib/python3.11/lib-dynload( /usr/local/lib/python3.11/dist-packages)? /usr/lib/python3/dist-packages( |$)" "$out"'
  check "python-can from Debian's dist-packages" 'grep -qx "can from: /usr/lib/python3/dist-packages/can/__init__.py" "$out"'
  check "both trees' modules imported" 'grep -qx "probes: 42 $token" "$out"'
  check "pytest: '1 passed' and exit 0" 'grep -qE "^1 passed in [0-9.]+s$" "$out" && grep -qx "pytest: exit 0" "$out"'
  check "no __pycache__ or .pytest_cache in the trees or the scenario's directory" 'grep -qx "written: \[\]" "$out"'
  check "no trace lines in the output" '! grep -qE "^\+[0-9]+ [0-9]+: " "$out"'
}

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
  refused "missing --python" "python directory not found: $work/in/nopkg" \
    bash "$harness" --python "$work/pkg" --python "$work/in/nopkg" "${ok_args[@]}"
  refused "missing HARNESS_PYTHON entry" "python directory not found: $work/in/gonepkg" \
    env HARNESS_PYTHON="$work/pkg $work/in/gonepkg" bash "$harness" "${ok_args[@]}"
  refused "a file as a python directory" "python directory is not a directory: $work/in/token.txt" \
    bash "$harness" --python="$work/in/token.txt" "${ok_args[@]}"
  refused "two python directories of one name" "two python directories named pkg" \
    bash "$harness" --python "$work/pkg" --python "$work/other/pkg" "${ok_args[@]}"
  refused "--python without a directory" "--python needs a DIR" bash "$harness" --python
  refused "HARNESS_PY_PACKAGES not a python3 package" "HARNESS_PY_PACKAGES names Debian python3-* packages, not 'numpy'" \
    env HARNESS_PY_PACKAGES=numpy bash "$harness" --python "$work/pkg" "${ok_args[@]}"

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

  # --python on the vcan0 path: the trees themselves on PYTHONPATH, nothing written into them.
  echo virtual >"$work/in/bus.txt"
  out="$work/py.out"
  PATH="$work/shim:$PATH" HARNESS_TIMEOUT=120 HARNESS_PYTHON="$work/pkg_env" \
    bash "$harness" --python "$work/pkg" "${py_files[@]}" "$work/in/py.sh" "$work/py" "$sim" >"$out" 2>&1
  rc=$?
  sed 's/^/  | /' "$out"
  check "python3 on PATH is WORKDIR/python-bin/python3, a link to /usr/bin/python3" \
    '[ "$(readlink "$work/py/python-bin/python3")" = /usr/bin/python3 ]'
  check_python "$work/pkg" "$work/pkg_env"
  check "python-can's frame through its virtual bus" 'grep -qx "received over virtual: 123#DEADBEEF" "$out"'
  check "nothing written into the host's trees" \
    '[ -z "$(find "$work/pkg" "$work/pkg_env" -name __pycache__)" ] && [ ! -e "$work/py/run/__pycache__" ]'
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

  # --python in the VM: the trees as /py/NAME, python-can over SocketCAN on vcan0.
  echo socketcan >"$work/in/bus.txt"
  out="$work/py.out"
  t0=$(date +%s)
  HARNESS_TIMEOUT=240 HARNESS_PYTHON="$work/pkg_env" \
    bash "$harness" --python "$work/pkg" "${py_files[@]}" "$work/in/py.sh" "$work/vm" "$sim" >"$out" 2>&1
  rc=$?
  t1=$(date +%s)
  sed 's/^/  | /' "$out"
  check "the VM path was taken" 'grep -q "booting a Debian kernel under QEMU" "$out"'
  check_python /py/pkg /py/pkg_env
  check "python-can's frame received on a second SocketCAN bus" 'grep -qx "received over socketcan: 123#DEADBEEF" "$out"'
  check "candump saw it on vcan0" 'grep -qE "^candump: +vcan0 +123 +\[4\] +DE AD BE EF$" "$out"'
  echo "figure: harness run of the --python scenario in the VM: $((t1 - t0)) s"
else
  echo "usage: harness_test.sh local|vm WORKDIR TSE_SIM" >&2
  exit 2
fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
