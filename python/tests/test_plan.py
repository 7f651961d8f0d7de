"""tse.plan: tse-kin plan's planner through libtse_kin.so (the same rows as tse-kin plan writes,
its refusals, the controller's parameters counted), and Controller.path against a fake controller
(the plan streamed from where the plate is, row for row).  The planner's own figures (durations
against the optimum, rows near a limit) are tests/planner's."""
import math
import os
import subprocess

import can as pycan
import numpy as np
import pytest

from tse import _protocol as P
from tse import can as tcan
from tse import plan

from fake_controller import FakeController, home_pose


def circle(n=12, r=0.05, z=1.0):
    k = np.arange(n + 1) * 2 * math.pi / n
    return np.column_stack([r * np.cos(k) - r, r * np.sin(k), np.full(n + 1, z), np.zeros((n + 1, 3))])


def test_the_rows_are_tse_kin_plans(tse_kin_cli, tmp_path):
    wp = circle()
    path = tmp_path / "circle.csv"
    path.write_text("x,y,z,roll,pitch,yaw\n" + "".join(",".join(repr(float(x)) for x in w) + "\n" for w in wp))
    out = subprocess.run([tse_kin_cli, "plan", str(path)], capture_output=True, text=True, check=True).stdout
    cli = np.array([[float(x) for x in line.split(",")] for line in out.splitlines() if line[:1].isdigit()])
    p = plan.plan(wp)
    assert p.rows.shape == cli.shape
    # tse-kin writes them as the wire carries them: whole microseconds and micrometres.
    assert np.array_equal(np.round(p.rows * 1e6), np.round(cli * 1e6))
    assert p.duration == pytest.approx(cli[-1, 0], abs=1e-6)
    assert p.v_peak <= 1 and p.a_peak <= 1 and p.near_share >= 0.6


def test_a_jerk_limit_is_tse_kin_plans(tse_kin_cli, tmp_path):
    """jerk="controller" plans as tse-kin plan --jerk controller does, a number as --jerk N; a bad
    limit is refused before anything is planned."""
    wp = circle()
    path = tmp_path / "circle.csv"
    path.write_text("x,y,z,roll,pitch,yaw\n" + "".join(",".join(repr(float(x)) for x in w) + "\n" for w in wp))
    for arg, jerk in (("controller", "controller"), ("25", 25.0)):
        out = subprocess.run([tse_kin_cli, "plan", "--jerk", arg, str(path)], capture_output=True, text=True,
                             check=True).stdout
        cli = np.array([[float(x) for x in line.split(",")] for line in out.splitlines() if line[:1].isdigit()])
        p = plan.plan(wp, jerk=jerk)
        assert np.array_equal(np.round(p.rows * 1e6), np.round(cli * 1e6))
        assert p.duration > plan.plan(wp).duration  # smoothed: longer
    for bad in (0.0, -1.0, math.inf, "slides"):
        with pytest.raises(ValueError, match="jerk"):
            plan.plan(wp, jerk=bad)


def test_refusals_name_the_waypoint():
    wp = np.array([[0, 0, 1.0, 0, 0, 0], [0, 0, 1.1, 0, 0, 0], [0, 0, 1.7, 0, 0, 0]])
    with pytest.raises(plan.PlanError, match="waypoint 3 is outside the workspace"):
        plan.plan(wp)
    with pytest.raises(plan.PlanError, match="waypoint 2: t = 0.1 s cannot be kept"):
        plan.plan(wp[:2], t=[0.0, 0.1])
    with pytest.raises(ValueError, match=r"\(n, 6\)"):
        plan.plan(wp[:, :5])


def test_the_parameters_given_are_planned_against():
    wp = np.array([[0, 0, 0.9, 0, 0, 0], [0, 0, 1.2, 0, 0, 0]])
    params = plan.default_params()
    fast = plan.plan(wp, params=params)
    params[[p[0] for p in P.PARAMS].index("slide_vmax")] //= 2
    slow = plan.plan(wp, params=params)
    assert slow.v_limit == pytest.approx(0.075)
    assert slow.duration > fast.duration + 0.1
    # A speed cap on the plate from the first waypoint: slower still.
    capped = plan.plan(wp, v=[0.1, math.nan])
    assert capped.duration > 0.3 / 0.1


def test_the_rates_given_are_planned_at():
    """A controller at 100 kHz step interrupts: its step generator allows 0.9 x (100 - 2) steps per
    1 ms segment (the DIR set-up of 5 us a tick, plus one) at 1.28M steps/m, 0.06890625 m/s, against
    the built-in rates' 0.9 x 198 steps, 0.13921875 m/s.  Rates no controller runs at are refused."""
    wp = np.array([[0, 0, 0.9, 0, 0, 0], [0, 0, 1.2, 0, 0, 0]])
    assert plan.built_in_rates() == (200000, 1000)
    fast = plan.plan(wp)
    slow = plan.plan(wp, rates=(100000, 1000))
    assert fast.v_limit == pytest.approx(0.13921875, abs=1e-12)
    assert slow.v_limit == pytest.approx(0.06890625, abs=1e-12)
    assert slow.duration > fast.duration + 0.1
    for bad in ((200000, 3000), (200500, 1000), (200000, 0), (2 ** 24, 1), "fast", (1, 2, 3)):
        with pytest.raises(ValueError, match="rates"):
            plan.plan(wp, rates=bad)


@pytest.fixture
def rig(request):
    channel = f"tse-plan-{os.getpid()}-{request.node.name}"
    fake = FakeController(channel)
    bus = pycan.Bus(interface="virtual", channel=channel, receive_own_messages=False)
    ctl = tcan.Controller(node=3, timeout=2.0, heartbeat=False, bus=bus)
    yield ctl, fake
    ctl.close()
    bus.shutdown()
    fake.close()


def test_path_plans_from_where_the_plate_is_and_streams_the_plan(rig):
    ctl, fake = rig
    h = home_pose()
    # The first waypoint 2 cm away from the plate: the path goes there first.
    wp = np.array([[h[0] + 0.02, h[1], h[2], 0, 0, 0], [h[0] + 0.02, h[1] + 0.02, h[2] + 0.01, 0, 0, 0.05]])
    p, done = ctl.path(wp)
    assert done.rows == len(p.rows)
    assert np.allclose(p.rows[0, 1:], h, atol=1e-6)  # the hold row: where the plate was
    assert np.allclose(p.rows[-1, 1:], wp[-1], atol=1e-6)
    taken = np.array([[fake.taken[i][k] for k in ("x", "y", "z", "roll", "pitch", "yaw")]
                      for i in range(len(fake.taken))]) * 1e-6
    assert np.allclose(taken, p.rows[:, 1:], atol=0.6e-6)


def test_path_is_planned_at_the_controllers_rates(rig):
    """Controller.path plans at the rates the controller's INFO reports."""
    ctl, fake = rig
    h = home_pose()
    wp = np.array([h, [h[0], h[1], h[2] + 0.1, 0, 0, 0]])
    fake.info = ((9, 8, 7), 100000, 1000)
    p, done = ctl.path(wp)
    assert p.v_limit == pytest.approx(0.06890625, abs=1e-12)
    assert done.rows == len(p.rows)


def test_the_controllers_raw_set_is_what_plan_takes(rig):
    """ctl.params.raw(), which plan's docstring names, reads every parameter's wire integer in
    id order: the fake controller answers the table's defaults, which are default_params()."""
    ctl, _fake = rig
    raw = ctl.params.raw()
    assert raw == plan.default_params()
    assert raw[[p[0] for p in P.PARAMS].index("slide_vmax")] == 150000  # um/s: 0.15 m/s
