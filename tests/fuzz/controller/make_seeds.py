#!/usr/bin/env python3
"""Writes the controller fuzz target's seed corpus in its byte encoding (fuzz_controller.c's header
comment; change both together): well-formed sessions that reach every state and every command -
enable, home, staged poses near the home pose and MOVE_COMMIT (by duration, by speed, blended),
trajectories streamed with TRAJ_COMMIT, PARAM_SET/GET/SAVE and a power cycle, INFO_GET, STOP, ESTOP
(command, input, interrupt inside the controller), CLEAR_FAULT, DISABLE, the watchdog, limit switches,
bus-off, the flash failing - and refusals of every kind.
    make_seeds.py tests/fuzz/controller/corpus
The committed corpus is these seeds and the inputs a fuzzing run added to them that brought new
coverage, merged in: fuzz_controller -merge=1 tests/fuzz/controller/corpus WORK_DIR.
With --check REPLAY (the host build's replay_controller), each seed is replayed alone with
TSE_FUZZ_SUMMARY set, and the states it must reach are checked: a seed that no longer reaches
motion (the encoding or the firmware changed under it) is reported and nothing is written."""
import argparse
import hashlib
import os
import re
import struct
import subprocess
import sys
import tempfile

OPS = ["WAIT_MS", "WAIT_TICKS", "WAIT_LONG", "WAIT_REST", "CMD", "MSG", "POSE", "MOVE", "TRAJ",
       "PARAM", "RAW", "HOST", "ESTOP_IN", "LIMITS", "BUS", "STORAGE", "HOOK", "REBOOT", "PLANT_FAULT"]
OP = {name: i for i, name in enumerate(OPS)}
CMDS = {"ESTOP": 0, "STOP": 1, "ENABLE": 2, "DISABLE": 3, "HOME": 4, "CLEAR_FAULT": 5}
NEXT, SAME, RAW, PREV = 0, 1, 2, 3
HARNESS, FAST, FAST_BOARD, FAST_ON_SWITCH = 0, 1, 2, 3
# Host-to-controller messages in table order (the MSG operation's index).
MSGS = ["ESTOP", "STOP", "HOST_HEARTBEAT", "ENABLE", "DISABLE", "HOME", "CLEAR_FAULT", "POSE_A",
        "POSE_B", "POSE_C", "MOVE_COMMIT", "TRAJ_COMMIT", "PARAM_GET", "PARAM_SET", "PARAM_SAVE", "INFO_GET"]
PARAM = {"L": 0, "s_min": 7, "s_max": 8, "mu_min": 9, "steps_per_m": 11, "slide_vmax": 12,
         "slide_amax": 13, "plate_vmax": 14, "step_rate_max": 19, "watchdog_ms": 20,
         "status_ms": 21, "telemetry_ms": 22, "homing_speed": 23, "homing_backoff": 24,
         "home_sw_1": 25, "step_pulse_ns": 31, "dir_setup_ns": 32, "can_kbps": 33, "traj_lead": 34,
         "node": 35, "enable_level": 36}
# Fake hook points (tests/firmware/fake_hal.h).
AT_CLOCK, AT_RECEIVE, AT_CAN_STATE, AT_ENABLE = 0, 1, 2, 3


class Seed:
    def __init__(self, name, fixture, reaches=()):
        self.name, self.reaches, self.b = name, reaches, bytearray([fixture])

    def op(self, name, *operands):
        self.b.append(OP[name])
        self.b.extend(operands)
        return self

    def seq(self, mode, raw):
        return bytes([raw & 0xFF]) if mode == RAW else b""

    def cmd(self, name, seq=NEXT, raw=0, broadcast=False):
        self.op("CMD", CMDS[name] | (8 if broadcast else 0) | seq << 4)
        self.b.extend(self.seq(seq, raw))
        return self

    def ms(self, n):
        while n > 0:  # WAIT_LONG in 25 ms steps up to 1 s, the rest in WAIT_MS
            if n >= 25:
                k = min(n // 25, 40)
                self.op("WAIT_LONG", k - 1)
                n -= 25 * k
            else:
                k = min(n, 16)
                self.op("WAIT_MS", k - 1)
                n -= k
        return self

    def ticks(self, n):
        return self.op("WAIT_TICKS", n - 1)

    def rest(self, max_ms=3200):
        return self.op("WAIT_REST", max_ms // 100 - 1)

    def pose(self, dx=0, dy=0, dz=0, droll=0, dpitch=0, dyaw=0, parts=7, seq=NEXT, raw=0,
             far=False, reverse=False):
        """Offsets from the home pose in um and urad (4 per count; 512 with far)."""
        unit = 512 if far else 4
        m = (parts & 7) | seq << 3 | (32 if far else 0) | (64 if reverse else 0)
        offs = [round(v / unit) for v in (dx, dy, dz, droll, dpitch, dyaw)]
        self.op("POSE", m, *struct.pack("<6h", *offs))
        self.b.extend(self.seq(seq, raw))
        return self

    def move(self, ms=None, speed=None, seq=SAME, raw=0):
        if speed is not None:
            self.op("MOVE", seq | 4, *struct.pack("<H", (speed - 50000) // 8))
        else:
            self.op("MOVE", seq, *struct.pack("<H", ms - 1))
        self.b.extend(self.seq(seq, raw))
        return self

    def traj(self, dt_us, last=False, seq=SAME, raw=0, first=False, stranger=False):
        self.op("TRAJ", seq | (4 if last else 0) | (8 if first else 0) | (16 if stranger else 0),
                *struct.pack("<H", (dt_us - 1000) // 10))
        self.b.extend(self.seq(seq, raw))
        return self

    def param_set(self, name_or_id, value):
        pid = PARAM.get(name_or_id, name_or_id)
        return self.op("PARAM", pid, 4, *struct.pack("<i", value))

    def param_get(self, pid):
        if pid > 39:
            return self.op("PARAM", 0, 5 | 16, *struct.pack("<Hi", pid, 0))
        return self.op("PARAM", pid, 5, *struct.pack("<i", 0))

    def save(self, magic=None):
        if magic is None:
            return self.op("PARAM", 0, 6, 0, 0, 0, 0)
        return self.op("PARAM", 0, 7, *struct.pack("<I", magic))

    def msg(self, name, fields=b"", node=0, flip=None, seq=None):
        var = node | (4 if flip is not None else 0) | ((8 | seq << 4) if seq is not None else 0)
        self.op("MSG", MSGS.index(name), var)
        self.b.extend(fields)
        if flip is not None:
            self.b.append(flip)
        return self

    def raw(self, ident, data=b"", length=None):
        data = bytes(data)
        self.op("RAW", *struct.pack("<HB", ident, len(data) if length is None else length))
        self.b.extend(data.ljust(8, b"\0"))
        return self

    def host(self, alive=True, beat=False):
        return self.op("HOST", (1 if alive else 0) | (2 if beat else 0))

    def estop_input(self, open_, isr=False):
        return self.op("ESTOP_IN", (1 if open_ else 0) | (2 if isr else 0))

    def limits(self, mask):
        return self.op("LIMITS", *struct.pack("<H", mask))

    def bus(self, kind):
        return self.op("BUS", kind)

    def storage(self, fails):
        return self.op("STORAGE", 1 if fails else 0)

    def hook(self, at, n=1):
        return self.op("HOOK", at + 4 * (n - 1))

    def reboot(self):
        return self.op("REBOOT")

    def plant_fault(self, hardware=False):
        return self.op("PLANT_FAULT", 1 if hardware else 0)

    def home(self):
        return self.cmd("ENABLE").ms(2).cmd("HOME").rest()


def seeds():
    S = []

    def new(name, fixture=FAST, reaches=()):
        s = Seed(name, fixture, reaches)
        S.append(s)
        return s

    motion = ("moving", "idle")
    for fx in (FAST, FAST_BOARD, FAST_ON_SWITCH):
        new(f"home_{fx}", fx, ("homing", "idle")).home().ms(20)
        new(f"move_{fx}", fx, motion).home().pose(dx=2000, dz=-3000).move(ms=300).rest().ms(20)
    new("home_harness", HARNESS, ("homing", "idle")).home().ms(20)
    new("move_harness", HARNESS, motion).home().rest().pose(dx=1000, dz=-1000).move(ms=200).rest()
    new("move_speed", reaches=motion).home().pose(dy=3000, dyaw=20000).move(speed=60000).rest()
    new("move_rotate", reaches=motion).home().pose(droll=30000, dpitch=-20000).move(ms=400).rest()
    new("move_parts_reversed", reaches=motion).home().pose(dx=-3000, reverse=True).move(ms=250).rest()
    (new("blend", reaches=motion).home().pose(dx=3000).move(ms=400).ms(150)
     .pose(dx=3000, dy=3000).move(ms=400).ms(100).pose(dz=2000).move(ms=300).rest())
    (new("blend_board", FAST_BOARD, ("moving",)).home().pose(dx=3000).move(ms=400).ms(150)
     .pose(dx=3000, dy=3000).move(ms=400).rest())
    t = new("trajectory", reaches=motion).home()
    for i in range(1, 9):
        t.pose(dx=500 * i, dz=-300 * i).traj(50000, last=(i == 8), first=(i == 1))
    t.rest()
    # Past traj_lead (0.2 s), so that its clock starts and the queue runs dry.
    t = new("trajectory_underrun", reaches=("moving", "fault")).home()
    for i in range(1, 6):
        t.pose(dx=800 * i).traj(60000, first=(i == 1))
    t.rest()
    # A row of the stopped trajectory is refused `ended`, a stranger's too; a new one starts.
    t = new("trajectory_stop", reaches=("stopping",)).home()
    for i in range(1, 7):
        t.pose(dy=600 * i).traj(80000, first=(i == 1))
    t.ms(120).cmd("STOP").pose(dy=5000).traj(80000).rest().pose(dy=100).traj(80000, stranger=True) \
        .pose(dy=100).traj(80000, last=True, first=True).rest()
    # The rows after a row refused `queue_full` are refused `order`.
    t = new("trajectory_queue_full", reaches=("moving",)).home()
    for i in range(1, 36):
        t.pose(dx=100 * i).traj(40000, first=(i == 1))
    t.cmd("STOP").rest()
    new("traj_during_move", reaches=("moving",)).home().pose(dx=3000).move(ms=400).ms(50) \
        .pose(dx=2000).traj(50000, last=True, first=True).rest().pose(dz=500).traj(50000, first=True) \
        .pose(dz=900).move(ms=100).rest()
    new("stop_move", reaches=("stopping", "idle")).home().pose(dx=5000, dz=-5000).move(ms=800) \
        .ms(200).cmd("STOP").rest()
    new("stop_homing", reaches=("stopping",)).cmd("ENABLE").cmd("HOME").ms(30).cmd("STOP").rest() \
        .cmd("HOME").rest()
    new("estop_move", reaches=("estop", "disabled")).home().pose(dx=4000).move(ms=500).ms(100) \
        .cmd("ESTOP").ms(5).cmd("CLEAR_FAULT").cmd("ENABLE").cmd("HOME").rest()
    new("estop_broadcast", reaches=("estop",)).home().pose(dx=4000).move(ms=500).ms(100) \
        .cmd("ESTOP", broadcast=True).ms(5).cmd("STOP", broadcast=True).cmd("CLEAR_FAULT")
    new("stop_broadcast", reaches=("stopping",)).home().pose(dx=4000).move(ms=500).ms(100) \
        .cmd("STOP", broadcast=True).rest()
    new("estop_input_isr", reaches=("estop",)).home().pose(dx=4000).move(ms=500).ms(100) \
        .ticks(37).estop_input(True, isr=True).ticks(3).ms(3).cmd("CLEAR_FAULT") \
        .estop_input(False).cmd("CLEAR_FAULT").cmd("ENABLE").ms(5)
    new("estop_input_polled", reaches=("estop",)).home().estop_input(True).ms(3) \
        .estop_input(False).cmd("CLEAR_FAULT")
    for at in (AT_CLOCK, AT_RECEIVE, AT_CAN_STATE):
        new(f"estop_hook_{at}", reaches=("estop",)).home().pose(dx=4000).move(ms=500).ms(50) \
            .hook(at, 3).ms(3).estop_input(False).cmd("CLEAR_FAULT")
    new("estop_hook_enable", reaches=("estop",)).hook(AT_ENABLE).cmd("ENABLE").ms(3) \
        .estop_input(False).cmd("CLEAR_FAULT").cmd("ENABLE")
    new("watchdog", reaches=("fault",)).cmd("ENABLE").host(False).ms(600).cmd("CLEAR_FAULT") \
        .host(True).cmd("ENABLE").ms(20)
    new("watchdog_moving", reaches=("stopping", "fault")).home().pose(dx=5000).move(ms=900) \
        .host(False).ms(800).host(True).cmd("CLEAR_FAULT")
    new("watchdog_off", reaches=("idle",)).param_set("watchdog_ms", 0).cmd("ENABLE").host(False) \
        .ms(700).host(True).cmd("DISABLE")
    new("limit_high", reaches=("fault",)).home().pose(dx=4000).move(ms=500).ms(100) \
        .limits(1 << 10).rest().limits(0).cmd("CLEAR_FAULT")
    new("limit_low_homed", reaches=("fault",)).home().limits(1 << 3).ms(5).limits(0) \
        .cmd("CLEAR_FAULT")
    new("limit_during_homing", reaches=("homing",)).cmd("ENABLE").limits(0x3F).cmd("HOME") \
        .ms(100).limits(0).rest()
    new("bus_off", reaches=("fault",)).home().bus(0).ms(3).bus(1).cmd("CLEAR_FAULT") \
        .bus(2).ms(2).bus(3).ms(200)
    new("plant_fault", reaches=("fault",)).home().pose(dx=3000).move(ms=400).ms(50) \
        .plant_fault().rest().cmd("CLEAR_FAULT").plant_fault(hardware=True)
    new("params").param_get(12).param_set("slide_vmax", 100000) \
        .param_get(12).param_set("telemetry_ms", 10).param_set("status_ms", 20).save() \
        .reboot().param_get(12).ms(50)
    new("params_refused").param_set("slide_vmax", 10).param_set(40, 1).param_get(300) \
        .param_set("home_sw_1", 950000).param_set("can_kbps", 300).param_set("step_pulse_ns", 1000000) \
        .save(magic=0x12345678).storage(True).save().storage(False).save()
    new("params_state", reaches=("idle",)).cmd("ENABLE").param_set("slide_vmax", 100000).save() \
        .cmd("DISABLE").param_set("slide_vmax", 100000)
    new("params_rezero", reaches=("homing",)).home().cmd("DISABLE").param_set("steps_per_m", 256000) \
        .param_set("home_sw_1", 300000).cmd("ENABLE").pose(dx=1000).move(ms=100).cmd("HOME").rest() \
        .pose(dx=1000).move(ms=100).rest()
    new("params_margins", reaches=motion).home().cmd("DISABLE").param_set("mu_min", 60000) \
        .cmd("ENABLE").pose(dx=1000).move(ms=100).rest()
    new("step_rate_low", reaches=("homing",)).param_set("step_rate_max", 1000).cmd("ENABLE") \
        .cmd("HOME").rest()
    new("homing_fast", reaches=("homing",)).param_set("homing_speed", 500000).cmd("ENABLE") \
        .cmd("HOME").rest()
    new("staging", reaches=motion).home().pose(dx=1000, parts=3).move(ms=100) \
        .pose(dx=1000, parts=4, seq=SAME).pose(dx=2000, parts=7, seq=PREV).move(ms=100, seq=PREV) \
        .move(ms=100).rest().move(ms=100).pose(dx=500).move(ms=100, seq=RAW, raw=0).rest()
    new("unreachable", reaches=("idle",)).home().pose(dz=3000000, far=True).move(ms=500) \
        .pose(dx=200000, far=True).move(speed=80000).pose(dx=100).move(ms=1).rest()
    new("not_homed", reaches=("idle",)).cmd("ENABLE").pose(dx=1000).move(ms=100) \
        .pose(dx=1000).traj(20000)
    new("homing_fault", reaches=("homing", "fault")).cmd("ENABLE").limits(0x0101).cmd("HOME") \
        .rest().limits(0).cmd("CLEAR_FAULT")
    new("stop_homing_joint_move", HARNESS, ("stopping", "idle")).cmd("ENABLE").cmd("HOME") \
        .ms(1500).cmd("STOP").rest()
    new("stop_homing_joint_move_fast", reaches=("stopping",)).cmd("ENABLE").cmd("HOME").ms(300) \
        .cmd("STOP").rest()
    new("state_refusals", reaches=("homing",)).cmd("HOME").cmd("CLEAR_FAULT").cmd("DISABLE") \
        .cmd("ENABLE").cmd("ENABLE").cmd("HOME").cmd("ENABLE").cmd("DISABLE").pose(dx=10).move(ms=10) \
        .param_set("slide_vmax", 100000).save().rest().cmd("DISABLE")
    new("malformed").raw(0x061, [1, 2]).raw(0x7F1, [1]).raw(0x0D1, [9, 7, 0xE8, 3, 0, 0]) \
        .raw(0x0A1, [9, 0xFF, 0xFF, 0x7F, 0, 0, 0]).raw(0x111, [1, 2, 3, 4]).raw(0x072, [5]) \
        .raw(0x201, [0] * 8).raw(0x060, [5]).raw(0x031, [0] * 8).raw(0x0E1, [3, 0, 0, 0, 0, 0, 3], 7) \
        .raw(0x0F1, [], 0).raw(0x010, [1], 1).raw(0x011, [], 0)
    # INFO_GET at rest, moving, in e-stop; a page no firmware has (a flipped bit of the page: range),
    # another length, a broadcast.
    new("info", reaches=("moving", "estop")).msg("INFO_GET", b"\x00").home().pose(dx=3000).move(ms=400) \
        .ms(50).msg("INFO_GET", b"\x00").msg("INFO_GET", b"\x00", flip=12).msg("INFO_GET", b"\x00", flip=11) \
        .cmd("ESTOP").msg("INFO_GET", b"\x00").msg("INFO_GET", b"\x00", node=2).rest()
    # INFO_GET page 1 (BOARD) at rest and moving; node and enable_level set, refused out of range, saved
    # and taken through a power cycle (the rig's configured node overrides the stored one).
    new("board_node", reaches=("moving",)).msg("INFO_GET", b"\x01").param_set("node", 5) \
        .param_set("node", 16).param_set("enable_level", 2).param_set("enable_level", 3).save().reboot() \
        .msg("INFO_GET", b"\x01").home().pose(dx=3000).move(ms=400).ms(50).msg("INFO_GET", b"\x01").rest()
    new("msg_fields").msg("ENABLE", b"\x05").msg("MOVE_COMMIT", b"\x07\x05\x10\x00\x00\x00") \
        .msg("TRAJ_COMMIT", b"\x07\x00\x00\x00\x00\x03\x07") \
        .msg("POSE_A", b"\x01\xff\xff\x7f\x00\x00\x00", flip=30) \
        .msg("STOP", b"\x02", node=3).msg("ESTOP", b"\x02", node=2) \
        .msg("HOME", b"\x04", flip=11).msg("DISABLE", b"\x04", flip=3)
    return S


def summary_states(out):
    m = re.search(r"^states entered \(times\):(.*)$", out, re.M)
    pairs = m.group(1).split()
    return {pairs[i]: int(pairs[i + 1]) for i in range(0, len(pairs), 2)}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--check", metavar="REPLAY")
    args = ap.parse_args()
    all_seeds = seeds()
    if args.check:
        bad = 0
        env = dict(os.environ, TSE_FUZZ_SUMMARY="1")
        with tempfile.TemporaryDirectory() as tmp:
            for s in all_seeds:
                path = os.path.join(tmp, s.name)
                with open(path, "wb") as fh:
                    fh.write(s.b)
                r = subprocess.run([args.check, path], capture_output=True, text=True, env=env)
                if r.returncode != 0:
                    print(f"{s.name}: replay failed\n{r.stdout}{r.stderr}", file=sys.stderr)
                    bad += 1
                    continue
                entered = summary_states(r.stdout)
                missing = [st for st in s.reaches if entered.get(st, 0) == 0]
                if missing:
                    print(f"{s.name}: never entered {', '.join(missing)}", file=sys.stderr)
                    bad += 1
        if bad:
            sys.exit(f"{bad} seeds do not do what they are for; nothing written")
    os.makedirs(args.out, exist_ok=True)
    for s in all_seeds:
        with open(os.path.join(args.out, "seed_" + hashlib.sha1(s.b).hexdigest()[:16]), "wb") as fh:
            fh.write(s.b)
    print(f"{len(all_seeds)} seeds in {args.out}")


if __name__ == "__main__":
    main()
