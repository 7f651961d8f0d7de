"""A controller on python-can's in-process virtual bus that answers tse.can's trajectory exchanges as
docs/protocol.md says, for the host tests (the real one, tse-sim, runs in the vcan harness): STATUS
every 20 ms (idle, homed, enabled), telemetry at the home pose, PARAM_GET with the table's
defaults, and TRAJ_COMMIT rows into a queue of `capacity` that drains a row per its dt, its clock
starting with the first row.  A row is refused queue_full when the queue is full, order when its
number is not the one expected next, ended when its trajectory is not the open one; TRAJ_END says
how a trajectory ended.

over_report: STATUS reports that many free slots more than there are (a report that is behind).
stop_after: after that many rows taken, the trajectory ends as by a STOP from another host.
info: what INFO_GET page 0 is answered with after its ACK, ((major, minor, patch), step_hz,
segment_hz); None: refused as unknown, as a firmware older than INFO refuses it."""
import math
import threading
import time

import can as pycan

from tse import _protocol as P
from tse import can as tcan


class Recorder(pycan.Listener):
    """Every frame on the bus, in the bus's order."""

    def __init__(self):
        self.frames = []

    def on_message_received(self, msg):
        self.frames.append(msg)


def home_pose():
    """The controller's home pose from the defaults (README: X = Y = 0, zero orientation, at
    z = L sin((alpha_min + alpha_max) / 2))."""
    d = {p[0]: p[4] * 1e-6 for p in P.PARAMS}
    return [0.0, 0.0, d["L"] * math.sin((d["alpha_min"] + d["alpha_max"]) / 2), 0.0, 0.0, 0.0]


class FakeController:
    def __init__(self, channel, node=3, capacity=32, over_report=0, stop_after=None, info=((9, 8, 7), 200000, 1000)):
        self.node, self.capacity, self.over_report, self.stop_after = node, capacity, over_report, stop_after
        self.info = info
        self.bus = pycan.Bus(interface="virtual", channel=channel, receive_own_messages=False)
        import numpy as np  # the home pose's slides: tse.kin, only for the fake itself

        from tse import kin
        self.pose = home_pose()
        self.slides = list(kin.ik(np.array([self.pose])).q[0])
        self.state, self.last_seq = "idle", 9
        self.queue = []            # (end time, raw pose) of rows not yet reached
        self.taken = []            # raw poses of the rows taken, in order
        self.answers = []          # (seq, "ACK" or reason) in order
        self.open, self.ident, self.expect = False, None, None
        self.ended, self.ended_at = None, None  # (how, fault) of the last trajectory, and when
        self.staged = {}
        self.t0 = None
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def close(self):
        self._stop.set()
        self._thread.join()
        self.bus.shutdown()

    def _send(self, message, **v):
        self.bus.send(tcan.encode(message, self.node, **v))

    def _status(self):
        free = self.capacity - len(self.queue)
        self._send("STATUS", state=tcan._enum_value("state", self.state), fault=0, flags=3,
                   queue_depth=len(self.queue), queue_free=min(free + self.over_report, 255), last_seq=self.last_seq,
                   counter=0)
        raw = [round(v * 1e9) for v in self.slides]
        for k, m in enumerate(("SLIDES_A", "SLIDES_B", "SLIDES_C")):
            self._send(m, **{f"s_a{k + 1}": raw[2 * k], f"s_b{k + 1}": raw[2 * k + 1]})
        p = [round(v * 1e6) for v in self.pose]
        self._send("FK_A", x=p[0], y=p[1])
        self._send("FK_B", z=p[2], roll=p[3])
        self._send("FK_C", pitch=p[4], yaw=p[5])

    def _reject(self, fn, seq, reason, field=0, where=0):
        self.answers.append((seq, reason))
        self._send("REJECT", function=fn, seq=seq, reason=tcan._enum_value("reason", reason), scissor=0,
                   kin_status=0, field=field, where=where)

    def _end(self, how, now):
        self.open, self.ended, self.ended_at = False, how, now
        self.queue = []
        self._send("TRAJ_END", traj=self.ident, ended=tcan._enum_value("traj_end", how), fault=0,
                   rows=len(self.taken))
        self.state = "idle"

    def _row(self, v, now):
        fn, seq = P.MESSAGES["TRAJ_COMMIT"][0], v["seq"]
        first = bool(v["flags"] & P.TRAJ_FIRST)
        if not first and not (self.open and v["traj"] == self.ident):
            how = self.ended if self.ended and v["traj"] == self.ident else "none"
            ms = int((now - self.ended_at) * 1000) if how != "none" else 0
            return self._reject(fn, seq, "ended", tcan._enum_value("traj_end", how), ms)
        if not first and seq != self.expect:
            return self._reject(fn, seq, "order", self.expect)
        if first and self.state != "idle":
            return self._reject(fn, seq, "state", tcan._enum_value("state", self.state))
        if len(self.queue) >= self.capacity:
            return self._reject(fn, seq, "queue_full")
        if first:
            self.open, self.ident, self.t0, self.state = True, v["traj"], now, "moving"
            self.taken = []
        end = (self.queue[-1][0] if self.queue else now) + v["dt"] * 1e-6
        self.queue.append((end, self.staged.get(seq), bool(v["flags"] & P.TRAJ_LAST)))
        self.taken.append(self.staged.get(seq))
        self.expect, self.last_seq = (seq + 1) & 0xFF, seq
        self.answers.append((seq, "ACK"))
        self._send("ACK", function=fn, seq=seq, queue_depth=len(self.queue),
                   queue_free=self.capacity - len(self.queue), detail=0)
        if self.stop_after is not None and len(self.taken) == self.stop_after:
            self._end("stop", now)

    def _run(self):
        next_status = 0.0
        while not self._stop.is_set():
            now = time.monotonic()
            while self.queue and self.queue[0][0] <= now:
                _end, _pose, last = self.queue.pop(0)
                if last:
                    self._end("done", now)
            if now >= next_status:
                self._status()
                next_status = now + 0.02
            m = self.bus.recv(0.002)
            if m is None:
                continue
            name, node, v = tcan.decode(m, "to_controller")
            if node != self.node:
                continue
            if name.startswith("POSE_"):
                part = self.staged.setdefault(v["seq"], {})
                part.update({k: x for k, x in v.items() if k != "seq"})
            elif name == "PARAM_GET":
                self._send("ACK", function=P.MESSAGES[name][0], seq=0, queue_depth=0, queue_free=self.capacity,
                           detail=0)
                self._send("PARAM_VALUE", param=v["param"], value=P.PARAMS[v["param"]][4])
            elif name == "INFO_GET" and self.info is None:  # (not a row's answer: not in self.answers)
                self._send("REJECT", function=P.MESSAGES[name][0], seq=0, reason=tcan._enum_value("reason", "unknown"),
                           scissor=0, kin_status=0, field=0, where=0)
            elif name == "INFO_GET":
                self._send("ACK", function=P.MESSAGES[name][0], seq=0, queue_depth=len(self.queue),
                           queue_free=self.capacity - len(self.queue), detail=0)
                (major, minor, patch), step_hz, segment_hz = self.info
                self._send("INFO", major=major, minor=minor, patch=patch, step_hz=step_hz, segment_hz=segment_hz)
            elif name == "TRAJ_COMMIT":
                self._row(v, now)
            elif name == "STOP":
                self._send("ACK", function=P.MESSAGES[name][0], seq=v["seq"], queue_depth=0,
                           queue_free=self.capacity, detail=0)
                if self.open:
                    self._end("stop", now)
