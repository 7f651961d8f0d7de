# tse.can as a user scripts it: a controller on the bus (tse-sim, or the board the harness gives,
# target.sh), the pytest suite of the client (python/tests_sim) and the example that records
# telemetry (python/examples/move_and_plot.py).
# Run by python_can_test.sh through the harness with --python (Debian's python3, python-can and
# pytest, and our python/ tree on PYTHONPATH).  Prints the telemetry CSV between markers for the
# host to plot.
pass=0
fail=0
check() { if eval "$2"; then pass=$((pass + 1)); echo "ok: $1"; else fail=$((fail + 1)); echo "FAIL: $1"; fi; }

. ./target.sh
export TSE_KIN_LIB=$PWD/libtse_kin.so # tse.can's trajectory check (a data file)
# In the VM the host (Python under TCG) and tse-sim share one emulated CPU, which the simulator's
# 200,000 step ticks a second fill; a loaded machine stalls the whole VM for longer than the
# default 500 ms watchdog, and the Python host behind a simulator that makes late periods up back
# to back falls behind a stream.  As in stream.sh: tse-sim at nice 10 (busybox has no nice,
# python3 does), STATUS every 20 ms, the watchdog at 5 s (test_client checks it at 400 ms).  On the
# bench the controller has a CPU of its own.  The board has its own CPU (the emulator, on the
# host) and keeps its defaults.
printf 'import os, sys\nos.nice(10)\nos.execvp(sys.argv[1], sys.argv[1:])\n' >nice10.py
printf 'watchdog_ms = 5000\nstatus_ms = 20\n' >sim_params.txt
SIM_WRAP="python3 nice10.py" controller_start --params sim_params.txt
root=$(python3 -c 'import os, tse; print(os.path.dirname(os.path.dirname(tse.__file__)))')
check "python3 imports tse from the package tree" "[ -d \"$root/tests_sim\" ]"

# README's session first, on the robot as a newcomer finds it (powered up, not homed).  On the
# board only the client's suite runs: the session and the example (below) exercise the same client
# calls, and the emulated board runs slower than real time (docs/emulator.md).
if [ "$TSE_TARGET" != board ]; then
  python3 readme_session.py >readme.out 2>&1
  rc=$?
  cat readme.out
  check "README's five-line session moves the robot" \
    "[ $rc -eq 0 ] && [ \$(grep -c . readme_session.py) -eq 5 ] && at_pose 0.1 -0.05 1.1 0.1 -0.05 0.2"
fi

TSE_SIM_LOG=$PWD/sim.log python3 -m pytest -p no:cacheprovider -v -s --durations=5 "$root/tests_sim" >pytest.out 2>&1
rc=$?
cat pytest.out
check "pytest: tse.can against the controller ($TSE_TARGET)" "[ $rc -eq 0 ]"
[ $rc -eq 0 ] || [ "$TSE_TARGET" = board ] ||
  { echo "the simulator's states:"; grep -E 'state|accepted|late' sim.log | tail -40 | sed 's/^/  | /'; }

if [ "$TSE_TARGET" != board ]; then
  python3 "$root/examples/move_and_plot.py" --channel vcan0 --node 1 --csv telemetry.csv >example.out 2>&1
  rc=$?
  cat example.out
  check "the example moved the robot and recorded its telemetry" "[ $rc -eq 0 ] && [ \$(wc -l <telemetry.csv) -gt 20 ]"
  echo "=== telemetry begin"
  cat telemetry.csv 2>/dev/null
  echo "=== telemetry end"
fi

controller_stop
if [ "$TSE_TARGET" = board ]; then
  tse-rig log >log.txt 2>&1
  check "the drivers saw no STEP pulse too short and no step too soon after a DIR change" "! grep -q . log.txt"
else
  grep -E 'plant:|breach' sim.log
  check "the plant saw no breach" "! grep -q 'breaches 0x[1-9a-f]' sim.log"
fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
