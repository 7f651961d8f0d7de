#!/usr/bin/env bash
# tsectl's own contract, without a bus: usage errors exit 2 naming what is wrong, a bad trajectory
# file is refused before the bus is touched (naming its line), no CAN interface exits 1.
set -u
T=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
check() { local name=$1; shift; if "$@"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $name"; fi; }

"$T" --help | grep -q "usage: tsectl"; check "--help prints usage" test $? -eq 0
"$T" --iface x status >/dev/null 2>"$tmp/e"; check "missing --node exits 2" test $? -eq 2
"$T" --iface x --node 16 status >/dev/null 2>"$tmp/e"; check "node 16 exits 2" test $? -eq 2
"$T" --iface x --node 1 frobnicate >/dev/null 2>"$tmp/e"; rc=$?
check "unknown command exits 2" test $rc -eq 2
check "unknown command is named" grep -q frobnicate "$tmp/e"
printf 't,x,y,z,roll,pitch,yaw\n0.1,0,0,1,0,0,0\n0.2,0,0,1,0,0\n' >"$tmp/short.csv"
"$T" --iface nosuchcan0 --node 1 trajectory "$tmp/short.csv" >/dev/null 2>"$tmp/e"; rc=$?
check "a short row exits 2 before the bus" test $rc -eq 2
check "the short row's line is named" grep -q "short.csv:3: expected 7 fields" "$tmp/e"
printf '0.2,0,0,1,0,0,0\n0.1,0,0,1,0,0,0\n' >"$tmp/back.csv"
"$T" --iface nosuchcan0 --node 1 trajectory "$tmp/back.csv" >/dev/null 2>"$tmp/e"
check "time going back is refused with its line" grep -q "back.csv:2: t must increase" "$tmp/e"
printf '0.1,0,0,1,0,zero,0\n' >"$tmp/nan.csv"
"$T" --iface nosuchcan0 --node 1 trajectory "$tmp/nan.csv" >/dev/null 2>"$tmp/e"
check "a non-number is refused with its line and field" grep -q "nan.csv:1: field 6 'zero' is not a number" "$tmp/e"
"$T" --iface nosuchcan0 --node 1 move 0 0 1 0 0 >/dev/null 2>"$tmp/e"; check "move with five numbers exits 2" test $? -eq 2
"$T" --iface nosuchcan0 --node 1 move 0 0 1 0 0 x >/dev/null 2>"$tmp/e"; check "move with a non-number exits 2" test $? -eq 2
"$T" --iface nosuchcan0 --node 1 status >/dev/null 2>"$tmp/e"; rc=$?
check "no such CAN interface exits 1" test $rc -eq 1
check "the interface is named" grep -q nosuchcan0 "$tmp/e"
"$T" --iface x --node 1 params list | grep -q "steps_per_m"; check "params list needs no bus" test $? -eq 0
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
