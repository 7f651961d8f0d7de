"""tse.can's trajectory() on the host, against a fake controller (fake_controller.py): the whole
path checked before anything is sent by the controller's own validator, tsectl's (a row it would
refuse is refused naming the row, and nothing is sent); then streaming with several rows in flight
within the room the controller reports, rows refused queue_full and order sent again in order; and
a trajectory a STOP from elsewhere ended, named as such.  Against tse-sim: tests_sim, in the VM."""
import os

import can as pycan
import pytest

from tse import _protocol as P
from tse import can as tcan

from fake_controller import FakeController, Recorder, home_pose


@pytest.fixture
def rig(request):
    """(controller, fake, spy): a Controller and a FakeController on one virtual bus, and a spy
    recording every frame in bus order.  The fake's options come from the test's parameter."""
    channel = f"tse-traj-{os.getpid()}-{request.node.name}"
    fake = FakeController(channel, **getattr(request, "param", {}))
    ctl_bus = pycan.Bus(interface="virtual", channel=channel, receive_own_messages=False)
    spy_bus = pycan.Bus(interface="virtual", channel=channel)
    spy = Recorder()
    notifier = pycan.Notifier(spy_bus, [spy], timeout=0.01)
    ctl = tcan.Controller(node=3, timeout=2.0, heartbeat=False, bus=ctl_bus)
    yield ctl, fake, spy
    ctl.close()
    notifier.stop()
    spy_bus.shutdown()
    ctl_bus.shutdown()
    fake.close()


def rise(n, dt=0.02, dz=0.001):
    """n rows dt apart from the home pose: a rise of dz in Z, minimum-jerk (slides at a few mm/s,
    their speed changing by a fraction of a mm/s per row)."""
    p0, rows = home_pose(), []
    for i in range(n):
        s = i / (n - 1)
        e = s * s * s * (10 - 15 * s + 6 * s * s)
        rows.append((dt * (i + 1), p0[0], p0[1], p0[2] + dz * e, *p0[3:]))
    return rows


def to_controller(f):
    try:
        return tcan.decode(f, "to_controller")
    except tcan.DecodeError:
        return None


def test_a_row_the_controller_would_refuse_is_refused_before_anything_is_sent(rig):
    ctl, fake, spy = rig
    # A gentle rise of 30 rows, 9 rows of hold, then row 39 jumps 5 mm in X in 20 ms: the plate at
    # 0.25 m/s from rest, far beyond any slide's speed limit (0.15 m/s) and acceleration (a slide's
    # speed may change by about 1 cm/s a row).  Only that row can be refused, by construction.
    rows = rise(30) + [(0.6 + 0.02 * (i + 1), *rise(30)[-1][1:]) for i in range(9)]
    jump = list(rows[-1])
    jump[0] += 0.02
    jump[1] += 0.005
    rows.append(tuple(jump))
    rows += [(jump[0] + 0.02 * (i + 1), *jump[1:]) for i in range(5)]
    with pytest.raises(tcan.Rejected) as e:
        ctl.trajectory(rows)
    r = e.value
    print(r)
    assert (r.row, r.command, r.reason) == (39, "TRAJ_COMMIT", "timing")
    assert str(r).startswith("row 39 (t = 0.8 s) would be refused; nothing was sent: rejected: timing: TRAJ_COMMIT: ")
    names = {to_controller(f)[0] for f in spy.frames if to_controller(f)}
    assert not names & {"POSE_A", "POSE_B", "POSE_C", "TRAJ_COMMIT", "STOP"}, names
    assert fake.answers == []


@pytest.mark.parametrize("rig", [{"capacity": 6, "over_report": 3}], indirect=True)
def test_rows_stream_in_order_within_the_window_when_reports_are_behind(rig):
    ctl, fake, spy = rig
    rows = rise(40)
    seen = []
    done = ctl.trajectory(rows, progress=lambda taken, total: seen.append(taken))
    print(done, [a for a in fake.answers if a[1] != "ACK"][:6])
    assert done.rows == 40 and done.rows_per_s > 0
    assert seen == list(range(1, 41))
    # Every row taken once, in order, as sent: the file's poses in micrometres.
    want = [{"x": round(r[1] * 1e6), "y": round(r[2] * 1e6), "z": round(r[3] * 1e6), "roll": 0, "pitch": 0, "yaw": 0}
            for r in rows]
    assert fake.taken == want
    reasons = {a[1] for a in fake.answers}
    assert {"queue_full", "order"} <= reasons, "the reports overstated the room: rows were sent again"
    # Never more than TRAJ_WINDOW rows in flight, in the bus's own order.
    fn, in_flight, most = P.MESSAGES["TRAJ_COMMIT"][0], 0, 0
    for f in spy.frames:
        d = to_controller(f)
        if d and d[0] == "TRAJ_COMMIT":
            in_flight += 1
            most = max(most, in_flight)
            continue
        h = tcan.decode(f) if not d else None
        if h and h[0] in ("ACK", "REJECT") and h[2]["function"] == fn:
            in_flight -= 1
    assert 1 < most <= P.TRAJ_WINDOW


@pytest.mark.parametrize("rig", [{"stop_after": 10}], indirect=True)
def test_a_stop_from_elsewhere_is_named_and_not_answered_with_a_stop(rig):
    ctl, fake, spy = rig
    with pytest.raises(tcan.Ended) as e:
        ctl.trajectory(rise(40))
    r = e.value
    print(r)
    assert (r.ended, r.fault, r.row) == ("stop", "none", 10)
    assert str(r).startswith("the trajectory was stopped by a STOP that this client did not send (another terminal "
                             "or program) after 10 of 40 rows; row 10 (t = 0.22 s) was not taken")
    assert "rejected: ended: TRAJ_COMMIT: its trajectory was ended by a STOP" in str(r)
    assert not any(to_controller(f) and to_controller(f)[0] == "STOP" for f in spy.frames)


def sweep_x(dist=0.06, seconds=1.0, n=100):
    """n rows over `seconds` from the home pose: dist along X, minimum-jerk.  Its slides reach a speed
    between the step generator's limits at 100 kHz and at 200 kHz step interrupts with the default
    parameters, 0.9 x (100 - 2) and 0.9 x (200 - 2) steps per 1 ms segment at 1.28M steps/m (0.0689
    and 0.1392 m/s): what the controller's rates decide."""
    p0, rows = home_pose(), []
    for i in range(n):
        s = (i + 1) / n
        e = s * s * s * (10 - 15 * s + 6 * s * s)
        rows.append((seconds * s, p0[0] + dist * e, *p0[1:]))
    return rows


def test_info_is_the_controllers_answer(rig):
    ctl, _fake, spy = rig
    assert ctl.info() == tcan.Info((9, 8, 7), 200000, 1000)
    asked = [to_controller(f) for f in spy.frames if to_controller(f) and to_controller(f)[0] == "INFO_GET"]
    assert [a[2] for a in asked] == [{"page": 0}]


def test_the_check_is_at_the_controllers_rates(rig):
    ctl, fake, spy = rig
    rows = sweep_x()
    done = ctl.trajectory(rows)  # 200 kHz steps (the fake's INFO): within the step generator's limit
    assert done.rows == len(rows)
    fake.info = ((9, 8, 7), 100000, 1000)  # the same rows for a controller at 100 kHz
    before = len(fake.answers)
    with pytest.raises(tcan.Rejected) as e:
        ctl.trajectory(rows)
    r = e.value
    print(r)
    assert (r.command, r.reason, r.limit) == ("TRAJ_COMMIT", "timing", "step_generator")
    assert "would be refused; nothing was sent" in str(r)
    assert len(fake.answers) == before


@pytest.mark.parametrize("rig", [{"info": None}], indirect=True)
def test_a_firmware_older_than_info_is_judged_at_the_built_in_rates(rig):
    ctl, fake, _spy = rig
    with pytest.raises(tcan.Rejected) as e:
        ctl.info()
    assert e.value.reason == "unknown" and e.value.command == "INFO_GET"
    # The check still runs, at the built-in rates, and says so: a jump is refused before sending.
    p0 = home_pose()
    rows = [(0.02, *p0), (0.04, p0[0] + 0.005, *p0[1:])]
    with pytest.warns(UserWarning, match="does not know INFO_GET .* built-in rates, 200000 Hz step interrupts and "
                                         "1000 Hz control segments"):
        with pytest.raises(tcan.Rejected) as e:
            ctl.trajectory(rows)
    assert e.value.reason == "timing" and fake.answers == []
