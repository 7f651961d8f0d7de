#!/usr/bin/env bash
# tse-sim's parameter file, without a bus: a bad file stops it before it starts (exit 2, naming
# the file and line) and is left byte for byte as it was; --write-params writes a template that
# tse-sim then takes, and never overwrites a file.  (No CAN here: a good file gets tse-sim as far
# as opening the interface, which then fails with exit 1.)
set -u
T=$1
TSE_VERSION=$2
. "$(dirname "$0")/../support/check.sh"

"$T" --help 2>"$tmp/usage"; check "--help exits 0" test $? -eq 0
check "usage names --params" grep -q -- "--params FILE" "$tmp/usage"
check "usage names --write-params" grep -q -- "--write-params FILE" "$tmp/usage"

printf '# mine\nslide_vmax = 0.2\n\nslide_amax = 3 # m/s^2\nwatchdog_ms = soon\n' >"$tmp/bad.params"
cp "$tmp/bad.params" "$tmp/bad.orig"
"$T" --iface nosuchcan0 --node 1 --params "$tmp/bad.params" >"$tmp/out" 2>"$tmp/err"; rc=$?
check "a bad value exits 2" test $rc -eq 2
check "the bad value's file and line are named" grep -q "bad.params:5: watchdog_ms: 'soon' is not one finite number (in ms)" "$tmp/err"
check "the bad file is unchanged" cmp -s "$tmp/bad.params" "$tmp/bad.orig"
check "no temporary is left" test ! -e "$tmp/bad.params.tmp"

printf 'alpha_min_deg = 80\nalpha_max_deg = 70\n' >"$tmp/set.params"
cp "$tmp/set.params" "$tmp/set.orig"
"$T" --iface nosuchcan0 --node 1 --params "$tmp/set.params" >"$tmp/out" 2>"$tmp/err"; rc=$?
check "a refused set exits 2" test $rc -eq 2
check "the refused set names its line and rule" grep -q "set.params:2: alpha_min = 1.396263 rad must be below alpha_max = 1.22173 rad" "$tmp/err"
check "the refused set's file is unchanged" cmp -s "$tmp/set.params" "$tmp/set.orig"

# In range, but a 6 us STEP pulse does not fit the simulator's 5 us step interrupts.
printf 'step_pulse_ns = 6000\n' >"$tmp/pulse.params"
cp "$tmp/pulse.params" "$tmp/pulse.orig"
"$T" --iface nosuchcan0 --node 1 --params "$tmp/pulse.params" >"$tmp/out" 2>"$tmp/err"; rc=$?
check "a set the controller cannot adopt exits 2" test $rc -eq 2
check "it names the line and the rule, with the figures" grep -q "pulse.params:1: step_pulse_ns = 6000 ns does not end within one step interrupt period, 5000 ns at 200 kHz" "$tmp/err"
check "that file is unchanged" cmp -s "$tmp/pulse.params" "$tmp/pulse.orig"

printf 'PEST\x22\x00\x01\x02' >"$tmp/binary.params"
cp "$tmp/binary.params" "$tmp/binary.orig"
"$T" --iface nosuchcan0 --node 1 --params "$tmp/binary.params" >"$tmp/out" 2>"$tmp/err"; rc=$?
check "an old binary record exits 2" test $rc -eq 2
check "the binary file is called what it is" grep -q "binary.params: contains a NUL byte" "$tmp/err"
check "the binary file is unchanged" cmp -s "$tmp/binary.params" "$tmp/binary.orig"

"$T" --write-params "$tmp/t.params" >"$tmp/out" 2>"$tmp/err"; rc=$?
check "--write-params exits 0" test $rc -eq 0
check "the template holds every parameter in SI" grep -qx "slide_vmax = 0.15" "$tmp/t.params"
check "the template says units and ranges" grep -qx "# in m/s, 0.001..2, default 0.15" "$tmp/t.params"
cp "$tmp/t.params" "$tmp/t.orig"
"$T" --write-params "$tmp/t.params" >"$tmp/out" 2>"$tmp/err"; rc=$?
check "--write-params over an existing file exits 2" test $rc -eq 2
check "it says why" grep -q "t.params exists: not overwritten" "$tmp/err"
check "the existing file is unchanged" cmp -s "$tmp/t.params" "$tmp/t.orig"

"$T" --iface nosuchcan0 --node 1 --params "$tmp/t.params" >"$tmp/out" 2>"$tmp/err"; rc=$?
check "the template is taken (then no CAN: exit 1)" test $rc -eq 1
check "it got as far as the interface" grep -q "cannot open CAN interface nosuchcan0" "$tmp/err"
"$T" --iface nosuchcan0 --node 1 --params "$tmp/missing.params" >"$tmp/out" 2>"$tmp/err"; rc=$?
check "a missing file is the defaults (then no CAN: exit 1)" test $rc -eq 1
check "a missing file is not created at start" test ! -e "$tmp/missing.params"

# --start: one number inside the stroke; an empty or partial one is refused (it was read as 0).
for bad in "" "0.1x" "1"; do
  "$T" --iface nosuchcan0 --node 1 --start "$bad" >/dev/null 2>&1; rc=$?
  check "--start '$bad' exits 2" test $rc -eq 2
done

# --step-hz and --segment-hz: rates a controller runs at, or refused before anything starts; a set
# that cannot run at the rates asked is refused as the rates' (the defaults' 2.5 us STEP pulse ends
# within a 400 kHz step interrupt's 2.5 us period only at its very end: refused).
"$T" --version >"$tmp/out" 2>&1; rc=$?
check "--version exits 0 with the project's version" test $rc -eq 0 -a "$(cat "$tmp/out")" = "tse-sim $TSE_VERSION"
"$T" --iface nosuchcan0 --node 1 --step-hz 100000 --segment-hz 2000 >"$tmp/out" 2>"$tmp/err"; rc=$?
check "other rates a controller runs at are taken (then no CAN: exit 1)" test $rc -eq 1
for bad in "--segment-hz 3000" "--step-hz 200500" "--segment-hz 0" "--step-hz -5" "--step-hz 2x" \
           "--step-hz 16777216 --segment-hz 1" "--segment-hz 100000"; do
  # shellcheck disable=SC2086 # the option and its value, word by word
  "$T" --iface nosuchcan0 --node 1 $bad >/dev/null 2>"$tmp/err"; rc=$?
  check "'$bad' exits 2 before anything starts" test $rc -eq 2
  check "'$bad' is said wrong" grep -Eq "no controller runs at|takes whole hertz" "$tmp/err"
done
"$T" --iface nosuchcan0 --node 1 --step-hz 400000 >/dev/null 2>"$tmp/err"; rc=$?
check "the defaults at 400 kHz step interrupts: refused (exit 2), naming the rates" \
  test $rc -eq 2 -a -n "$(grep 'not even its default parameters run at 400000 Hz step interrupts' "$tmp/err")"

# A file is judged at the simulator's rates: a 6 us pulse fits 100 kHz step interrupts' 10 us
# (4 us low before a step one tick later: refused, at most half of 10 us), a 4 us one does (6 us
# low), which at the built-in 200 kHz leaves 1 us low (refused above as 6 us is).
printf 'step_pulse_ns = 4000\n' >"$tmp/slow.params"
"$T" --iface nosuchcan0 --node 1 --params "$tmp/slow.params" >/dev/null 2>"$tmp/err"; rc=$?
check "a 4 us pulse at 200 kHz: refused (exit 2) with the built-in rates' figures" \
  test $rc -eq 2 -a -n "$(grep 'slow.params:1: step_pulse_ns = 4000 ns leaves 1000 ns low' "$tmp/err")"
"$T" --iface nosuchcan0 --node 1 --step-hz 100000 --params "$tmp/slow.params" >/dev/null 2>"$tmp/err"; rc=$?
check "the same file at --step-hz 100000: taken (then no CAN: exit 1)" test $rc -eq 1
"$T" --iface nosuchcan0 --node 1 --step-hz 100000 --params "$tmp/pulse.params" >/dev/null 2>"$tmp/err"; rc=$?
check "a 6 us pulse at --step-hz 100000: refused with that rate's figures" \
  test $rc -eq 2 -a -n "$(grep 'pulse.params:1: step_pulse_ns = 6000 ns leaves 4000 ns low before the same slide.s next step, which may come 10000 ns later (1 step interrupt at 100 kHz' "$tmp/err")"

# The node id (issue 26 pt 4): --node overrides the parameter `node`, which a file may set; without
# either, node 1 (the default).  A node outside 1..15 in the file or on the line is refused.
"$T" --iface nosuchcan0 >"$tmp/out" 2>"$tmp/err"; rc=$?
check "without --node tse-sim starts (then no CAN: exit 1)" test $rc -eq 1
check "... having got as far as the interface" grep -q "cannot open CAN interface nosuchcan0" "$tmp/err"
printf 'node = 16\n' >"$tmp/node16.params"
"$T" --iface nosuchcan0 --params "$tmp/node16.params" >"$tmp/out" 2>"$tmp/err"; rc=$?
check "node = 16 in the file: refused (exit 2), naming the range" \
  test $rc -eq 2 -a -n "$(grep 'node16.params:1: node = 16 is outside 1..15' "$tmp/err")"
printf 'enable_level = 3\n' >"$tmp/level.params"
"$T" --iface nosuchcan0 --params "$tmp/level.params" >"$tmp/out" 2>"$tmp/err"; rc=$?
check "enable_level = 3 in the file: refused (exit 2), naming the range" \
  test $rc -eq 2 -a -n "$(grep 'enable_level = 3 is outside 0..2' "$tmp/err")"
"$T" --iface nosuchcan0 --node 0 >/dev/null 2>"$tmp/err"; rc=$?
check "--node 0 is refused (exit 2)" test $rc -eq 2 -a -n "$(grep -- '--node takes 1..15' "$tmp/err")"

check_done
