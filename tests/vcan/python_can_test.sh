#!/usr/bin/env bash
# tse.can against tse-sim through the harness (python_can.sh in the VM, or on vcan0) with README's
# Python session, then the example's telemetry plotted on the host (matplotlib is not in the VM) into WORKDIR/telemetry.png.
# Prints pytest's closing line as the last line of the client's part.
# Usage: python_can_test.sh PYTHON PYDIR WORKDIR TSE_SIM
set -u
py=$1; pydir=$2; work=$3; shift 3
here=$(dirname "$(readlink -f "$0")")
out="$work/python_can.out"
mkdir -p "$work"
# README's five-line session, as printed there (the first python block of its "## Python").
readme=$(dirname "$pydir")/README.md
awk '/^## Python/ { on = 1; next } on && /^```python/ { grab = 1; next } grab && /^```/ { exit } grab' \
  "$readme" >"$work/readme_session.py"
bash "$here/harness.sh" --python "$pydir" --file "$work/readme_session.py" "$here/python_can.sh" "$work" "$@" >"$out" 2>&1
rc=$?
sed '/=== telemetry begin/,/=== telemetry end/d' "$out"
sed -n '/=== telemetry begin/,/=== telemetry end/p' "$out" | sed '1d;$d' >"$work/telemetry.csv"
prc=1
if [ -s "$work/telemetry.csv" ]; then
  "$py" "$pydir/examples/move_and_plot.py" --plot-from "$work/telemetry.csv" --png "$work/telemetry.png"
  prc=$?
fi
echo "pytest (tse.can against tse-sim): $(grep -E '^=+ .*(passed|failed|error).* in [0-9.]+s' "$out" | tail -1 | tr -d '=' | sed 's/^ *//; s/ *$//')"
[ $rc -eq 0 ] && [ $prc -eq 0 ]
