#!/usr/bin/env bash
# tsectl's own contract, without a bus: help needs no bus (per command too), usage errors exit 2
# naming what is wrong (and, for ranges, the unit and the range), a bad trajectory file is refused
# before the bus is touched (naming FILE:LINE), no CAN interface exits 1, progress output in a log
# is a few plain lines.  tsectl_usage.sh TSECTL VERSION (the project's, for --version).
set -u
T=$1
TSE_VERSION=$2
. "$(dirname "$0")/../support/check.sh"

"$T" --help >"$tmp/e"; check "--help prints usage" grep -q "usage: tsectl" "$tmp/e"
"$T" move --help >"$tmp/e" 2>&1; rc=$?
check "move --help needs no bus (exit 0)" test $rc -eq 0
check "move --help shows move's synopsis" grep -q "move X Y Z ROLL PITCH YAW" "$tmp/e"
"$T" help trajectory >"$tmp/e" 2>&1
check "trajectory help says what t is measured from" grep -q "t is measured from the moment the controller starts the trajectory" "$tmp/e"
check "trajectory help says no hold row is needed" grep -q "so no hold row is needed at the start" "$tmp/e"
check "trajectory help says what the first row must satisfy" grep -q "the first row must start gently from rest" "$tmp/e"
"$T" --iface x --node 1 params --help >"$tmp/e" 2>&1; check "params --help with options exits 0" test $? -eq 0
"$T" --iface x status >/dev/null 2>"$tmp/e"; rc=$?
check "missing --node exits 2" test $rc -eq 2
check "missing --node is named" grep -q -- "--node N is needed" "$tmp/e"
"$T" --iface x --node 16 status >/dev/null 2>"$tmp/e"; check "node 16 exits 2" test $? -eq 2
"$T" --iface x --node 1 frobnicate >/dev/null 2>"$tmp/e"; rc=$?
check "unknown command exits 2" test $rc -eq 2
check "unknown command is named" grep -q frobnicate "$tmp/e"
printf 't,x,y,z,roll,pitch,yaw\n0.1,0,0,1,0,0,0\n0.2,0,0,1,0,0\n' >"$tmp/short.csv"
"$T" --iface nosuchcan0 --node 1 trajectory "$tmp/short.csv" >/dev/null 2>"$tmp/e"; rc=$?
check "a short row exits 2 before the bus" test $rc -eq 2
check "the short row's line is named" grep -q "short.csv:3:" "$tmp/e"
printf '0.1,0,0,1,0,0,0\n0.2,0,0,,1,0,0\n' >"$tmp/shift.csv"
"$T" --iface nosuchcan0 --node 1 trajectory "$tmp/shift.csv" >/dev/null 2>"$tmp/e"; rc=$?
check "an empty field (columns that would shift) exits 2" test $rc -eq 2
check "the empty field's line is named" grep -q "shift.csv:2:" "$tmp/e"
printf '0.1,0,0,1,0,0,0\n0.2,4.5,0,1,0,0,0\n' >"$tmp/far.csv"
"$T" --iface nosuchcan0 --node 1 trajectory "$tmp/far.csv" >/dev/null 2>"$tmp/e"; rc=$?
check "a pose past the wire's range exits 2 before the bus" test $rc -eq 2
check "the far row's line is named" grep -q "far.csv:2:" "$tmp/e"
printf '0.2,0,0,1,0,0,0\n0.1,0,0,1,0,0,0\n' >"$tmp/back.csv"
"$T" --iface nosuchcan0 --node 1 trajectory "$tmp/back.csv" >/dev/null 2>"$tmp/e"
check "time going back is refused with its line" grep -q "back.csv:2:" "$tmp/e"
printf '0.1,0,0,1,0,zero,0\n' >"$tmp/nan.csv"
"$T" --iface nosuchcan0 --node 1 trajectory "$tmp/nan.csv" >/dev/null 2>"$tmp/e"
check "a non-number is refused with its line" grep -q "nan.csv:1:" "$tmp/e"
"$T" --iface nosuchcan0 --node 1 move 0 0 1 0 0 >/dev/null 2>"$tmp/e"; check "move with five numbers exits 2" test $? -eq 2
"$T" --iface nosuchcan0 --node 1 move 0 0 1 0 0 x >/dev/null 2>"$tmp/e"; rc=$?
check "move with a non-number exits 2" test $rc -eq 2
check "the non-number's axis is named" grep -q "YAW is not a number" "$tmp/e"
"$T" --iface nosuchcan0 --node 1 move 0 0 5 0 0 0 >/dev/null 2>"$tmp/e"; rc=$?
check "move past the wire's range exits 2 naming the unit" grep -q "Z is outside the wire's range -4..4 m" "$tmp/e"
"$T" --iface nosuchcan0 --node 1 move 0 0 1 0 0 0 --duration 1 --speed 0.1 >/dev/null 2>"$tmp/e"; rc=$?
check "move with both --duration and --speed exits 2 before the bus" test $rc -eq 2
check "both timing flags are named" grep -q "give --duration or --speed, not both" "$tmp/e"
"$T" --iface nosuchcan0 --node 1 move 0 0 1 0 0 0 --speed 0.1 --speed 0.2 >/dev/null 2>"$tmp/e"
check "a timing flag given twice exits 2" test $? -eq 2
"$T" --iface nosuchcan0 --node 1 params set slide_vmax 3 >/dev/null 2>"$tmp/e"; rc=$?
check "params set out of range exits 2" test $rc -eq 2
check "the range error prints the unit and the range" grep -q "m/s" "$tmp/e"
"$T" --iface nosuchcan0 --node 1 params set slide_vmax 0.2 >/dev/null 2>"$tmp/e"; rc=$?
check "params set in SI passes the check and reaches the bus (exit 1 here)" test $rc -eq 1
"$T" --iface nosuchcan0 --node 1 params set eta_deg 30 >/dev/null 2>"$tmp/e"; rc=$?
check "an angle in degrees is taken" test $rc -eq 1
"$T" --iface nosuchcan0 --node 1 params set nosuch 1 >/dev/null 2>"$tmp/e"; rc=$?
check "an unknown parameter exits 2 naming it" grep -q "nosuch" "$tmp/e"
"$T" --iface nosuchcan0 --node 1 status >/dev/null 2>"$tmp/e"; rc=$?
check "no such CAN interface exits 1" test $rc -eq 1
check "the interface is named" grep -q nosuchcan0 "$tmp/e"
"$T" params list >"$tmp/e"; check "params list needs no bus" grep -q "steps_per_m" "$tmp/e"
check "params list shows SI units" grep -Eq "^slide_vmax +0.15 +m/s" "$tmp/e"
# path (issue 25): the waypoint file is read before the bus, as a trajectory file is.
"$T" help path >"$tmp/e" 2>&1; rc=$?
check "path help needs no bus (exit 0)" test $rc -eq 0
check "path help says what a waypoint file is and what --dry-run does" grep -q -- "--dry-run prints" "$tmp/e"
printf 'x,y,z,roll,pitch,yaw\n0,0,1,0,0,0\n0,0,abc,0,0,0\n' >"$tmp/wp.csv"
"$T" --iface nosuchcan0 --node 1 path "$tmp/wp.csv" >/dev/null 2>"$tmp/e"; rc=$?
check "a bad waypoint row exits 2 before the bus" test $rc -eq 2
check "the bad waypoint's line and column are named" grep -q "wp.csv:3: column 3 (z)" "$tmp/e"
printf '0,0,1,0,0,0\n0,0,1.1,0,0,0\n' >"$tmp/wp.csv"
"$T" --iface nosuchcan0 --node 1 path "$tmp/wp.csv" --blend 2 >/dev/null 2>"$tmp/e"; rc=$?
check "path --blend 2 exits 2 naming the range" test $rc -eq 2
check "the blend's range is said" grep -q "0 to 1 m" "$tmp/e"
"$T" --iface nosuchcan0 --node 1 path "$tmp/wp.csv" --frob >/dev/null 2>"$tmp/e"; rc=$?
check "path with an unknown option exits 2 naming it" grep -q -- "--frob" "$tmp/e"
"$T" --iface nosuchcan0 --node 1 path "$tmp/wp.csv" --dry-run >/dev/null 2>"$tmp/e"; rc=$?
check "a good waypoint file reaches the bus (exit 1 here)" test $rc -eq 1
"$T" --iface nosuchcan0 --node 1 path "$tmp/wp.csv" --plot >/dev/null 2>"$tmp/e"; rc=$?
check "path --plot without a file exits 2 naming it" grep -q -- "--plot needs a FILE.png" "$tmp/e"
if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
  "$T" --iface nosuchcan0 --node 1 path "$tmp/wp.csv" --plot "$tmp/p.png" >/dev/null 2>"$tmp/e"; rc=$?
  check "path --plot with matplotlib here reaches the bus (exit 1 here)" test $rc -eq 1
fi
# info (issue 27 pt 4): the version and the rates; --version needs nothing.
"$T" --version >"$tmp/e" 2>&1; rc=$?
check "--version exits 0 with tsectl's version" test $rc -eq 0 -a "$(cat "$tmp/e")" = "tsectl $TSE_VERSION"
"$T" help info >"$tmp/e" 2>&1; rc=$?
check "info help needs no bus (exit 0)" test $rc -eq 0
check "info help says what a firmware older than INFO gets" grep -q "the others judge at the built-in rates" "$tmp/e"
"$T" --iface nosuchcan0 --node 1 info --yaml >/dev/null 2>"$tmp/e"; rc=$?
check "info with an unknown option exits 2 naming it" test $rc -eq 2
check "the unknown option is named" grep -q -- "--yaml" "$tmp/e"
"$T" --iface nosuchcan0 --node 1 info --json >/dev/null 2>"$tmp/e"; rc=$?
check "info --json reaches the bus (exit 1 here)" test $rc -eq 1
# node set and scan (issue 26 pt 4): an id outside 1..15 refused before the bus, naming the range;
# scan needs no --node; node set does.
for bad in 0 16 5x -3 ""; do
  "$T" --iface nosuchcan0 --node 1 node set "$bad" >/dev/null 2>"$tmp/e"; rc=$?
  check "node set '$bad' exits 2" test $rc -eq 2
  check "node set '$bad' names the range" grep -q "is not a node id: a whole number 1..15 (nothing sent)" "$tmp/e"
done
"$T" --iface nosuchcan0 --node 1 node set >/dev/null 2>"$tmp/e"; rc=$?
check "node set without an id exits 2" test $rc -eq 2
"$T" --iface nosuchcan0 node set 5 >/dev/null 2>"$tmp/e"; rc=$?
check "node set without --node exits 2 naming it" test $rc -eq 2 -a -n "$(grep -- '--node N is needed' "$tmp/e")"
"$T" --iface nosuchcan0 --node 1 node set 5 >/dev/null 2>"$tmp/e"; rc=$?
check "node set 5 reaches the bus (exit 1 here)" test $rc -eq 1
"$T" --iface nosuchcan0 scan >/dev/null 2>"$tmp/e"; rc=$?
check "scan needs no --node and reaches the bus (exit 1 here)" test $rc -eq 1
"$T" --iface nosuchcan0 scan now >/dev/null 2>"$tmp/e"; rc=$?
check "scan with an argument exits 2" test $rc -eq 2
"$T" help scan >"$tmp/e" 2>&1
check "scan help says it needs no --node" grep -q "Needs no --node" "$tmp/e"
check_done
