# Streaming as README lays a file out (the first row at the current pose, rows 20 ms apart, no hold
# row): ten runs in a row from tsectl and ten from tse.can, each to its last row with no underrun;
# a file tsectl refuses is refused by tse.can naming the same row, with nothing sent.  Prints the
# rows per second each run reached.  Run by the harness with --python (tse.can), the files
# stream_files.py and stream_client.py, and libtse_kin.so (tse.can's check) as data files.
pass=0
fail=0
check() { if eval "$2"; then pass=$((pass + 1)); echo "ok: $1"; else fail=$((fail + 1)); echo "FAIL: $1"; fi; }
T="tsectl --iface vcan0 --node 1 --timeout $(awk -v s="${TSE_VM_SLOW:-1}" 'BEGIN { printf "%d", 10000 * s }')" # x the VM's slowness (harness)
export TSE_KIN_LIB=$PWD/libtse_kin.so

# Here the host and the controller share one emulated CPU, which the simulator's 200,000 step ticks a
# second fill: it runs behind real time, and makes its late periods up back to back, faster than
# real time, whenever it gets the CPU; on the bench the controller has a CPU of its own and keeps
# time.  So the simulator runs at a lower priority (nice 10; busybox has no nice, python3 does),
# taking the CPU the host leaves, and reports STATUS every 20 ms instead of 100, so that a host
# whose queue is full learns of room as fast as a catching-up simulator makes it.  The watchdog at
# 5 s: a loaded machine can stall the whole VM for longer than the default 500 ms, which the
# simulator, its clock the host's, would take for a silent host (e2e and tests_sim check the
# watchdog).  Streaming itself runs on the defaults: traj_lead 0.2 s, a queue of 32 rows.
printf 'watchdog_ms = 5000\nstatus_ms = 20\n' >params.txt
python3 -c 'import os, sys; os.nice(10); os.execvp(sys.argv[1], sys.argv[1:])' \
  tse-sim --iface vcan0 --node 1 --params params.txt >sim.log 2>&1 &
sim=$!
i=0
while [ $i -lt 120 ] && ! grep -q 'tse-sim: node' sim.log; do sleep 0.5; i=$((i + 1)); done
tsectl --iface vcan0 --node 1 heartbeat &
hb=$!
$T enable >/dev/null 2>&1 && $T home --wait >out.txt 2>&1
check "homed" "[ $? -eq 0 ]"
# The simulator says where it came to rest as it sees the plate stop, which may be after tsectl saw
# STATUS say idle (its own thread, at nice 10 on a busy machine): wait for the line.
i=0
while [ $i -lt 40 ] && ! grep -q 'at rest: plate' sim.log; do sleep 0.25; i=$((i + 1)); done
rest=$(grep 'at rest: plate' sim.log | tail -1 | awk '{ print $5, $6, $7, $9, $10, $11 }')
python3 stream_files.py $rest
check "the files are laid out from the rest pose ($rest)" "[ -s circle.csv ] && [ -s fast.csv ]"

runs=0
rates=""
fills=""
for i in 1 2 3 4 5 6 7 8 9 10; do
  $T trajectory circle.csv >out.txt 2>&1
  rc=$?
  rate=$(sed -n 's/.*(\([0-9]*\) rows\/s;.*/\1/p' out.txt)
  fill=$(sed -n 's/.*filled after [0-9]* rows at \([0-9]*\) rows\/s.*/\1/p' out.txt)
  rates="$rates $rate"
  fills="$fills ${fill:--}"
  if [ $rc -eq 0 ]; then runs=$((runs + 1)); else sed 's/^/  | /' out.txt; fi
done
check "tsectl: ten runs in a row of a 20 ms file with no hold row, each to its last row" "[ $runs -eq 10 ]"
echo "figure: tsectl streaming a 20 ms file (50 rows/s needed), rows/s per run:$rates"
echo "figure: tsectl's own pace, rows/s until the controller's queue filled, per run:$fills"
check "no underrun in tsectl's runs" "! grep -q 'fault underrun' sim.log"

python3 stream_client.py run 10 circle.csv >py.txt 2>&1
rc=$?
sed 's/^/  | /' py.txt
check "tse.can: ten runs in a row of the same file, each to its last row" "[ $rc -eq 0 ] && [ \$(grep -c 'rows streamed' py.txt) -eq 10 ]"
echo "figure: tse.can streaming a 20 ms file, rows/s per run: $(sed -n 's/.*(\([0-9]*\) rows\/s.*/\1/p' py.txt | tr '\n' ' ')"
echo "figure: tse.can's own pace, rows/s until the queue filled, per run: $(sed -n 's/.*, \([0-9]*\) rows\/s until.*/\1/p' py.txt | tr '\n' ' ')"
check "no underrun in tse.can's runs" "! grep -q 'fault underrun' sim.log"

before=$(grep -c 'motion accepted' sim.log)
$T trajectory fast.csv >out.txt 2>&1
rc=$?
sed 's/^/  | /' out.txt
row=$(sed -n 's/.*fast\.csv:[0-9]*: row \([0-9]*\) .*would be refused.*/\1/p' out.txt)
check "tsectl refuses the fast file before sending (exit 3), naming the row" "[ $rc -eq 3 ] && [ -n \"$row\" ]"
python3 stream_client.py refuse fast.csv >py.txt 2>&1
rc=$?
sed 's/^/  | /' py.txt
check "tse.can refuses the same row (tsectl counts from 1, Python from 0), with nothing sent" \
  "[ $rc -eq 0 ] && grep -q \"refused row \$((row - 1)) (0-based): row \$((row - 1)) .*would be refused; nothing was sent: rejected: timing\" py.txt && [ \$(grep -c 'motion accepted' sim.log) -eq $before ]"

kill $hb
kill -INT $sim
sleep 0.5
[ "$fail" -eq 0 ] || { echo "the simulator's states:"; grep -E 'state|accepted' sim.log | tail -40 | sed 's/^/  | /'; }
echo "figure: $(tail -1 sim.log)"
grep -E 'plant:|breach' sim.log
check "the plant saw no breach" "! grep -q 'plant:' sim.log"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
