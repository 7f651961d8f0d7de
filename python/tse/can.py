"""tse.can: a TSE controller on a CAN bus, from a Python session (python-can).

    from tse.can import Controller
    with Controller("vcan0", node=1) as ctl:       # the heartbeat runs while the session is open
        ctl.enable(); ctl.home()
        ctl.move([0.1, -0.05, 1.1, 0.1, -0.05, 0.2], duration=2)
        print(ctl.status())

The frames are packed and read from the protocol's message table as protogen prints it
(tse/_protocol.py, generated from firmware/include/fw/proto_messages.def, with a test that it is current), so
nothing here restates the wire format.  The exchanges are tsectl's: a command carries the next
sequence number after the controller's last accepted one (read from STATUS), and is answered by
exactly one ACK or REJECT; a REJECT raises Rejected, worded as tsectl words it.

Errors: ValueError for an argument that cannot be sent (nothing is sent), Rejected for a refusal
by the controller (or by its own rules, checked before sending), Fault for a motion that ended in
fault or e-stop, Ended (a Fault) for a trajectory the controller ended before its last row (a STOP
from elsewhere, a fault, an underrun, an e-stop), Timeout when the controller does not answer in
time.  All but ValueError derive from TseError.
"""

import contextlib
import ctypes
import math
import queue
import threading
import time
import warnings
from collections import namedtuple

from ._needs import need

_pycan = need("can", "python3-can", "tse.can")

from . import _protocol as _P

__all__ = ["Controller", "Status", "Telemetry", "MoveInfo", "Streamed", "Info", "Found", "TseError", "Rejected",
           "Fault", "Ended", "Timeout", "encode", "decode", "reject_words", "scan"]

# --- The codec, driven by the table --------------------------------------------------------------

_SIZE = {"u8": 1, "i8": 1, "u16": 2, "i16": 2, "u24": 3, "i24": 3, "u32": 4, "i32": 4}
_BY_FUNCTION = {(d[0], d[1]): name for name, d in _P.MESSAGES.items()}
_FIELDS = {name: tuple(f[0] for f in d[3]) for name, d in _P.MESSAGES.items()}


def _field(message, name):
    for f in _P.MESSAGES[message][3]:
        if f[0] == name:
            return f
    raise KeyError(f"{message} has no field {name}")


def encode(message, node, **values):
    """The frame of MESSAGE (a table name, e.g. "POSE_A") to or from NODE (0..15) with the given
    raw field values (every field of the message, integers).  ValueError names a field that is
    missing, unknown or outside the table's range."""
    if message not in _P.MESSAGES:
        raise ValueError(f"unknown message {message!r}")
    function, _direction, length, fields, _doc = _P.MESSAGES[message]
    if not isinstance(node, int) or not 0 <= node <= _P.NODE_MASK:
        raise ValueError(f"node {node!r} is not 0..{_P.NODE_MASK}")
    unknown = set(values) - set(_FIELDS[message])
    if unknown:
        raise ValueError(f"{message} has no field {sorted(unknown)[0]!r} (fields: {', '.join(_FIELDS[message])})")
    data = bytearray(length)
    for name, ftype, offset, lo, hi, *_ in fields:
        if name not in values:
            raise ValueError(f"{message}.{name} is missing")
        v = values[name]
        if isinstance(v, bool) or not isinstance(v, int):
            raise ValueError(f"{message}.{name} = {v!r} is not an integer")
        if not lo <= v <= hi:
            raise ValueError(f"{message}.{name} = {v} is outside [{lo}, {hi}] (raw units)")
        n = _SIZE[ftype]
        data[offset:offset + n] = (v & ((1 << (8 * n)) - 1)).to_bytes(n, "little")
    return _pycan.Message(arbitration_id=function << _P.NODE_BITS | node, is_extended_id=False, data=bytes(data))


class DecodeError(ValueError):
    """A frame the table does not describe: reason is the protocol's word (unknown, bad_length,
    range) and field the offending field's name (range only)."""

    def __init__(self, reason, text, field=None):
        super().__init__(text)
        self.reason = reason
        self.field = field


def decode(frame, direction="to_host"):
    """(message name, node, {field: raw value}) of a python-can frame travelling in DIRECTION
    ("to_host" or "to_controller"); DecodeError when the table does not describe it."""
    if frame.is_extended_id or frame.is_remote_frame or frame.is_error_frame or frame.arbitration_id > 0x7FF:
        raise DecodeError("unknown", f"frame 0x{frame.arbitration_id:X} is not a standard data frame")
    name = _BY_FUNCTION.get((frame.arbitration_id >> _P.NODE_BITS, direction))
    if name is None:
        raise DecodeError("unknown", f"no {direction} message has function 0x{frame.arbitration_id >> _P.NODE_BITS:02X}")
    _function, _direction, length, fields, _doc = _P.MESSAGES[name]
    if frame.dlc != length:
        raise DecodeError("bad_length", f"{name} is {length} bytes, this frame {frame.dlc}")
    out = {}
    for fname, ftype, offset, lo, hi, *_ in fields:
        n = _SIZE[ftype]
        v = int.from_bytes(bytes(frame.data[offset:offset + n]), "little", signed=ftype.startswith("i"))
        if not lo <= v <= hi:
            raise DecodeError("range", f"{name}.{fname} = {v} is outside [{lo}, {hi}]", fname)
        out[fname] = v
    return name, frame.arbitration_id & _P.NODE_MASK, out


def _enum(kind, value):
    return _P.ENUMS[kind].get(value, "?")


def _enum_value(kind, name):
    return next(v for v, n in _P.ENUMS[kind].items() if n == name)


# --- What the controller reports -----------------------------------------------------------------

Status = namedtuple("Status", "state fault homed enabled estop_open switch_alarm error_passive "
                              "queue_depth queue_free last_seq counter")
Status.__doc__ = """A STATUS frame: state and fault as the table names them ("idle", "none", ...); the
flags (homed, drives enabled, e-stop input open, a switch disagreeing with the step count, CAN error
passive); the trajectory queue; the last accepted sequence number; the free-running counter."""

Telemetry = namedtuple("Telemetry", "time slides pose state")
Telemetry.__doc__ = """One telemetry period: time (python-can's receive time of its last frame, s),
slides (the six commanded slide positions A1, B1, A2, B2, A3, B3, m), pose (x, y, z in m, roll,
pitch, yaw in rad, from the controller's forward kinematics; None before homing) and the state of
the latest STATUS."""

MoveInfo = namedtuple("MoveInfo", "start bound slide demand")
MoveInfo.__doc__ = """How an accepted move starts ("rest", "blended" into the running move, or "after" it)
and what set its pace ("asked", a plate limit's name such as "plate_vmax", or "slide_vmax",
"step_generator" (the slide speed limit in effect when lower than slide_vmax) and "slide_amax" with
the slide 1..6 (A1, B1, A2, B2, A3, B3) and what it would have needed without the
stretch over its limit, 1.14 = 14 % over; slide 0 and demand 0 otherwise): the controller's
MOVE_INFO, kept as Controller.last_move."""

Info = namedtuple("Info", "version step_hz segment_hz")
Info.__doc__ = """What the controller is (its INFO): version, its firmware's (major, minor, patch), and the rates it
runs at, step_hz step interrupts and segment_hz control segments per second, which its paths are
judged at (the slide speed its step generator allows, the segments acceleration is measured over)."""

Found = namedtuple("Found", "node version board step_hz segment_hz")
Found.__doc__ = """A controller scan() found: its node id, its firmware's version (major, minor, patch), its board's
name (BOARD, INFO_GET page 1) and its rates (INFO).  version and the rates are None from a firmware
older than INFO; board is None from one older than BOARD (or when its answer did not come)."""

Streamed = namedtuple("Streamed", "rows seconds rows_per_s fill_rows_per_s")
Streamed.__doc__ = """What trajectory() returns: the rows streamed, the seconds from the first row sent to the last
acknowledged, the rows per second that makes, and the rows per second until the controller's queue
first filled (this client's own pace; None if it never filled: then rows_per_s is)."""

_TELEMETRY_ORDER = ("SLIDES_A", "SLIDES_B", "SLIDES_C", "FK_A", "FK_B", "FK_C")  # a period's frames as sent
_TELEMETRY_FUNCTIONS = frozenset(_P.MESSAGES[m][0] for m in _TELEMETRY_ORDER)
_REJECT_FIELDS = tuple(f[0] for f in _P.MESSAGES["REJECT"][3])  # function, seq, reason, ...


def _status_of(v):
    f, bit = v["flags"], _P.STATUS_FLAGS
    return Status(_enum("state", v["state"]), _enum("fault", v["fault"]), bool(f & bit["homed"]),
                  bool(f & bit["drives"]), bool(f & bit["estop_in"]), bool(f & bit["switches_off"]),
                  bool(f & bit["error_passive"]), v["queue_depth"], v["queue_free"], v["last_seq"], v["counter"])


class TseError(Exception):
    """Anything the controller (or its silence) refused."""


class Timeout(TseError):
    """No answer within the time limit."""


class Fault(TseError):
    """A motion that ended in fault or e-stop: state and fault as STATUS names them."""

    def __init__(self, text, state, fault):
        super().__init__(text)
        self.state = state
        self.fault = fault


class Ended(Fault):
    """A trajectory the controller ended before its last row, as it reported it (TRAJ_END, and the
    refusal of a row that came after):

    ended     how: "stop" (a STOP this client did not send), "fault", or "none" (not reported)
    fault     for "fault", which: "underrun" (the host fell behind), "estop", "watchdog", ...; else "none"
    row       the first row it did not take (0-based); None when every row was taken
    late      for an underrun, how late that row came (s), from the controller's refusal of it; None
              when it had not been sent
    The robot is at rest when it is raised."""

    def __init__(self, text, ended, fault, row, late, state):
        super().__init__(text, state, fault)
        self.ended = ended
        self.row = row
        self.late = late


class Rejected(TseError):
    """A REJECT: the controller refused a command and applied nothing of it.

    command   the refused message ("MOVE_COMMIT", ...)
    reason    the protocol's word: "kinematics", "timing", "state", "not_homed", ...
    scissor   the first failing scissor 1..3 (kinematics, timing), else None
    status    the kinematic status of the first failing point ("unreachable", ...), else None
    fraction  where along the path the first failing point is, 0..1 (kinematics), else None
    state     the controller's state when it refused (reason "state"), else None
    limit     the limit a timing refusal is against ("slide_vmax", "slide_amax", or "step_generator"
              when the step generator's speed limit is below slide_vmax: _protocol.CODES["slide_limit"]),
              else None
    rule      the rule a refused parameter set breaks ("alpha_order", "pulse_low", ...:
              _protocol.CODES["param_rule"]; "unspecified" from an older controller), else None
    row       the trajectory row (0-based) that was refused (trajectory only), else None
    raw       the REJECT's fields
    str(e) is tsectl's wording: "rejected: REASON: ...".
    """

    def __init__(self, raw, row=None, prefix=""):
        self.raw = dict(raw)
        self.command = _command_name(raw["function"])
        self.reason = _enum("reason", raw["reason"])
        kin = self.reason == "kinematics"
        self.scissor = raw["scissor"] if self.reason in ("kinematics", "timing") else None
        self.status = _enum("kin_status", raw["kin_status"]) if kin else None
        self.fraction = raw["where"] / _P.PER_MILLE if kin else None
        self.state = _enum("state", raw["field"]) if self.reason == "state" else None
        self.limit = self.rule = None
        if self.reason == "timing":
            code = raw["field"] // _P.REJECT_LIMIT_STRIDE
            self.limit = _P.CODES["slide_limit"].get(code, (str(code),))[0]
        if self.reason == "param_set":
            self.rule = _P.CODES["param_rule"].get(raw["where"], (str(raw["where"]),))[0]
        self.row = row
        self.words = reject_words(raw)
        super().__init__(prefix + self.words)


def _command_name(function):
    return _BY_FUNCTION.get((function, "to_controller"), "?")


def _at_rest(st):
    """Whether the controller of Status st is at rest, as tsectl judges it (rest_wait.c)."""
    from . import _native
    f = _native.load().tse_py_rest_state
    f.restype = ctypes.c_int
    f.argtypes = [ctypes.c_int]
    return f(_enum_value("state", st.state)) != 0


def _param_name(pid):
    return _P.PARAMS[pid][0] if 0 <= pid < len(_P.PARAMS) else None


def reject_words(raw):
    """A REJECT's fields (raw values, as decode gives them) in tsectl's words:
    "rejected: REASON: explanation", from tsectl's own text (reject_text.c in libtse_kin.so), so the
    two cannot differ.  Without the library: the reason and the raw fields, and why no more."""
    fields = [int(raw[k]) for k in _REJECT_FIELDS]
    try:
        from . import _native
        f = _native.load().tse_py_reject_text
    except (ImportError, OSError, AttributeError) as e:
        return (f"rejected: {_enum('reason', raw['reason'])}: {_command_name(raw['function'])} "
                f"(fields {fields}; no words: {e})")
    f.restype = ctypes.c_char_p
    f.argtypes = [ctypes.c_int * 7, ctypes.c_char_p, ctypes.c_size_t]
    buf = ctypes.create_string_buffer(512)
    return f((ctypes.c_int * 7)(*fields), buf, len(buf)).decode()


# --- The trajectory check, tsectl's (libtse_kin.so) -------------------------------------------------

def _check_rows(params, rates, pose0, slides0, plan):
    """The controller's whole-path check (tse_py_traj_check) of plan [(dt_us, raw pose)] from rest at
    pose0 with slides slides0 under the raw parameter set params at rates (step_hz, segment_hz):
    (None, None) when every row passes, (row, REJECT fields) for the first it would refuse, None when
    it refuses the set."""
    from . import _native  # ctypes only; ImportError saying how to build the library
    step_hz, segment_hz = _native.checked_rates(rates)
    f = _native.load().tse_py_traj_check
    c_int, c_double, c_long, c_uint = ctypes.c_int, ctypes.c_double, ctypes.c_long, ctypes.c_uint
    f.restype = c_int
    f.argtypes = [ctypes.POINTER(c_int), c_int, c_uint, c_uint, ctypes.POINTER(c_double), ctypes.POINTER(c_double),
                  c_long, ctypes.POINTER(c_uint), ctypes.POINTER(c_double), ctypes.POINTER(c_long),
                  ctypes.POINTER(c_int), ctypes.POINTER(c_double), ctypes.POINTER(c_double)]
    scales = [f[6] for f in _POSE_FIELDS]
    n = len(plan)
    poses = (c_double * (6 * n))(*(raw[k] * scales[k] for _dt, raw in plan for k in range(6)))
    dts = (ctypes.c_uint * n)(*(dt for dt, _raw in plan))
    row, reject, v_peak, a_peak = c_long(), (c_int * 7)(), c_double(), c_double()
    rc = f((c_int * len(params))(*params), len(params), step_hz, segment_hz, (c_double * 6)(*pose0),
           (c_double * 6)(*slides0), n, dts, poses, ctypes.byref(row), reject, ctypes.byref(v_peak), ctypes.byref(a_peak))
    if rc == -2:
        raise TseError("libtse_kin.so and tse/_protocol.py know different parameter tables: rebuild the library")
    if rc < 0:
        return None
    if rc == 0:
        return None, None
    return row.value, dict(zip(_FIELDS["REJECT"], reject))


# --- Values people write -------------------------------------------------------------------------

def _round_away(x):
    return int(math.floor(abs(x) + 0.5)) * (1 if x >= 0 else -1)


# The six pose fields in x, y, z, roll, pitch, yaw order, as the table gives them.
_POSE_FIELDS = tuple(_field(m, k) for m, k in (("POSE_A", "x"), ("POSE_A", "y"), ("POSE_B", "z"), ("POSE_B", "roll"),
                                              ("POSE_C", "pitch"), ("POSE_C", "yaw")))


def _pose_raw(pose):
    """The six wire integers of a pose (m, rad), checked against the POSE fields' ranges."""
    try:
        p = [float(v) for v in pose]
    except (TypeError, ValueError):
        raise ValueError(f"a pose is six numbers x, y, z (m), roll, pitch, yaw (rad), not {pose!r}") from None
    if len(p) != 6:
        raise ValueError(f"a pose is six numbers x, y, z (m), roll, pitch, yaw (rad), not {len(p)}")
    raw = []
    for v, (name, _t, _o, lo, hi, unit, scale, *_) in zip(p, _POSE_FIELDS):
        if not math.isfinite(v) or not lo <= _round_away(v / scale) <= hi:
            raise ValueError(f"{name} = {v!r} {unit} is outside the wire's range {lo * scale:g}..{hi * scale:g} {unit}")
        raw.append(_round_away(v / scale))
    return raw


def _raw_socketcan(bus):
    """(send, pack) writing a frame straight to a SocketCAN bus's socket, one system call a frame,
    or (None, None) for other buses.  python-can's send adds a select and logging to every frame,
    which a slow machine feels (the vcan harness's emulated VM streams trajectory rows at a fraction
    of the rate without this)."""
    try:
        from can.interfaces.socketcan.socketcan import SocketcanBus, build_can_frame
    except ImportError:
        return None, None
    if isinstance(bus, SocketcanBus) and bus.channel:
        return bus.socket.send, build_can_frame
    return None, None


# --- The controllers on a bus ---------------------------------------------------------------------

def _scan_take(e, name, v):
    """One answer from a node into its entry (a dict)."""
    if name == "INFO":
        e["infos"] += 1
        e["version"], e["rates"] = (v["major"], v["minor"], v["patch"]), (v["step_hz"], v["segment_hz"])
    elif name == "BOARD":
        chars = bytes(v[f[0]] for f in _P.MESSAGES["BOARD"][3])
        e["board"] = chars.split(b"\0", 1)[0].decode("ascii")
    elif name == "REJECT" and v["function"] == _P.MESSAGES["INFO_GET"][0]:
        e["older"] = True  # unknown: older than INFO; range (page 1): older than BOARD


def scan(bus, timeout=2.0, interface="socketcan"):
    """The controllers on a bus, as `tsectl scan` finds them: INFO_GET pages 0 and 1 to every node id
    1..15, then every answer read for `timeout` seconds.  bus: a python-can bus the caller owns, or
    a channel name (opened with `interface`, closed after).  Returns a list of Found, by node id
    (empty when none answered); a node that answers INFO twice (two controllers on one id) is
    warned about.  Run it while no Controller reads the same bus object."""
    if not timeout > 0:
        raise ValueError(f"timeout {timeout!r} is not a positive number of seconds")
    own = isinstance(bus, str)
    if own:
        try:
            bus = _pycan.Bus(channel=bus, interface=interface)
        except (OSError, _pycan.CanError, ValueError, ImportError) as e:
            raise TseError(f"cannot open CAN channel {bus!r} ({interface}): {e}") from e
    try:
        for node in range(1, _P.NODE_MASK + 1):
            for page in (0, 1):
                bus.send(encode("INFO_GET", node, page=page), timeout=timeout)
        found = {}
        end = time.monotonic() + timeout
        while (left := end - time.monotonic()) > 0:
            frame = bus.recv(left)
            if frame is None:
                break
            try:
                name, node, v = decode(frame)
            except DecodeError:
                continue
            if node and name in ("INFO", "BOARD", "REJECT", "ACK", "STATUS"):
                _scan_take(found.setdefault(node, {"infos": 0}), name, v)
    finally:
        if own:
            bus.shutdown()
    out = []
    for node in sorted(found):
        e = found[node]
        if e["infos"] > 1:
            warnings.warn(f"node {node} answered INFO_GET {e['infos']} times: two controllers share node id {node}",
                          stacklevel=2)
        rates = e.get("rates", (None, None))
        out.append(Found(node, e.get("version"), e.get("board"), rates[0], rates[1]))
    return out


# --- The controller ------------------------------------------------------------------------------

class Controller:
    """One controller on a CAN bus (python-can).

    Controller(channel="vcan0", node=1, interface="socketcan", timeout=2.0, heartbeat=True, bus=None)
    opens the bus (or uses BUS, a python-can bus the caller owns) and starts a reader thread and,
    with heartbeat, the host heartbeat (HOST_HEARTBEAT every 100 ms: the controller's watchdog
    stops the robot and latches a fault when it falls silent while enabled).  timeout is how long
    an answer may take (s).  Use it as a context manager, or call close(): on exit a running
    motion is stopped (STOP) and waited for, then the heartbeat and the reader end.
    """

    HEARTBEAT_PERIOD = 0.1

    def __init__(self, channel="vcan0", node=1, interface="socketcan", timeout=2.0, heartbeat=True, bus=None):
        if not isinstance(node, int) or not 1 <= node <= _P.NODE_MASK:
            raise ValueError(f"node {node!r} is not 1..{_P.NODE_MASK}")
        if not timeout > 0:
            raise ValueError(f"timeout {timeout!r} is not a positive number of seconds")
        self.node = node
        self.timeout = float(timeout)
        self._own_bus = bus is None
        # The kernel passes the node's frames; telemetry only while someone watches (on a slow machine
        # 120 telemetry frames a second nobody reads fill the socket's queue, and answers are lost).
        self._filters_all = [{"can_id": node, "can_mask": _P.NODE_MASK, "extended": False}]
        self._filters_quiet = [{"can_id": fn << _P.NODE_BITS | node, "can_mask": 0x7FF, "extended": False}
                               for name, (fn, direction, *_rest) in _P.MESSAGES.items()
                               if direction == "to_host" and fn not in _TELEMETRY_FUNCTIONS]
        if bus is None:
            try:
                bus = _pycan.Bus(channel=channel, interface=interface, can_filters=self._filters_quiet)
            except (OSError, _pycan.CanError, ValueError, ImportError) as e:
                raise TseError(f"cannot open CAN channel {channel!r} ({interface}): {e}") from e
        self._bus = bus
        self._raw_send, self._raw_frame = _raw_socketcan(bus)
        self._cond = threading.Condition()
        self._hold_cond = threading.Condition()  # _reading(): the reader thread waits while _hold
        self._hold = self._held = False
        self._send_lock = threading.Lock()
        self._cmd_lock = threading.RLock()
        self._status = None
        self.last_move = None     # the MoveInfo of the latest move this object committed
        self._status_serial = 0
        self._answers = []        # (serial, name, fields) of ACK, REJECT and PARAM_VALUE, newest last
        self._traj_end = None     # the newest TRAJ_END's fields
        self._serial = 0
        self._watchers = []
        # One telemetry period in the making: its frames in the order the controller sends them
        # (SLIDES_A..C, FK_A..C).  _tel_epoch counts watches begun; a period begun before the
        # newest is dropped (the reader's side of the hand-over, so no lock).
        self._tel = []
        self._tel_epoch = self._tel_epoch_seen = 0
        self._closed = False
        self._reader = threading.Thread(target=self._read, name=f"tse-can-reader-{node}", daemon=True)
        self._reader.start()
        self._hb_stop = None
        self._hb_thread = None
        self.params = _Params(self)
        if heartbeat:
            self.start_heartbeat()

    # -- session --
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def close(self):
        """Stops a running motion (and waits for rest), ends the heartbeat and the reader, and
        closes the bus if this object opened it.  Calling it again does nothing."""
        if self._closed:
            return
        try:
            st = self._status
            if st is not None and not _at_rest(st):
                self.stop(wait=True)
        except TseError:
            pass
        finally:
            self.stop_heartbeat()
            with self._hold_cond:
                self._closed = True
                self._hold_cond.notify_all()
            self._reader.join(timeout=1.0)
            if self._own_bus:
                self._bus.shutdown()

    def start_heartbeat(self):
        """Starts the host heartbeat (if it is not running)."""
        if self._hb_thread is not None:
            return
        self._hb_stop = threading.Event()
        self._hb_thread = threading.Thread(target=self._beat, args=(self._hb_stop,), name="tse-can-heartbeat",
                                           daemon=True)
        self._hb_thread.start()

    def stop_heartbeat(self):
        """Ends the host heartbeat: an enabled controller's watchdog then stops it and latches a
        watchdog fault (unless its watchdog_ms is 0)."""
        if self._hb_thread is None:
            return
        self._hb_stop.set()
        self._hb_thread.join()
        self._hb_thread = None

    @property
    def heartbeat_running(self):
        return self._hb_thread is not None

    def _beat(self, stop):
        counter = 0
        while not stop.is_set():
            try:
                self._send("HOST_HEARTBEAT", counter=counter)
            except (_pycan.CanError, OSError):
                pass  # a full transmit queue: the next beat tries again
            counter = (counter + 1) & 0xFF
            stop.wait(self.HEARTBEAT_PERIOD)

    # -- the bus --
    def _send(self, message, node=None, **values):
        self._send_frames([encode(message, self.node if node is None else node, **values)])

    def _send_frames(self, frames):
        with self._send_lock:
            for frame in frames:
                if self._raw_send is not None:
                    data = self._raw_frame(frame)
                    with contextlib.suppress(OSError):  # a full transmit queue: python-can's send waits
                        if self._raw_send(data) == len(data):
                            continue
                self._bus.send(frame, timeout=self.timeout)

    def _read(self):
        while not self._closed:
            with self._hold_cond:
                if self._hold:  # a stream reads the bus itself meanwhile
                    self._held = True
                    self._hold_cond.notify_all()
                    self._hold_cond.wait_for(lambda: not self._hold or self._closed)
                    self._held = False
            if not self._closed:
                self._read_one(0.1)

    def _read_one(self, timeout):
        """Reads a frame (up to timeout s) and takes it in: (name, fields) of a message from this
        node, else None."""
        try:
            frame = self._bus.recv(timeout)
        except (_pycan.CanError, OSError, ValueError):
            if not self._closed:
                time.sleep(0.01)
            return None
        if frame is None:
            return None
        if not self._watchers and frame.arbitration_id >> _P.NODE_BITS in _TELEMETRY_FUNCTIONS:
            self._tel.clear()  # telemetry nobody watches is not worth a decode on a slow machine;
            return None        # a watcher starts on a period of its own
        try:
            name, node, v = decode(frame)
        except DecodeError:
            return None
        if node != self.node:
            return None
        self._take(name, v, frame.timestamp)
        return name, v

    @contextlib.contextmanager
    def _reading(self):
        """The caller reads the bus itself (_read_one) while the reader thread waits: a streamed row's
        answer then reaches the thread that sends the next row without a hand-over between threads,
        which a slow machine feels."""
        with self._hold_cond:
            self._hold = True
            if not self._hold_cond.wait_for(lambda: self._held or self._closed, timeout=self.timeout):
                self._hold = False
                raise Timeout(f"the reader of node {self.node}'s frames did not yield within {self.timeout:g} s")
        try:
            yield
        finally:
            with self._hold_cond:
                self._hold = False
                self._hold_cond.notify_all()

    def _take(self, name, v, stamp):
        with self._cond:
            if name == "STATUS":
                self._status = _status_of(v)
                self._status_serial += 1
            elif name in ("ACK", "REJECT", "PARAM_VALUE", "MOVE_INFO", "INFO", "BOOT_ID", "BOOT_LAYOUT", "BOOT_APP"):
                self._serial += 1
                self._answers.append((self._serial, name, v))
                del self._answers[:-512]
            elif name == "TRAJ_END":
                self._traj_end = v
            else:
                self._telemetry(name, v, stamp)
                return
            self._cond.notify_all()

    def _telemetry(self, name, v, stamp):
        """Takes a telemetry frame into the period in the making and publishes the period when it
        is whole: a Telemetry is made of one period's frames only.  A period starts at SLIDES_A;
        a frame out of its order, or a period begun before the newest watch (whose frames may have
        stopped at the socket's filter half way, and whose rest may come long after), is dropped
        until the next SLIDES_A."""
        tel = self._tel
        if self._tel_epoch_seen != self._tel_epoch:
            self._tel_epoch_seen = self._tel_epoch
            tel.clear()
        k = _TELEMETRY_ORDER.index(name)
        if k == 0:
            tel.clear()
        elif len(tel) != k:
            tel.clear()
            return
        # Each frame's two fields in SI, by their scales in the table (as _pose_raw packs a pose).
        tel.append(tuple(v[f[0]] * f[6] for f in _P.MESSAGES[name][3]))
        if k == 2 and not (self._status is not None and self._status.homed):
            self._publish(Telemetry(stamp, tel[0] + tel[1] + tel[2], None, self._state()))
        elif k == 5:
            self._publish(Telemetry(stamp, tel[0] + tel[1] + tel[2], tel[3] + tel[4] + tel[5], self._state()))

    def _state(self):
        return self._status.state if self._status is not None else None

    def _publish(self, t):
        for q in list(self._watchers):
            try:
                q.put_nowait(t)
            except queue.Full:
                pass  # a watcher that does not read loses its oldest news, never blocks the reader

    # -- exchanges --
    def _mark(self):
        with self._cond:
            return self._serial

    def _wait_for(self, pick, timeout, what):
        """Waits until pick() (called under the lock) returns something, up to timeout s."""
        end = time.monotonic() + timeout
        with self._cond:
            while True:
                got = pick()
                if got is not None:
                    return got
                left = end - time.monotonic()
                if left <= 0 or self._closed:
                    raise Timeout(f"no {what} from node {self.node} within {timeout:g} s (is it on the bus?)")
                self._cond.wait(min(left, 0.2))

    def _fresh_status(self, timeout=None):
        with self._cond:
            seen = self._status_serial
        return self._wait_for(lambda: self._status if self._status_serial > seen else None,
                              self.timeout if timeout is None else timeout, "STATUS")

    def _answer(self, mark, message, seq):
        function = _P.MESSAGES[message][0]

        def pick():
            for serial, name, v in self._answers:
                if serial > mark and name in ("ACK", "REJECT") and v["function"] == function and \
                        (seq is None or v["seq"] == seq):
                    return name, v
            return None
        return self._wait_for(pick, self.timeout, f"answer to {message}")

    def _exchange(self, message, **values):
        """Sends MESSAGE and waits for its ACK or REJECT (the one carrying its seq, when it has
        one).  Returns (mark, "ACK" or "REJECT", fields); mark dates what came after the send."""
        mark = self._mark()
        self._send(message, **values)
        name, v = self._answer(mark, message, values.get("seq"))
        return mark, name, v

    def _command(self, message, seq=None, **values):
        """Sends MESSAGE (with the next sequence number unless seq is given) and returns its ACK's
        fields; a REJECT raises Rejected."""
        with self._cmd_lock:
            if seq is None:
                seq = (self._fresh_status().last_seq + 1) & 0xFF
            _mark, name, v = self._exchange(message, seq=seq, **values)
            if name == "REJECT":
                raise Rejected(v)
            return v

    def _wait_rest(self, expected, what, settled=False):
        """tsectl's wait, by tsectl's own judgement of each STATUS (rest_wait.c in libtse_kin.so):
        follows STATUS until the controller is at rest after having been seen in motion (or has
        been at rest for 2 s without moving; at once when settled: every STATUS from now on comes
        after what the caller asked for, a STOP already acknowledged).  Fault at rest in disabled,
        fault or e-stop; Timeout past three times what was planned and a minute."""
        from . import _native  # ctypes only; ImportError saying how to build the library
        lib = _native.load()
        lib.tse_py_rest_limit.restype = ctypes.c_double
        lib.tse_py_rest_limit.argtypes = [ctypes.c_double]
        judge = lib.tse_py_rest_judge
        judge.restype = ctypes.c_int
        judge.argtypes = [ctypes.c_double, ctypes.c_int, ctypes.POINTER(ctypes.c_int), ctypes.c_double, ctypes.c_int,
                          ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_size_t]
        limit = lib.tse_py_rest_limit(float(expected))
        seen = ctypes.c_int(0)
        words = ctypes.create_string_buffer(160)
        t0 = time.monotonic()
        while True:
            el = time.monotonic() - t0
            st = None if el > limit else self._fresh_status(min(self.timeout, limit - el + 0.1))
            state = -1 if st is None else _enum_value("state", st.state)
            fault = 0 if st is None else _enum_value("fault", st.fault)
            v = judge(float(expected), int(settled), ctypes.byref(seen), time.monotonic() - t0 if st else el, state,
                      fault, what.encode(), words, len(words))
            if v > 0:
                return st
            if v == -2:  # (tse_py.h)
                raise Timeout(words.value.decode())
            if v < 0:
                raise Fault(words.value.decode(), st.state, st.fault)

    # -- commands --
    def status(self):
        """The controller's next STATUS (a Status)."""
        return self._fresh_status()

    def flash(self, path, progress=None):
        """Updates the controller's firmware with the image at path, as `tsectl flash` does
        (tse/flash.py; docs/protocol.md, "Updating the firmware"): asks an application to restart
        into its bootloader (Rejected "state" while its drives may be on), refuses an image for
        another board or too long before anything is erased, then erases, writes (progress(done,
        total) after each block), verifies and starts it.  Returns a tse.flash.Flashed (version, crc,
        erase_s, transfer_s, rate).  ValueError for a file that is no good image, nothing sent."""
        from .flash import flash
        with self._cmd_lock:
            return flash(self, path, progress)

    def info(self):
        """What the controller is (INFO_GET, answered in every state): an Info with its firmware's version
        and the rates it runs at.  A controller whose firmware is older than INFO refuses INFO_GET
        as unknown: Rejected with reason "unknown"."""
        with self._cmd_lock:
            mark, name, v = self._exchange("INFO_GET", page=0)
            if name == "REJECT":
                raise Rejected(v)

            def pick():
                for serial, got, f in self._answers:
                    if serial > mark and got == "INFO":
                        return Info((f["major"], f["minor"], f["patch"]), f["step_hz"], f["segment_hz"])
                return None
            return self._wait_for(pick, self.timeout, "INFO")

    def set_node(self, node):
        """Changes the controller's node id to `node` (1..15): PARAM_SET of the parameter node, then
        PARAM_SAVE, as `tsectl node set` does.  It takes effect when the controller restarts; until
        then it answers on its current id (this object keeps talking to it there).  Returns node.
        ValueError (nothing sent) outside 1..15; Rejected when the controller refuses."""
        lo, hi = _P.PARAMS[_P.PARAM_SPELLINGS["node"][0]][2:4]
        if isinstance(node, bool) or not isinstance(node, int) or not lo <= node <= hi:
            raise ValueError(f"node {node!r} is not a node id: a whole number {lo}..{hi} (nothing sent)")
        self.params.set("node", node)
        self.params.save()
        return node

    def _rates(self):
        """(step_hz, segment_hz) to judge this controller's paths at: its INFO's; from a controller that
        does not know INFO_GET (its firmware older than INFO, when every firmware ran at the built-in
        rates) the built-in ones, with a warning saying so."""
        from . import _native
        try:
            i = self.info()
        except Rejected as e:
            if e.reason != "unknown":
                raise
            rates = _native.built_in_rates()
            warnings.warn(f"node {self.node} does not know INFO_GET (a firmware older than INFO): judged at the "
                          f"built-in rates, {rates[0]} Hz step interrupts and {rates[1]} Hz control segments, which "
                          "every such firmware ran at", stacklevel=3)
            return rates
        return _native.checked_rates((i.step_hz, i.segment_hz))

    def enable(self):
        """Energises the drives."""
        self._command("ENABLE")

    def disable(self):
        """De-energises the drives (only at rest); the slides keep their zero."""
        self._command("DISABLE")

    def clear(self):
        """Leaves fault or e-stop (the e-stop input must be closed); the drives stay off."""
        self._command("CLEAR_FAULT")

    def stop(self, wait=False):
        """Controlled stop: the motion decelerates along its path and the trajectory queue is
        dropped.  wait: until at rest (a KeyboardInterrupt meanwhile sends ESTOP, then is raised)."""
        try:
            self._command("STOP")
            if wait:
                return self._wait_rest(0, "stopping", settled=True)
        except KeyboardInterrupt:
            if wait:
                self.estop()
            raise
        return None

    def _halt(self):
        """Ends a motion this object started and may no longer follow (an exception, such as
        KeyboardInterrupt, in a waiting call): STOP, then wait until at rest; a KeyboardInterrupt
        meanwhile sends ESTOP and is raised.  A failing exchange is not raised: the caller raises
        what interrupted it."""
        try:
            self.stop(wait=True)
        except TseError:
            pass

    def _motion(self, start, what, wait):
        """Runs start(), which sends the command that starts a motion and returns its planned
        duration (0 when unknown), then with wait follows the motion to rest.  A refusal, timeout
        or fault (TseError) is raised as it is; anything else raised meanwhile (KeyboardInterrupt
        above all, even before the answer came: the motion may have been taken) stops the robot
        first (_halt), then is raised."""
        try:
            planned = start()
            if wait:
                self._wait_rest(planned, what)
            return planned
        except TseError:
            raise
        except BaseException:
            self._halt()
            raise

    def estop(self):
        """Emergency stop, sent at once (no STATUS first): stepping is cut and an e-stop fault
        latches."""
        self._command("ESTOP", seq=0)

    def home(self, wait=True):
        """Homes the six slides, then goes to the home pose.  wait: until at rest (a homing
        already running is waited for).  A KeyboardInterrupt while it waits stops the robot as in
        move()."""
        def start():
            try:
                self._command("HOME")
            except Rejected as e:
                if not (wait and e.reason == "state" and e.state == "homing"):
                    raise
            return 0
        self._motion(start, "homing", wait)

    def move(self, pose, duration=None, speed=None, wait=True):
        """Moves the plate to pose (x, y, z in m; roll, pitch, yaw in rad) in a straight line in
        position, in duration s or at the plate speed speed m/s (neither: 2 s).  The controller
        validates the whole path before the first step.  Returns the planned duration (s, after
        any stretching to the slide limits); wait: until at rest.  A KeyboardInterrupt (Ctrl-C) while
        it waits stops the robot (STOP, then waits until at rest; a second one sends ESTOP) before
        it is raised."""
        if duration is not None and speed is not None:
            raise ValueError("give duration or speed, not both")
        kind = "speed" if speed is not None else "duration"
        value = speed if speed is not None else (2.0 if duration is None else duration)
        try:
            value = float(value)
        except (TypeError, ValueError):
            raise ValueError(f"{kind} {value!r} is not a number") from None
        lo, hi = _field("MOVE_COMMIT", "value")[3:5]
        per = _P.UM_PER_M if kind == "speed" else _P.MS_PER_S  # MOVE_COMMIT's value: um/s or ms
        raw = _round_away(value * per) if math.isfinite(value) else 0
        if not lo <= raw <= hi:
            raise ValueError(f"{kind} must be {lo / per:g} to {hi / per:g} {'m/s' if kind == 'speed' else 's'}")
        p = _pose_raw(pose)

        def start():
            with self._cmd_lock:
                seq = (self._fresh_status().last_seq + 1) & 0xFF
                self._send_pose(seq, p)
                mark = self._mark()
                ack = self._command("MOVE_COMMIT", seq=seq, kind=_enum_value("move_kind", kind), value=raw)
                self.last_move = self._move_info(mark, seq)
            return ack["detail"] / _P.MS_PER_S
        return self._motion(start, "moving", wait)

    def _move_info(self, mark, seq):
        """The MOVE_INFO of the move committed under seq (it follows the ACK), or None from a
        controller that sends none."""
        def pick():
            for serial, name, v in self._answers:
                if serial > mark and name == "MOVE_INFO" and v["seq"] == seq:
                    return MoveInfo(_enum("move_start", v["start"]), _enum("move_bound", v["bound"]), v["slide"],
                                    v["demand"] / _P.PER_MILLE)
            return None
        try:
            return self._wait_for(pick, min(self.timeout, 0.3), "MOVE_INFO")
        except Timeout:
            return None

    def _pose_frames(self, seq, raw):
        return [encode("POSE_A", self.node, seq=seq, x=raw[0], y=raw[1]),
                encode("POSE_B", self.node, seq=seq, z=raw[2], roll=raw[3]),
                encode("POSE_C", self.node, seq=seq, pitch=raw[4], yaw=raw[5])]

    def _send_pose(self, seq, raw):
        self._send_frames(self._pose_frames(seq, raw))

    def trajectory(self, rows, progress=None):
        """Streams a timed path: rows of (t, x, y, z, roll, pitch, yaw), t in s from the moment the
        controller starts the trajectory (once it holds traj_lead of it; the plate at rest where it
        is until then), and waits until the robot is at rest on the last row.  Returns Streamed
        (rows, seconds, rows per second, and rows per second until the controller's queue filled).

        Every row is checked before anything is sent: its values (ValueError naming the row), then
        the whole path by the controller's own validator, tsectl's (libtse_kin.so), from the
        controller's parameters, rates (info(); the built-in ones, with a warning, from a firmware
        older than INFO), pose and slides: a row it would refuse raises Rejected with .row
        and nothing is sent.  Rows then stream with the controller's flow control, several in
        flight.  progress(taken, total) is called as each row is acknowledged.  The rule is
        tsectl's: the path runs to its last row, or (a row refused, an exception such as
        KeyboardInterrupt) the robot is stopped with STOP and waited for before the error is raised
        (Rejected with .row for a refused row); a trajectory the controller ended itself (a STOP
        from elsewhere, a fault, an underrun, an e-stop) raises Ended once the robot is at rest.
        No part of a path is left running."""
        rows = [tuple(r) for r in rows]
        if not rows:
            raise ValueError("a trajectory needs at least one row")
        lo_dt, hi_dt = _field("TRAJ_COMMIT", "dt")[3:5]
        plan, prev_us = [], 0
        for i, r in enumerate(rows):
            if len(r) != 7:
                raise ValueError(f"row {i}: {len(r)} values, expected 7 (t, x, y, z, roll, pitch, yaw)")
            try:
                t = float(r[0])
                pose = _pose_raw(r[1:])
            except ValueError as e:
                raise ValueError(f"row {i}: {e}") from None
            if not math.isfinite(t):
                raise ValueError(f"row {i}: t = {r[0]!r} is not a finite time")
            us = _round_away(t * _P.US_PER_S)  # the wire's whole microseconds, as tsectl rounds them
            if not lo_dt <= us - prev_us <= hi_dt:
                raise ValueError(f"row {i}: t = {t:g} s is {(us - prev_us) / _P.US_PER_S:g} s after the "
                                 f"{'previous row' if i else 'start'}; it must be {lo_dt / _P.US_PER_S:g} to "
                                 f"{hi_dt / _P.US_PER_S:g} s")
            plan.append((us - prev_us, pose))
            prev_us = us
        with self._cmd_lock:
            st = self._fresh_status()
            if st.state != "idle" or not st.homed:
                raise TseError(f"not started: a trajectory starts at rest from a homed, enabled controller, and node "
                               f"{self.node} is {st.state}{'' if st.homed else ' and not homed'}")
            self._check_path(plan, rows)
            try:
                return self._stream(plan, rows, self._fresh_status(), progress)
            except Ended:
                raise
            except BaseException:
                self._stop_at_rest()
                raise

    def path(self, waypoints, t=None, v=None, period=0.02, blend=0.0, progress=None):
        """Plans a path through waypoints ((n, 6): x, y, z, roll, pitch, yaw) from where the plate is,
        against the controller's own parameters and rates (read first; info()), with tse.plan
        (tsectl path's planner; t, v, period and blend as tse.plan.plan takes them), then streams it
        with trajectory().
        The path starts at the plate's pose: the first waypoint takes its place when it is within
        10 um (and 10 urad) of it, otherwise the path goes to it first.  Returns (Plan, Streamed);
        a path the planner refuses raises tse.plan.PlanError and nothing is sent.  Needs numpy."""
        from . import plan as _plan
        np = _plan.np
        wp = np.asarray(waypoints, dtype=float)
        if wp.ndim != 2 or wp.shape[1] != 6 or len(wp) < 1:
            raise ValueError(f"waypoints must be an (n, 6) array of x, y, z, roll, pitch, yaw; got shape {wp.shape}")
        n = len(wp)
        tt = None if t is None else np.array(np.broadcast_to(np.asarray(t, dtype=float), (n,)))
        vv = None if v is None else np.array(np.broadcast_to(np.asarray(v, dtype=float), (n,)))
        params = self.params.raw()
        rates = self._rates()
        with contextlib.closing(self.watch(timeout=1.0)) as w:
            tel = next((x for x in w if x.pose is not None), None)
        if tel is None:
            raise TseError(f"no telemetry from node {self.node} (telemetry_ms is 0?): a path is planned from where "
                           "the plate is")
        here = np.asarray(tel.pose, dtype=float)
        d = np.abs(here - wp[0])
        d[3:] = np.abs(np.remainder(d[3:] + math.pi, 2 * math.pi) - math.pi)
        if d.max() <= 10e-6:
            wp = wp.copy()
            wp[0] = here
            if tt is not None:
                tt[0] = math.nan
        else:
            wp = np.vstack([here, wp])
            if tt is not None:
                tt = np.concatenate([[math.nan], np.where(tt[:1] == 0.0, math.nan, tt[:1]), tt[1:]])
            if vv is not None:
                vv = np.concatenate([[math.nan], vv])
        p = _plan.plan(wp, tt, vv, params, period, blend, rates=rates)
        return p, self.trajectory(p.rows.tolist(), progress)

    def _check_path(self, plan, rows):
        """tsectl's check of the whole path before sending (tse_py_traj_check, the controller's
        validator), from the controller's parameters, rates, pose and slides; Rejected names the row."""
        params = self.params.raw()
        rates = self._rates()
        with contextlib.closing(self.watch(timeout=1.0)) as w:
            tel = next((t for t in w if t.pose is not None), None)
        if tel is None:
            warnings.warn(f"no telemetry from node {self.node} (telemetry_ms is 0?), so the path cannot be checked "
                          "from where the robot is before sending; the controller checks each row as it comes",
                          stacklevel=3)
            return
        r = _check_rows(params, rates, tel.pose, tel.slides, plan)
        if r is None:
            raise TseError(f"node {self.node}'s parameters give no valid geometry at its rates (a firmware mismatch?)")
        row, reject = r
        if row is not None:
            raise Rejected(reject, row=row, prefix=f"row {row} (t = {rows[row][0]:g} s) would be refused; nothing "
                                                   "was sent: ")

    def _stream(self, plan, rows, st, progress):
        """Sends the rows as ACK and STATUS report room, up to TRAJ_WINDOW of them in flight, and
        reads their answers as they come (in order, as the controller sends them); a row refused
        queue_full is sent again, with the rows after it (refused order meanwhile), once there is
        room.  Then waits until at rest."""
        n, ident = len(plan), (st.last_seq + 1) & 0xFF
        function = _P.MESSAGES["TRAJ_COMMIT"][0]
        nxt, taken, flight, credit, resend = 0, 0, [], st.queue_free, None
        ended, ended_row, refusal = False, None, None
        with self._cond:
            self._traj_end = None
        t_first = t_last = None
        full = None  # (rows taken, time) when the queue first filled
        t_answer = time.monotonic()
        with self._reading():
            while taken < n:
                while not ended and resend is None and nxt < n and len(flight) < _P.TRAJ_WINDOW and credit > 0:
                    seq, (dt, pose) = (ident + nxt) & 0xFF, plan[nxt]
                    flags = (_P.TRAJ_FIRST if nxt == 0 else 0) | (_P.TRAJ_LAST if nxt == n - 1 else 0)
                    self._send_frames(self._pose_frames(seq, pose) +
                                      [encode("TRAJ_COMMIT", self.node, seq=seq, dt=dt, flags=flags, traj=ident)])
                    now = time.monotonic()
                    if not flight:
                        t_answer = now
                    if nxt == 0:
                        t_first = now
                    flight.append(nxt)
                    nxt, credit = nxt + 1, credit - 1
                ended = ended or self._ended_by(ident) is not None
                if ended and not flight:
                    break
                got = self._read_one(0.05)
                name, v = got if got is not None else (None, None)
                if name in ("ACK", "REJECT") and v["function"] == function and flight and \
                        v["seq"] == (ident + flight[0]) & 0xFF:
                    i = flight.pop(0)
                    t_answer = time.monotonic()
                    if name == "ACK":
                        taken, t_last, credit = taken + 1, t_answer, v["queue_free"] - len(flight)
                        if v["queue_free"] == 0 and full is None:
                            full = taken, t_answer
                        if progress is not None:
                            progress(taken, n)
                        continue
                    reason = _enum("reason", v["reason"])
                    if reason == "queue_full" and resend is None:
                        resend, credit = i, 0  # a report was behind: the rows after it are refused "order"
                    elif reason == "order" and resend is not None:
                        pass
                    elif reason == "ended":
                        ended = True
                        if ended_row is None:
                            ended_row, refusal = i, v
                    else:
                        raise Rejected(v, row=i, prefix=f"row {i} (t = {rows[i][0]:g} s) was refused by the controller: ")
                    if resend is not None and not flight:
                        nxt, resend = resend, None
                elif name == "STATUS":
                    credit = v["queue_free"] - len(flight)  # rows in flight take slots it does not know of yet
                    if _enum("state", v["state"]) in ("fault", "estop") and taken > 0:
                        ended = True  # its TRAJ_END says how, if it came
                if flight and time.monotonic() - t_answer > self.timeout:
                    raise Timeout(f"no answer to row {flight[0]} from node {self.node} within {self.timeout:g} s")
        if taken < n:
            self._raise_ended(ident, rows, taken, ended_row, refusal, t_first, t_last)
        seconds = t_last - t_first
        fill = (full[0] - 1) / (full[1] - t_first) if full and full[0] > 1 and full[1] > t_first else None
        done = Streamed(n, seconds, (n - 1) / seconds if seconds > 0 else 0.0, fill)
        try:
            self._wait_rest(max(sum(dt for dt, _ in plan) / _P.US_PER_S - seconds, 0.1), "finishing")
        except Fault:
            if self._ended_by(ident) is None:
                raise
        if self._ended_by(ident) is not None:
            self._raise_ended(ident, rows, taken, ended_row, refusal, t_first, t_last, at_rest=True)
        return done

    def _ended_by(self, ident):
        """This trajectory's TRAJ_END, when it says the trajectory ended before its last row."""
        end = self._traj_end
        if end is not None and end["traj"] == ident and _enum("traj_end", end["ended"]) != "done":
            return end
        return None

    def _raise_ended(self, ident, rows, taken, ended_row, refusal, t_first, t_last, at_rest=False):
        """Waits until at rest (the controller is stopping already), then raises Ended as tsectl
        words it."""
        if not at_rest:
            try:
                self._wait_rest(0, "stopping")
            except Fault:
                pass  # at rest in fault: the end says which
        end, n = self._ended_by(ident), len(rows)
        if end is not None:
            how, fault, row = _enum("traj_end", end["ended"]), _enum("fault", end["fault"]), end["rows"]
        elif refusal is not None:
            how, fault, row = _enum("traj_end", refusal["field"] & 15), _enum("fault", refusal["field"] >> 4), ended_row
        else:
            how, fault, row = "none", "none", taken
        what = ("was stopped by a STOP that this client did not send (another terminal or program)" if how == "stop"
                else "ran out of path at the controller (underrun): the host fell behind" if fault == "underrun"
                else "was ended by an e-stop" if fault == "estop"
                else f"was ended by a {fault} fault" if how == "fault" else "was ended by the controller")
        if row < n:
            text = f"the trajectory {what} after {row} of {n} rows; row {row} (t = {rows[row][0]:g} s) was not taken"
        else:
            text = (f"the trajectory {what} before it reached its last row (t = {rows[-1][0]:g} s); all {n} rows had "
                    "been taken")
        late = None
        if refusal is not None and ended_row == row:
            text += f"; row {row} was refused: {reject_words(refusal)}"
            late = refusal["where"] * 1e-3 if fault == "underrun" else None
        elif fault == "underrun":
            text += f"; row {row} had not been sent when the controller needed it"
        if fault == "underrun" and taken > 1 and t_last is not None and t_last > t_first:
            text += (f"; streaming reached {(taken - 1) / (t_last - t_first):.0f} rows/s, the rows come "
                     f"{n / rows[-1][0]:.0f} per second")
        st = self._status
        raise Ended(text, how, fault, row if row < n else None, late, st.state if st is not None else None)

    def _stop_at_rest(self):
        self._halt()

    def watch(self, timeout=None, maxlen=1000):
        """An iterator of Telemetry, one per telemetry period, from now on.  It ends when none
        has come for timeout s (None: never) or the controller is closed.  Up to maxlen periods wait while the caller is
        busy; beyond that the newest are dropped."""
        q = queue.Queue(maxsize=maxlen)
        self._tel_epoch += 1
        self._watchers.append(q)
        self._filter_telemetry()
        try:
            last = time.monotonic()
            while not self._closed:  # a closed controller ends its watches
                try:
                    item = q.get(timeout=0.2)
                except queue.Empty:
                    if timeout is not None and time.monotonic() - last > timeout:
                        return
                    continue
                last = time.monotonic()
                yield item
        finally:
            self._watchers.remove(q)
            self._filter_telemetry()

    def _filter_telemetry(self):
        """Telemetry through the bus's filter only while someone watches (a bus this object opened)."""
        if self._own_bus and not self._closed:
            with contextlib.suppress(_pycan.CanError, OSError, ValueError):
                self._bus.set_filters(self._filters_all if self._watchers else self._filters_quiet)

    # -- parameters (ctl.params) --
    def _param_value(self, mark, pid):
        def pick():
            for serial, name, v in self._answers:
                if serial > mark and name == "PARAM_VALUE" and v["param"] == pid:
                    return v["value"]
            return None
        return self._wait_for(pick, self.timeout, f"PARAM_VALUE of {_param_name(pid)}")

    def _param_exchange(self, message, **values):
        with self._cmd_lock:
            mark, name, v = self._exchange(message, **values)
            if name == "REJECT":
                raise Rejected(v)
            return self._param_value(mark, values["param"]) if "param" in values else None


class _Params:
    """ctl.params: the controller's parameters in SI (m, rad, m/s, ratios; NAME_deg in degrees;
    names with a unit suffix in that unit), as tsectl params reads and writes them.

        ctl.params["slide_vmax"]            -> 0.15
        ctl.params["slide_vmax"] = 0.14     (only while disabled or in fault)
        ctl.params.dump()                   -> {name: value} of every parameter
        ctl.params.raw()                    -> [wire integer of every parameter, by id]
        ctl.params.save()                   (non-volatile store)
    A name the table does not know, or a value outside its range, is a ValueError naming the
    parameter and the range (nothing is sent); a set the controller refuses raises Rejected."""

    def __init__(self, ctl):
        self._ctl = ctl

    @staticmethod
    def names():
        """Every spelling a parameter may be given by."""
        return list(_P.PARAM_SPELLINGS)

    @staticmethod
    def _key(name):
        key = _P.PARAM_SPELLINGS.get(str(name).lower())
        if key is None:
            raise ValueError(f"unknown parameter {name!r} (names: {', '.join(p[0] for p in _P.PARAMS)})")
        return key

    def get(self, name):
        pid, per_unit, _unit = self._key(name)
        return self._ctl._param_exchange("PARAM_GET", param=pid) / per_unit

    def set(self, name, value):
        """Sets one parameter; returns the value the controller now holds (SI)."""
        pid, per_unit, unit = self._key(name)
        pname, _wu, lo, hi, _def, _doc = _P.PARAMS[pid]
        try:
            v = float(value)
        except (TypeError, ValueError):
            raise ValueError(f"{name} = {value!r} is not a number") from None
        raw = _round_away(v * per_unit) if math.isfinite(v) else None
        if raw is None or not lo <= raw <= hi:
            u = f" {unit}" if unit else ""
            raise ValueError(f"{name} = {value!r}{u} is outside {lo / per_unit:.15g}..{hi / per_unit:.15g}{u}")
        return self._ctl._param_exchange("PARAM_SET", param=pid, value=raw) / per_unit

    def save(self):
        """Stores the running set in the controller's non-volatile memory."""
        magic = _field("PARAM_SAVE", "magic")[3]
        self._ctl._param_exchange("PARAM_SAVE", magic=magic)

    def dump(self):
        return {p[0]: self.get(p[0]) for p in _P.PARAMS}

    def raw(self):
        """Every parameter as it travels (its wire integer), in parameter-id order: the set
        tse.plan.plan and the path checks take."""
        return [self._ctl._param_exchange("PARAM_GET", param=pid) for pid in range(len(_P.PARAMS))]

    def __getitem__(self, name):
        return self.get(name)

    def __setitem__(self, name, value):
        self.set(name, value)
