"""tse.can on the host, without a controller: its codec against the firmware's own (the frames
protogen packs with proto_encode), its REJECT wording against tsectl's, and arguments refused
before anything reaches the bus.  The client against tse-sim runs in the vcan harness
(tests/vcan, python_can.sh)."""
import math
import os
import subprocess
import sys
from pathlib import Path

import can as pycan
import pytest

from tse import _protocol as P
from tse import can as tcan

from fake_controller import Recorder

BUILD = Path(__file__).resolve().parents[2] / "build" / "host"


def tool(env, default):
    path = Path(os.environ.get(env) or BUILD / default)
    if not path.exists():
        pytest.fail(f"{path} not found: build the host preset, or set {env}")
    return str(path)


@pytest.fixture(scope="module")
def sample_frames():
    """protogen's sample frames: id, data, message and the values the C codec packed."""
    out = subprocess.run([tool("TSE_PROTOGEN", "host_tools/protogen/protogen"), "frames", "5"], check=True,
                         capture_output=True, text=True).stdout
    rows = []
    for line in out.splitlines():
        ident, data, name, *fields = line.split(",")
        rows.append((int(ident), bytes.fromhex(data), name, {k: int(v) for k, v in (f.split("=") for f in fields)}))
    return rows


def test_codec_reads_and_packs_the_firmware_frames(sample_frames):
    assert len(sample_frames) == 20 * len(P.MESSAGES)
    for ident, data, name, values in sample_frames:
        direction = P.MESSAGES[name][1]
        frame = pycan.Message(arbitration_id=ident, is_extended_id=False, data=data)
        assert tcan.decode(frame, direction) == (name, 5, values)
        packed = tcan.encode(name, 5, **values)
        assert (packed.arbitration_id, bytes(packed.data)) == (ident, data)


def test_codec_refuses_what_the_table_does_not_describe():
    with pytest.raises(ValueError, match=r"POSE_A\.x = 4000001 is outside \[-4000000, 4000000\]"):
        tcan.encode("POSE_A", 1, seq=0, x=4000001, y=0)
    with pytest.raises(ValueError, match=r"POSE_A has no field 'z'"):
        tcan.encode("POSE_A", 1, seq=0, x=0, y=0, z=0)
    with pytest.raises(ValueError, match=r"POSE_A\.y is missing"):
        tcan.encode("POSE_A", 1, seq=0, x=0)
    with pytest.raises(ValueError, match=r"node 16"):
        tcan.encode("STOP", 16, seq=0)
    status = tcan.encode("STATUS", 1, state=3, fault=0, flags=1, queue_depth=0, queue_free=64, last_seq=9, counter=1)
    short = pycan.Message(arbitration_id=status.arbitration_id, is_extended_id=False, data=bytes(status.data)[:7])
    with pytest.raises(tcan.DecodeError, match="STATUS is 8 bytes, this frame 7") as e:
        tcan.decode(short)
    assert e.value.reason == "bad_length"
    bad = bytearray(status.data)
    bad[0] = 99  # no such state
    with pytest.raises(tcan.DecodeError, match=r"STATUS\.state = 99") as e:
        tcan.decode(pycan.Message(arbitration_id=status.arbitration_id, is_extended_id=False, data=bytes(bad)))
    assert (e.value.reason, e.value.field) == ("range", "state")
    with pytest.raises(tcan.DecodeError) as e:
        tcan.decode(pycan.Message(arbitration_id=0x7F1, is_extended_id=False, data=b""))
    assert e.value.reason == "unknown"


def test_reject_words_are_tsectls_own():
    """tse.can words a REJECT with tsectl's text itself (reject_text.c in libtse_kin.so): every reason
    begins "rejected: <its wire name>:", and the fields are read as the wire defines them (slides in
    frame order A1, B1, A2, ...; the slide plus REJECT_LIMIT_STRIDE times the limit's code; where in
    thousandths of the limit)."""
    traj = P.MESSAGES["TRAJ_COMMIT"][0]
    for code, name in P.ENUMS["reason"].items():
        if code == 0:
            continue
        words = tcan.reject_words({"function": traj, "seq": 1, "reason": code, "scissor": 1, "kin_status": 0,
                                   "field": 0, "where": 0})
        assert words.startswith(f"rejected: {name}:"), words
    amax = next(c for c, (n, _w) in P.CODES["slide_limit"].items() if n == "slide_amax")
    words = tcan.reject_words({"function": traj, "seq": 1, "reason": next(c for c, n in P.ENUMS["reason"].items() if n == "timing"),
                               "scissor": 2, "kin_status": 0, "field": 3 + amax * P.REJECT_LIMIT_STRIDE,
                               "where": 1350})
    assert words.startswith("rejected: timing: TRAJ_COMMIT: slide A2 (scissor 2) would need 1.35 times"), words


def test_reject_words_without_the_library_name_the_reason():
    code = ("import tse.can as c, tse._protocol as P\n"
            "print(c.reject_words({'function': P.MESSAGES['MOVE_COMMIT'][0], 'seq': 1, 'reason': 4, 'scissor': 0,"
            " 'kin_status': 0, 'field': 1, 'where': 0}))")
    env = dict(os.environ, TSE_KIN_LIB="/nonexistent/libtse_kin.so")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True, env=env).stdout
    assert out.startswith("rejected: state: MOVE_COMMIT (fields [") and "no words" in out, out


def test_rejected_carries_the_reason_scissor_status_and_path_fraction():
    fn = P.MESSAGES["MOVE_COMMIT"][0]
    e = tcan.Rejected({"function": fn, "seq": 4, "reason": 8, "scissor": 2, "kin_status": 2, "field": 0, "where": 375})
    assert (e.command, e.reason, e.scissor, e.status, e.fraction) == ("MOVE_COMMIT", "kinematics", 2, "unreachable", 0.375)
    assert str(e).startswith("rejected: kinematics: MOVE_COMMIT: scissor 2 is unreachable at 37.5% of the path")
    e = tcan.Rejected({"function": fn, "seq": 4, "reason": 4, "scissor": 0, "kin_status": 0, "field": 1, "where": 0})
    assert (e.reason, e.state, e.scissor, e.status, e.fraction) == ("state", "disabled", None, None, None)


def test_rejected_names_the_limit_and_the_rule():
    traj = P.MESSAGES["TRAJ_COMMIT"][0]
    e = tcan.Rejected({"function": traj, "seq": 4, "reason": 14, "scissor": 2, "kin_status": 0, "field": 4 + 32,
                       "where": 1350})
    assert (e.reason, e.limit, e.rule, e.scissor) == ("timing", "step_generator", None, 2)
    assert "1.35 times its speed limit in effect, the step generator's, lower than slide_vmax" in str(e)
    e = tcan.Rejected({"function": traj, "seq": 4, "reason": 14, "scissor": 1, "kin_status": 0, "field": 1 + 16,
                       "where": 2000})
    assert e.limit == "slide_amax"
    pset = P.MESSAGES["PARAM_SET"][0]
    e = tcan.Rejected({"function": pset, "seq": 0, "reason": 12, "scissor": 0, "kin_status": 0, "field": 31,
                       "where": 8})
    assert (e.reason, e.rule, e.limit) == ("param_set", "pulse_low", None)
    assert str(e).startswith("rejected: param_set: step_pulse_ns: the STEP pulse (step_pulse_ns) must leave a low "
                             "time at least as long as itself")


class Recorder(pycan.Listener):
    def __init__(self):
        self.frames = []

    def on_message_received(self, msg):
        self.frames.append(msg)


@pytest.fixture
def quiet_controller():
    """A Controller on python-can's in-process virtual bus, with a listener on the same channel
    that records every frame it sends (nobody answers)."""
    channel = f"tse-test-{os.getpid()}"
    ctl_bus = pycan.Bus(interface="virtual", channel=channel, receive_own_messages=False)
    spy_bus = pycan.Bus(interface="virtual", channel=channel)
    rec = Recorder()
    notifier = pycan.Notifier(spy_bus, [rec], timeout=0.05)
    ctl = tcan.Controller(node=3, timeout=0.3, heartbeat=False, bus=ctl_bus)
    yield ctl, rec
    ctl.close()
    notifier.stop()
    spy_bus.shutdown()
    ctl_bus.shutdown()


def test_bad_arguments_send_nothing(quiet_controller):
    ctl, rec = quiet_controller
    with pytest.raises(ValueError, match=r"x = 4\.5 m is outside the wire's range -4\.\.4 m"):
        ctl.move([4.5, 0, 1, 0, 0, 0])
    with pytest.raises(ValueError, match="six numbers"):
        ctl.move([0, 0, 1])
    with pytest.raises(ValueError, match=r"yaw = nan rad"):
        ctl.move([0, 0, 1, 0, 0, math.nan])
    with pytest.raises(ValueError, match="duration must be 0.001 to 3600 s"):
        ctl.move([0, 0, 1, 0, 0, 0], duration=0)
    with pytest.raises(ValueError, match="not both"):
        ctl.move([0, 0, 1, 0, 0, 0], duration=1, speed=0.1)
    with pytest.raises(ValueError, match=r"row 1: t = 0\.0015 s is 0\.0005 s after the previous row"):
        ctl.trajectory([(0.001, 0, 0, 1, 0, 0, 0), (0.0015, 0, 0, 1, 0, 0, 0)])
    with pytest.raises(ValueError, match=r"row 0: roll = 4\.0 rad is outside"):
        ctl.trajectory([(0.5, 0, 0, 1, 4.0, 0, 0)])
    with pytest.raises(ValueError, match="unknown parameter 'slide_speed'"):
        ctl.params["slide_speed"] = 0.1
    with pytest.raises(ValueError, match=r"slide_vmax = 3 m/s is outside 0\.001\.\.[0-9.]+ m/s"):
        ctl.params["slide_vmax"] = 3
    with pytest.raises(ValueError, match="eta_deg = 'abc' is not a number"):
        ctl.params.set("eta_deg", "abc")
    assert rec.frames == []


def test_silence_is_a_timeout_and_the_heartbeat_beats(quiet_controller):
    ctl, rec = quiet_controller
    with pytest.raises(tcan.Timeout, match="no STATUS from node 3"):
        ctl.enable()
    ctl.start_heartbeat()
    import time
    time.sleep(0.35)
    ctl.stop_heartbeat()
    n = len(rec.frames)
    time.sleep(0.25)
    beats = [tcan.decode(f, "to_controller") for f in rec.frames]
    assert n >= 3 and len(rec.frames) == n, "the heartbeat beats every 100 ms and stops when told"
    assert [b[2]["counter"] for b in beats] == list(range(n)) and {b[:2] for b in beats} == {("HOST_HEARTBEAT", 3)}


def test_a_bus_that_cannot_be_opened_is_named():
    with pytest.raises(tcan.TseError, match=r"cannot open CAN channel 'tse-no-such-bus' \(socketcan\)"):
        tcan.Controller("tse-no-such-bus", node=1)
    with pytest.raises(ValueError, match="node 0 is not 1..15"):
        tcan.Controller("vcan0", node=0)


def test_watch_ends_on_silence_and_on_close(quiet_controller):
    import time
    ctl, _ = quiet_controller
    t0 = time.monotonic()
    assert list(ctl.watch(timeout=0.3)) == []
    assert time.monotonic() - t0 >= 0.3  # it waited the silence out, then ended
    w = ctl.watch()
    import threading
    threading.Timer(0.3, ctl.close).start()
    assert list(w) == []


def _send_period(bus, slides, pose, upto=6):
    """The controller's telemetry period (telemetry.c: SLIDES_A..C, then FK_A..C), its first upto frames."""
    raw_s, raw_p = [round(v * 1e9) for v in slides], [round(v * 1e6) for v in pose]
    frames = [tcan.encode(f"SLIDES_{c}", 3, **{f"s_a{k + 1}": raw_s[2 * k], f"s_b{k + 1}": raw_s[2 * k + 1]})
              for k, c in enumerate("ABC")]
    frames += [tcan.encode("FK_A", 3, x=raw_p[0], y=raw_p[1]), tcan.encode("FK_B", 3, z=raw_p[2], roll=raw_p[3]),
               tcan.encode("FK_C", 3, pitch=raw_p[4], yaw=raw_p[5])]
    for f in frames[:upto]:
        bus.send(f)


def test_a_watch_never_mixes_two_telemetry_periods(quiet_controller):
    """A watch that ends half way through a period (on the bus the socket's filter then stops the
    rest), and a new watch whose first frame is the last of a later period: the new watch's first
    sample is a whole period of its own, not the old period's slides and x, y, z, roll with the new
    pitch and yaw (what Controller.path once planned from: the pose before the last trajectory)."""
    import threading
    import time
    ctl, _ = quiet_controller
    sender = pycan.Bus(interface="virtual", channel=f"tse-test-{os.getpid()}")
    try:
        old_s, old_p = [0.1 * k for k in range(6)], [0.1, -0.05, 1.1, 0.1, -0.05, 0.2]
        new_s, new_p = [0.2 + 0.1 * k for k in range(6)], [0.12, -0.06, 1.1, 0.1, -0.05, 0.2]
        # Homed (the fake's flags): a period is published with its pose.
        sender.send(tcan.encode("STATUS", 3, state=tcan._enum_value("state", "idle"), fault=0, flags=3,
                                queue_depth=0, queue_free=32, last_seq=0, counter=0))
        w = ctl.watch(timeout=1.0)
        threading.Timer(0.1, lambda: (_send_period(sender, old_s, old_p), _send_period(sender, old_s, old_p, upto=5))).start()
        first = next(w)
        assert first.pose == pytest.approx(old_p) and first.slides == pytest.approx(old_s)
        time.sleep(0.3)  # the reader has taken the half period
        w.close()

        w = ctl.watch(timeout=1.0)
        # The rest of a period (its FK_C), then whole periods.
        tail = tcan.encode("FK_C", 3, pitch=round(new_p[4] * 1e6), yaw=round(new_p[5] * 1e6))
        threading.Timer(0.1, lambda: (sender.send(tail), _send_period(sender, new_s, new_p),
                                      _send_period(sender, new_s, new_p))).start()
        first = next(w)
        w.close()
        assert first.pose == pytest.approx(new_p) and first.slides == pytest.approx(new_s)
    finally:
        sender.shutdown()
