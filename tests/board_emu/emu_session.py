"""The TSE emulator (emu/run.sh) from Python, standard library and python-can only.

Emulator: runs emu/run.sh with its sockets in a private directory; its `rig(request)` speaks the
rig protocol (docs/emulator.md) and `bus()` opens a python-can bus on the CAN socket (RecordBus),
which the project's own client takes: tse.can.Controller(bus=emu.bus(), ...).
"""
import os
import select
import socket
import struct
import subprocess
import threading
import time

import can

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
RUN = os.path.join(ROOT, "emu", "run.sh")
RECORD = struct.Struct("<IBBH8s")


class RigError(Exception):
    """The rig answered `error: ...`, or not at all."""


def _connect(path, deadline):
    while True:
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            s.connect(path)
            return s
        except OSError:
            s.close()
            if time.monotonic() > deadline:
                raise
            time.sleep(0.05)


class RecordBus(can.BusABC):
    """A python-can bus on the emulator's CAN socket: 16-byte records (docs/emulator.md)."""

    def __init__(self, path, deadline=None, **kwargs):
        self._sock = _connect(path, deadline or time.monotonic() + 30)
        self._buf = b""
        self.channel_info = f"tse-emu {path}"
        super().__init__(channel=path, **kwargs)

    def send(self, msg, timeout=None):
        can_id = msg.arbitration_id | (0x80000000 if msg.is_extended_id else 0) | (0x40000000 if msg.is_remote_frame else 0)
        self._sock.sendall(RECORD.pack(can_id, msg.dlc, 0, 0, bytes(msg.data).ljust(8, b"\0")))

    def _recv_internal(self, timeout):
        end = None if timeout is None else time.monotonic() + timeout
        while len(self._buf) < RECORD.size:
            left = None if end is None else max(0.0, end - time.monotonic())
            ready, _, _ = select.select([self._sock], [], [], left)
            if not ready:
                return None, False
            chunk = self._sock.recv(4096)
            if not chunk:
                raise can.CanOperationError("the emulator closed the CAN socket")
            self._buf += chunk
        rec, self._buf = self._buf[:RECORD.size], self._buf[RECORD.size:]
        can_id, length, _flags, _res, data = RECORD.unpack(rec)
        msg = can.Message(timestamp=time.time(), arbitration_id=can_id & 0x1FFFFFFF,
                          is_extended_id=bool(can_id & 0x80000000), is_remote_frame=bool(can_id & 0x40000000),
                          dlc=length, data=data[:length])
        return msg, False

    def shutdown(self):
        super().shutdown()
        self._sock.close()


def frame_bits(length):
    """A standard frame's time on the bus in bits, as the bridge takes it (docs/emulator.md)."""
    return 44 + 8 * length + 3


class BusFlood(threading.Thread):
    """FRAME (a can.Message) sent on BUS, the emulator's CAN socket, over and over at the bus's full
    rate in virtual time: the bridge puts its frames on the bus back to back, and holds 64 waiting
    before it stops reading the socket, so the flood keeps about AHEAD waiting (what virtual time
    has carried, counted at frame_bits, plus AHEAD) and the frames of the bus's other users queue
    behind those only.  Stop with stop(); then `sent` and `seconds` (virtual) say what it did."""

    def __init__(self, em, bus, frame, bitrate=500000, ahead=48):
        super().__init__(daemon=True)
        self.em, self.bus, self.frame, self.ahead = em, bus, frame, ahead
        self.frame_ns = frame_bits(frame.dlc) * 1e9 / bitrate
        self.sent = 0
        self.seconds = 0.0
        self.error = None
        self._halt = threading.Event()

    def run(self):
        try:
            t0 = self.em.time_ns()
            while not self._halt.is_set():
                elapsed = self.em.time_ns() - t0
                self.seconds = elapsed / 1e9
                for _ in range(int(elapsed / self.frame_ns) + self.ahead - self.sent):
                    self.bus.send(self.frame)
                    self.sent += 1
                time.sleep(0.002)
        except Exception as e:  # noqa: BLE001  (reported by stop())
            self.error = e

    def stop(self):
        self._halt.set()
        self.join(30)
        if self.error:
            raise self.error
        return self.sent


class Emulator:
    """emu/run.sh on ELF, its files in WORKDIR (flash image flash.bin unless FLASH is given)."""

    def __init__(self, elf, workdir, bitrate=500000, flash=None, hse_hz=None, icount=None, extra=()):
        self.workdir = workdir
        self.can_path = os.path.join(workdir, "can.sock")
        self.rig_path = os.path.join(workdir, "rig.sock")
        self.console = os.path.join(workdir, "console.txt")
        self.flash = flash or os.path.join(workdir, "flash.bin")
        self.log = os.path.join(workdir, "qemu.log")
        cmd = [RUN, "--elf", elf, "--can", self.can_path, "--rig", self.rig_path, "--flash", self.flash,
               "--console", self.console, "--bitrate", str(bitrate)]
        if hse_hz is not None:
            cmd += ["--hse-hz", str(hse_hz)]
        if icount is not None:
            cmd += ["--icount", icount]
        if extra:
            cmd += ["--", *extra]
        self._cmd = cmd
        self._proc = None
        self._rig = None
        self._rig_buf = b""
        self._rig_lock = threading.Lock()  # a request and its answer, one thread at a time

    def __enter__(self):
        self.start()
        return self

    def __exit__(self, *exc):
        self.stop()
        return False

    def start(self):
        with open(self.log, "ab") as log:
            self._proc = subprocess.Popen(self._cmd, stdout=log, stderr=subprocess.STDOUT)
        deadline = time.monotonic() + 30
        try:
            self._rig = _connect(self.rig_path, deadline)
        except OSError:
            self.stop()
            raise RuntimeError(f"the emulator did not serve its rig socket (log: {self.log}):\n{self.read_log()}")

    def stop(self):
        if self._rig:
            self._rig.close()
            self._rig = None
        if self._proc and self._proc.poll() is None:
            self._proc.terminate()
            try:
                self._proc.wait(10)
            except subprocess.TimeoutExpired:
                self._proc.kill()
                self._proc.wait()
        self._proc = None

    def running(self):
        return self._proc is not None and self._proc.poll() is None

    def read_log(self):
        with open(self.log, errors="replace") as f:
            return f.read()

    def read_console(self):
        try:
            with open(self.console, errors="replace") as f:
                return f.read()
        except FileNotFoundError:
            return ""

    def bus(self, **kwargs):
        return RecordBus(self.can_path, **kwargs)

    def rig(self, request, timeout=10.0):
        """The rig's answer lines to REQUEST, without the final `ok`; RigError on `error: ...`.
        Threads may share the rig: one request at a time."""
        with self._rig_lock:
            return self._rig_request(request, timeout)

    def _rig_request(self, request, timeout):
        self._rig.sendall(request.encode() + b"\n")
        lines = []
        end = time.monotonic() + timeout
        while True:
            while b"\n" not in self._rig_buf:
                left = end - time.monotonic()
                ready, _, _ = select.select([self._rig], [], [], max(0.0, left))
                if not ready:
                    raise RigError(f"no answer to {request!r} within {timeout} s")
                chunk = self._rig.recv(4096)
                if not chunk:
                    raise RigError(f"the emulator closed the rig socket (log: {self.log})")
                self._rig_buf += chunk
            line, self._rig_buf = self._rig_buf.split(b"\n", 1)
            text = line.decode()
            if text == "ok":
                return lines
            if text.startswith("error:"):
                raise RigError(f"{request!r}: {text}")
            lines.append(text)

    def time_ns(self):
        return int(self.rig("time")[0].split()[1])

    def slides(self):
        return [float(v) for v in self.rig("slides")[0].split()[1:]]
