# The demo, run on the bus by scripts/demo.sh: the simulated controller driven by tsectl through
# homing, a few moves and a streamed trajectory, with progress shown.
T="tsectl --iface vcan0 --node 1 --timeout 5000"
tse-sim --iface vcan0 --node 1 >sim.log 2>&1 &
sim=$!
sleep 0.5
tsectl --iface vcan0 --node 1 heartbeat &
hb=$!
echo "--- the controller at power-up"
$T status
echo "--- enable and home (each slide finds its switch, then all go to the home pose)"
$T enable && $T home --wait
for target in "0.10 -0.05 1.10 0.10 -0.05 0.20" "-0.15 0.10 0.70 -0.05 0.08 -0.30" "0.00 0.00 1.40 0.00 0.00 0.00"; do
  echo "--- move to $target (m, rad)"
  $T move $target --duration 1.5 --wait
  grep 'at rest: plate' sim.log | tail -1 | sed 's/tse-sim: at rest:/the simulator measures the/'
done
echo "--- a pose outside the workspace is refused, with its reason"
$T move 0.8 0 1.0 0 0 0
echo "--- a trajectory streamed with flow control (3 cm by 2 cm in 3 s, rows 20 ms apart from where the plate is)"
awk 'BEGIN { print "t,x,y,z,roll,pitch,yaw"; n = 150; for (i = 0; i < n; ++i) { s = i / (n - 1); e = s*s*s*(10 - 15*s + 6*s*s);
      printf "%.3f,%.6f,%.6f,1.40,0,0,0\n", 0.02 * (i + 1), 0.03 * e, 0.02 * e } }' >traj.csv
$T trajectory traj.csv
echo "--- live telemetry"
$T watch --count 2
$T status
kill $hb
kill -INT $sim
sleep 0.5
echo "--- the simulator's log"
cat sim.log
