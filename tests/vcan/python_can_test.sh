#!/usr/bin/env bash
# tse.can against a controller through the harness (python_can.sh in the VM, or on vcan0) with
# README's Python session, then the example's telemetry plotted on the host (matplotlib is not in
# the VM) into WORKDIR/telemetry.png.  The controller is tse-sim, or with --board ELF that image on
# the emulated board (harness.sh --board), where only the client's suite runs.  Prints pytest's closing line as the last line of the
# client's part.
# Usage: python_can_test.sh PYTHON PYDIR WORKDIR [--board ELF] BINARY... (tse-sim or, for the
# board, tse-rig and tse-canbridge; tsectl and tse-kin for target.sh)
set -u
py=$1; pydir=$2; work=$3; shift 3
board=()
[ "${1:-}" != --board ] || { board=(--board "$2"); shift 2; }
here=$(dirname "$(readlink -f "$0")")
out="$work/python_can.out"
mkdir -p "$work"
# README's five-line session, as printed there (the first python block of its "## Python").
readme=$(dirname "$pydir")/README.md
awk '/^## Python/ { on = 1; next } on && /^```python/ { grab = 1; next } grab && /^```/ { exit } grab' \
  "$readme" >"$work/readme_session.py"
# numpy: Controller.path plans with tse.plan, whose arrays are numpy's.
HARNESS_PY_PACKAGES=python3-numpy bash "$here/harness.sh" ${board[@]+"${board[@]}"} --python "$pydir" --file "$work/readme_session.py" \
  --file "$here/target.sh" "$here/python_can.sh" "$work" "$@" >"$out" 2>&1
rc=$?
sed '/=== telemetry begin/,/=== telemetry end/d' "$out"
sed -n '/=== telemetry begin/,/=== telemetry end/p' "$out" | sed '1d;$d' >"$work/telemetry.csv"
prc=1
if [ ${#board[@]} -ne 0 ]; then
  prc=0 # the example runs against tse-sim only (python_can.sh)
elif [ -s "$work/telemetry.csv" ]; then
  "$py" "$pydir/examples/move_and_plot.py" --plot-from "$work/telemetry.csv" --png "$work/telemetry.png"
  prc=$?
fi
target=tse-sim
[ ${#board[@]} -eq 0 ] || target="the board"
echo "pytest (tse.can against $target): $(grep -E '^=+ .*(passed|failed|error).* in [0-9.]+s' "$out" | tail -1 | tr -d '=' | sed 's/^ *//; s/ *$//')"
[ $rc -eq 0 ] && [ $prc -eq 0 ]
