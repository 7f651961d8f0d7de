# The simulator on the bus, driven with can-utils: it answers, reports its state, refuses a
# malformed frame, and latches the watchdog when the host falls silent.
pass=0
fail=0
check() { if eval "$2"; then pass=$((pass + 1)); echo "ok: $1"; else fail=$((fail + 1)); echo "FAIL: $1"; fi; }

candump -t d vcan0 >dump.log &
dump=$!
tse-sim --iface vcan0 --node 1 >sim.log 2>&1 &
sim=$!
sleep 1
cansend vcan0 061#01          # ENABLE, seq 1
sleep 0.2
cansend vcan0 061#0203        # ENABLE with two bytes: malformed
sleep 1.0                     # no heartbeat: the 500 ms watchdog must trip
kill -INT $sim
sleep 0.5
kill $dump

check "STATUS frames from node 1" "grep -q ' 201 ' dump.log"
check "ENABLE acknowledged (ACK of function 0x06, seq 1)" "grep -q ' 041 .*06 01' dump.log"
check "malformed ENABLE rejected as bad_length (REJECT 0x06, reason 1)" "grep -q ' 031 .*06 00 01' dump.log"
check "state idle after ENABLE" "grep -q 'state idle' sim.log"
check "watchdog latched after host silence" "grep -q 'fault watchdog' sim.log"
check "simulator stopped cleanly on SIGINT" "grep -q 'tse-sim: stopped' sim.log"
echo "--- sim log"
cat sim.log
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
