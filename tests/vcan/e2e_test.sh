#!/usr/bin/env bash
# The end-to-end scenario through the harness, then the candump of the whole session decoded with
# the DBC by Debian's python3-canmatrix on the host.
# Usage: e2e_test.sh PYTHON DBC WORKDIR TSE_SIM TSECTL TSE_KIN
set -u
py=$1; dbc=$2; work=$3; shift 3
here=$(dirname "$(readlink -f "$0")")
out="$work/e2e.out"
mkdir -p "$work"
bash "$here/harness.sh" "$here/e2e.sh" "$work" "$@" >"$out" 2>&1
rc=$?
sed '/=== dump begin/,/=== dump end/d' "$out"
sed -n '/=== dump begin/,/=== dump end/p' "$out" | sed '1d;$d' >"$work/session.log"
"$py" "$here/decode_log.py" "$dbc" "$work/session.log"
drc=$?
[ $rc -eq 0 ] && [ $drc -eq 0 ]
