"""tse.plan: waypoints to a trajectory the controller accepts, near the fastest its slides allow.

The planner of `tse-kin plan` (planner/ in C, docs in planner/include/plan/plan.h) through ctypes,
from libtse_kin.so: the same path (a spline through every waypoint, or straight pieces with their
corners cut by at most `blend` metres), the same time law against the controller's own limits, and
the same check of the rows by the controller's validator before they are returned.

    import numpy as np
    from tse import plan
    k = np.arange(13) * 2 * np.pi / 12
    wp = np.column_stack([0.05 * np.cos(k) - 0.05, 0.05 * np.sin(k), np.full(13, 1.0), np.zeros((13, 3))])
    p = plan.plan(wp)
    p.rows          # (n, 7): t, x, y, z, roll, pitch, yaw, what Controller.trajectory streams
    p.duration, p.near_share

Parameters are the controller's raw set (its wire integers in parameter-id order, as PARAM_GET
reads them, tse.can.Controller.params.raw()); None plans with the controller's defaults.  Rates are
the controller's (step_hz, segment_hz) as tse.can.Controller.info() reports them; None plans for a
controller at the built-in ones.
"""

import ctypes
import math
from collections import namedtuple

from ._needs import need

np = need("numpy", "python3-numpy", "tse.plan")

from . import _native
from . import _protocol as _P

__all__ = ["Plan", "PlanError", "plan", "default_params", "built_in_rates"]


class PlanError(ValueError):
    """The planner refused: a waypoint (counted from 1) or the path between two outside the
    workspace, a time it cannot keep, bad input; the message is tse-kin plan's."""


class Plan(namedtuple("Plan", "rows duration v_peak a_peak v_limit a_limit rows_mid rows_near retries")):
    """rows: (n, 7) array t, x, y, z, roll, pitch, yaw (the first holds the first waypoint traj_lead in);
    duration [s]; v_peak, a_peak: the worst slide speed and acceleration over their limits as the
    controller's validator measures the rows; v_limit [m/s], a_limit [m/s^2]: the limits;
    rows_mid: rows outside the first and last 5 % of the time, rows_near: of those, rows with some
    slide at 90 % or more of a limit; retries: the validator's refusals on the way (a stretch
    slowed each time)."""

    @property
    def near_share(self):
        """The share of rows_mid at 90 % or more of a limit."""
        return self.rows_near / self.rows_mid if self.rows_mid else 0.0


def default_params():
    """The controller's default parameter set, raw (its wire integers in parameter-id order)."""
    return [p[4] for p in _P.PARAMS]


def built_in_rates():
    """(step_hz, segment_hz): the controller's built-in rates, which plan() assumes without rates."""
    return _native.built_in_rates()


_f = None


def _fn():
    global _f
    if _f is None:
        dp = ctypes.POINTER(ctypes.c_double)
        _f = _native.load().tse_py_plan
        _f.restype = ctypes.c_long
        _f.argtypes = [ctypes.POINTER(ctypes.c_int), ctypes.c_int, ctypes.c_uint, ctypes.c_uint, ctypes.c_long, dp, dp,
                       dp, ctypes.c_double, ctypes.c_double, ctypes.c_double, ctypes.c_long, dp, dp, ctypes.c_char_p,
                       ctypes.c_size_t]
    return _f


def _column(a, n, what):
    if a is None:
        return None
    a = np.ascontiguousarray(np.broadcast_to(np.asarray(a, dtype=float), (n,)), dtype=float)
    return a


def plan(waypoints, t=None, v=None, params=None, period=0.02, blend=0.0, jerk=None, rates=None):
    """Plans a path through waypoints ((n, 6) array of x, y, z, roll, pitch, yaw in m and rad).

    t: the time each waypoint is passed [s] from the start (NaN where free; the first 0), or None;
    v: the plate's speed from each waypoint to the next at most [m/s] (NaN where none), or None;
    params: the controller's raw parameter set (None: its defaults); period: rows' spacing [s];
    blend: 0 for a smooth curve through every waypoint, else straight pieces whose corners are cut
    by at most that many metres; jerk: None (the controller bounds no trajectory's jerk), a limit for
    the slides [m/s^3], or "controller" for the one its own moves keep to; rates: the controller's
    (step_hz, segment_hz), as Controller.info() reports them (None: the built-in rates,
    built_in_rates()), which its slide speed limit and the span its acceleration is measured over
    follow.  Returns a Plan; raises PlanError with the planner's reason."""
    wp = np.ascontiguousarray(np.asarray(waypoints, dtype=float))
    if wp.ndim != 2 or wp.shape[1] != 6:
        raise ValueError(f"waypoints must be an (n, 6) array of x, y, z, roll, pitch, yaw; got shape {wp.shape}")
    n = wp.shape[0]
    tt, vv = _column(t, n, "t"), _column(v, n, "v")
    raw = default_params() if params is None else [int(x) for x in params]
    step_hz, segment_hz = _native.checked_rates(rates)
    if len(raw) != len(_P.PARAMS):
        raise ValueError(f"params: {len(raw)} values, the controller has {len(_P.PARAMS)}")
    if not (math.isfinite(period) and math.isfinite(blend)):
        raise ValueError("period and blend must be finite numbers")
    if jerk is None:
        jmax = 0.0
    elif isinstance(jerk, str):
        if jerk != "controller":
            raise ValueError(f"jerk: a limit in m/s^3, None or 'controller'; got {jerk!r}")
        jmax = -1.0
    else:
        jmax = float(jerk)
        if not (math.isfinite(jmax) and jmax > 0.0):
            raise ValueError(f"jerk: a limit in m/s^3 must be a positive finite number; got {jerk!r}")
    dp = ctypes.POINTER(ctypes.c_double)
    ptr = lambda a: None if a is None else a.ctypes.data_as(dp)
    c_params = (ctypes.c_int * len(raw))(*raw)
    stats = np.zeros(8)
    err = ctypes.create_string_buffer(1024)
    # Room for the rows: 20 s of the path at the period, and a row per waypoint; planned again with
    # the room it needs when longer.
    cap = int(20.0 / period) + n + 2
    for _attempt in range(2):
        rows = np.zeros((cap, 7))
        got = _fn()(c_params, len(raw), step_hz, segment_hz, n, ptr(wp), ptr(tt), ptr(vv), float(period), float(blend),
                    jmax, cap, ptr(rows), ptr(stats), err, len(err))
        if got == -2:
            raise RuntimeError("libtse_kin.so and tse/_protocol.py know different parameter tables: rebuild the library")
        if got < 0:
            raise PlanError(err.value.decode().removeprefix("plan: "))
        if got <= cap:
            d, vp, ap, vl, al, mid, near, retries = stats
            return Plan(rows[:got].copy(), d, vp, ap, vl, al, int(mid), int(near), int(retries))
        cap = got
    raise RuntimeError("the planner's row count changed between two calls")
