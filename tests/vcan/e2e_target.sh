# The end-to-end scenario against either controller (tests/vcan/target.sh): tse-sim, or the
# production image on the emulated board, driven the same way by tsectl on vcan0: enable, home on
# the switches, moves checked against the slides where they physically are (the rig's step counts
# on the board) to within a step and a half of the pose's inverse kinematics, a trajectory, a STOP
# mid-move, an e-stop (on the board through its input, the rig's e-stop chain), clear, home again.
pass=0
fail=0
check() { if eval "$2"; then pass=$((pass + 1)); echo "ok: $1"; else fail=$((fail + 1)); echo "FAIL: $1"; fi; }
. ./target.sh
echo "target: $TSE_TARGET"

controller_start
$T status >out.txt 2>&1
sed -n 's/^/  | /;1p' out.txt
check "the controller is up: disabled, no fault" "grep -q 'state disabled, fault none' out.txt"
$T heartbeat &
hb=$!

$T enable >/dev/null 2>&1 && $T home --wait >out.txt 2>&1; rc=$?
sed -n 's/^/  | /;$p' out.txt
$T status >out.txt 2>&1
check "homing ends at rest, homed" "[ $rc -eq 0 ] && grep -q 'state idle, fault none, homed' out.txt"
cmd=$(sed -n 's/^slides //;s/ m$//p' out.txt)
check "homed at the home pose: six equal slides, where the controller counts them" \
  "echo $cmd | awk '{ for (k = 2; k <= 6; ++k) if (\$k != \$1) exit 1 }' && slides_near \"\$(slides_now)\" \"$cmd\" 1"

P1="0.1 -0.05 1.1 0.1 -0.05 0.2"
$T move $P1 --duration 1 --wait >out.txt 2>&1; rc=$?
sed -n 's/^/  | /;1p' out.txt
check "move to $P1" "[ $rc -eq 0 ] && at_pose $P1"
P2="-0.05 0.04 1.25 -0.03 0.04 -0.15"
$T move $P2 --speed 0.1 --wait >out.txt 2>&1; rc=$?
check "move to $P2 at 0.1 m/s" "[ $rc -eq 0 ] && at_pose $P2"

# A trajectory: 2 cm along X and Y in 1.5 s with minimum-jerk easing, 30 ms rows.
awk 'BEGIN { print "t,x,y,z,roll,pitch,yaw"; print "0.5,-0.05,0.04,1.25,-0.03,0.04,-0.15"; n = 50;
      for (i = 1; i <= n; ++i) { s = i / n; e = s*s*s*(10 - 15*s + 6*s*s);
      printf "%.3f,%.6f,%.6f,1.25,-0.03,0.04,-0.15\n", 0.5 + 0.03 * i, -0.05 + 0.02 * e, 0.04 + 0.02 * e } }' >traj.csv
$T trajectory traj.csv >out.txt 2>&1; rc=$?
tail -1 out.txt | sed 's/^/  | /'
check "trajectory streamed and ended on its last row" "[ $rc -eq 0 ] && at_pose -0.03 0.06 1.25 -0.03 0.04 -0.15"

# A STOP mid-move: at rest short of the target, and the slides where the controller says.
$T move 0 0 1.0 0 0 0 --duration 4 >/dev/null 2>&1
sleep 1
$T stop --wait >out.txt 2>&1; rc=$?
$T status >status.txt 2>&1
cmd=$(sed -n 's/^slides //;s/ m$//p' status.txt)
check "STOP mid-move: at rest (idle), short of the target" \
  "[ $rc -eq 0 ] && grep -q 'state idle' status.txt && ! at_pose 0 0 1.0 0 0 0 2>/dev/null"
check "after the STOP the slides are where the controller counts them" "slides_near \"\$(slides_now)\" \"$cmd\" 1"

# E-stop during a move: the board through its input (the rig opens the chain), tse-sim by command.
$T move 0 0 1.2 0 0 0 --duration 3 >/dev/null 2>&1
sleep 1
if [ "$TSE_TARGET" = board ]; then tse-rig estop open; else $T estop >/dev/null 2>&1; fi
sleep 1
$T status >out.txt 2>&1
s1=$(slides_now)
sleep 1
s2=$(slides_now)
sed -n 's/^/  | /;1p' out.txt
check "e-stop: state estop, drives off" "grep -q 'state estop, fault estop.*drives off' out.txt"
check "no slide moves after the e-stop" "[ \"$s1\" = \"$s2\" ]"
if [ "$TSE_TARGET" = board ]; then
  $T clear >out.txt 2>&1; rc=$?
  check "clear is refused while the e-stop chain is open" "[ $rc -eq 3 ]"
  tse-rig estop closed
fi
$T clear >/dev/null 2>&1 && $T enable >/dev/null 2>&1 && $T home --wait >out.txt 2>&1; rc=$?
$T status >out.txt 2>&1
check "clear, enable, home again: homed" "[ $rc -eq 0 ] && grep -q 'state idle, fault none, homed' out.txt"
$T move $P1 --duration 1 --wait >/dev/null 2>&1; rc=$?
check "and moves again: $P1" "[ $rc -eq 0 ] && at_pose $P1"

if [ "$TSE_TARGET" = board ]; then
  tse-rig log >log.txt 2>&1
  sed 's/^/  | /' log.txt | head -5
  check "the drivers saw no STEP pulse too short and no step too soon after a DIR change" "! grep -q . log.txt"
fi
kill $hb
controller_stop
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
