"""Where the robot physically is, for the client's suite against either controller the vcan
harness gives it (TSE_TARGET): tse-sim, whose plant logs its pose at rest (its own forward
kinematics of the slides it was stepped to) in $TSE_SIM_LOG; or the production image on the
emulated board, whose rig counts the STEP edges (tse-rig, docs/emulator.md), the pose being
tse-kin's forward kinematics of those slides."""
import os
import re
import subprocess
import time

TARGET = os.environ.get("TSE_TARGET", "sim")
BOARD = TARGET == "board"
SIM_LOG = os.environ.get("TSE_SIM_LOG", "sim.log")


def sim_log():
    with open(SIM_LOG) as f:
        return f.read()


def _rig(request):
    return subprocess.run(["tse-rig", *request.split()], capture_output=True, text=True, check=True).stdout


def slides():
    """The six slides where they are (board: the rig's count; sim: the plant's at its last rest)."""
    if BOARD:
        return [float(v) for v in _rig("slides").split()[1:]]
    raise NotImplementedError("tse-sim's plant logs poses, not slides")


def pose_at_rest():
    """The plate pose at rest: the plant's latest 'at rest' line (sim), or the forward kinematics
    of the rig's slides (board)."""
    if BOARD:
        out = subprocess.run(["tse-kin", "fk"], input=",".join(f"{s:.9f}" for s in slides()) + "\n",
                             capture_output=True, text=True, check=True).stdout.strip().split(",")
        assert out[0] == "ok", f"no pose for the rig's slides: {out}"
        return [float(v) for v in out[2:8]]
    # tse-sim logs the rest in the control tick that sends the STATUS saying idle, just after it:
    # a client that has that STATUS may read the log first (a loaded machine preempts tse-sim
    # between the two).  So the rest after the latest motion is awaited, a bounded time: a motion
    # that ended otherwise (an e-stop, a fault) logs none, and the latest rest is what there is.
    deadline = time.monotonic() + 2.0 * float(os.environ.get("TSE_VM_SLOW", "1"))
    while True:
        log = sim_log()
        if log.rfind("at rest: plate") > log.rfind("motion accepted") or time.monotonic() > deadline:
            break
        time.sleep(0.02)
    rest = re.findall(r"at rest: plate (\S+) (\S+) (\S+) m, (\S+) (\S+) (\S+) rad", log)
    assert rest, "the simulator reported no rest"
    return [float(v) for v in rest[-1]]


def mark():
    """Something that changes when the robot moves: the motions the simulator accepted, or the
    rig's step counts."""
    return _rig("steps") if BOARD else sim_log().count("motion accepted")


def motions_since(m):
    """Motions since mark m: counted on tse-sim; on the board, 1 when the slides moved at all
    (the rig sees steps, not motions), else 0."""
    if BOARD:
        return int(_rig("steps") != m)
    return sim_log().count("motion accepted") - m


def controller_clock():
    """The controller's own time in s: real time on tse-sim; on the board, the emulator's virtual
    time (the rig's clock), which never runs ahead of real time."""
    if BOARD:
        return int(_rig("time").split()[1]) / 1e9
    return time.monotonic()


def controller_sleep(seconds):
    """Lets `seconds` of the controller's own time pass: real time on tse-sim; on the board, the
    emulator's virtual time (the rig's clock), which runs slower than real time."""
    if not BOARD:
        time.sleep(seconds)
        return
    start = controller_clock()
    while controller_clock() - start < seconds:
        time.sleep(0.05)
