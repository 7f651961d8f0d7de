# What a scenario needs to run against either controller the harness gives it (TSE_TARGET): a
# tse-sim it starts itself (sim), or the production image on the emulated board (board), which
# the harness has already put on vcan0 and whose rig tse-rig reads.  Sourced by the scenarios
# (busy box sh); they call check() as they like.
#
# Times: the emulated board runs slower than real time (docs/emulator.md: a fifth of it, less on
# a loaded machine), so waits for the controller are in the controller's own time where they
# can be (tsectl's waits follow its STATUS), and in real seconds with generous margins otherwise.
NODE=${NODE:-1}
# A wait for an answer: what the controller needs (ms, on the reference machine) times how much
# slower the VM runs now (TSE_VM_SLOW, the harness's measure; 1 on vcan0 directly).
answer_ms() { awk -v ms="$1" -v s="${TSE_VM_SLOW:-1}" 'BEGIN { printf "%d", ms * s }'; }
T="tsectl --iface vcan0 --node $NODE --timeout $(answer_ms 20000)"

# controller_start [tse-sim arguments]: the controller is on the bus and has sent a STATUS.
# SIM_WRAP (words): a command tse-sim runs under (python_can.sh: at a lower priority).
controller_start() {
  if [ "$TSE_TARGET" = board ]; then
    $T status >/dev/null 2>&1
  else
    ${SIM_WRAP:-} tse-sim --iface vcan0 --node "$NODE" "$@" >sim.log 2>&1 &
    sim_pid=$!
    sleep 0.5
    $T status >/dev/null 2>&1
  fi
}

controller_stop() {
  [ -z "${sim_pid:-}" ] || { kill -INT "$sim_pid"; wait "$sim_pid"; sim_pid=; }
}

# The six slides where they physically are (board: the rig's step counts; sim: the commanded
# slides, which the plant follows step for step), metres, on one line.
slides_now() {
  if [ "$TSE_TARGET" = board ]; then
    tse-rig slides | sed -n 's/^slides //p'
  else
    commanded_slides
  fi
}

# The slides the controller reports it commanded (its telemetry, to the nanometre), metres.
commanded_slides() {
  $T status --json | sed -n 's/.*"slides": \[\([^]]*\)\].*/\1/p' | tr -d ,
}

# The slides of pose X Y Z ROLL PITCH YAW (m, rad) by tse-kin's inverse kinematics, or nothing.
ik_slides() {
  echo "$1,$2,$3,$4,$5,$6" | tse-kin ik | awk -F, '$1 == "ok" { print $3, $4, $5, $6, $7, $8 }'
}

# slides_near "Q1..Q6" "R1..R6" STEPS: every slide within STEPS steps (1/1,280,000 m each) of the
# other; prints the largest difference in steps on stderr.
slides_near() {
  echo "$1 $2" | awk -v n="$3" '{ w = 0; for (k = 1; k <= 6; ++k) { d = $k - $(k + 6); if (d < 0) d = -d;
      if (d > w) w = d } printf "  slides within %.2f steps\n", w * 1280000 > "/dev/stderr"; exit !(NF == 12 && w * 1280000 <= n) }'
}

# at_pose X Y Z ROLL PITCH YAW: the slides are those of the pose, within 1.5 steps (a step of the
# commanded slides' rounding, and the homing edge's step on the board).
at_pose() {
  slides_near "$(slides_now)" "$(ik_slides "$@")" 1.5
}

# ctl COMMAND...: runs tsectl COMMAND (output in out.txt), returns its status, and writes a line
# to transcript.txt: the command, its exit status and, for a refusal, the controller's reason (for
# kinematics with the scissor and its status).  The transcripts of one scenario on tse-sim and on
# the board must be the same (the differential test).
ctl() {
  $T "$@" >out.txt 2>&1
  local rc=$?
  local why
  why=$(grep -o 'rejected: [a-z_]*' out.txt | head -1)
  [ -z "$why" ] || why="$why$(grep -o ': scissor [0-9] is [a-z]*' out.txt | head -1)"
  echo "$* -> $rc${why:+, $why}" >>transcript.txt
  return $rc
}

# The commanded slides in whole steps (1,280,000 a metre), as the controller reports them.
steps_now() {
  commanded_slides |
    awk '{ for (k = 1; k <= 6; ++k) printf("%s%d", (k > 1 ? " " : ""), ($k < 0 ? -1 : 1) * int(($k < 0 ? -$k : $k) * 1280000 + 0.5)); print "" }'
}
