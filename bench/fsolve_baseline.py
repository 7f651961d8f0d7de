#!/usr/bin/python3
"""Baseline for the IK benchmark: scipy.optimize.fsolve on the contract's six constraint equations.

For every pose of a trajectory the ball joints C_i are computed (kinematics.md, "Top plate") and
fsolve solves F(q) = 0, the three scissors' F1 and F2, for q = (s_A1, s_B1, ..., s_B3):
  warm: seeded with the previous pose's solution (the first pose from home),
  cold: seeded with home (every slide at the vertical-axis solution for Z = L sin((a_min + a_max)/2),
        the same home as tse-kin's cold start).
fsolve is called as one normally would, with its own finite-difference Jacobian (the figures
`fsolve,warm_us` / `fsolve,cold_us`); it is also timed with the analytic Jacobian M (lines
`fsolve,analytic_warm_us` / `fsolve,analytic_cold_us`), which favours fsolve.

Trajectory (the same as `tse-kin bench`): pose k = 0..N-1 at t = 0.002 k,
  X = 0.15 sin t, Y = 0.12 sin 1.7t, Z = 1.0 + 0.3 sin 0.5t,
  roll = 0.08 sin 1.3t, pitch = 0.06 sin 0.9t, yaw = 0.2 sin 0.7t;
or, with --stdin, poses x,y,z,roll,pitch,yaw as CSV lines on standard input.

Timing: every solve is timed on its own (perf_counter_ns); the figure is the median over all poses
of all --repeats batches, in microseconds per 6-DOF inverse kinematics.  Before timing, fsolve's
answers are checked against the mpmath oracle (tests/oracle/tse_oracle.py) on a few poses.
With --tse-kin PATH it runs `PATH bench --n N` and prints the ratios fsolve / tse-kin (double).

fsolve's xtol is scipy's default (relative 1.5e-8: about 1e-9 m here, against tse-kin's ~1e-12 m);
--xtol 1e-13 makes it match tse-kin's accuracy, at some cost.

Usage: fsolve_baseline.py [--n 2000] [--repeats 5] [--stdin] [--xtol X] [--tse-kin PATH] [--check 8]
"""
import argparse
import math
import os
import statistics
import subprocess
import sys
import time

import numpy as np
from scipy.optimize import fsolve

# Prototype parameters (kinematics.md, "Design parameters").
L = 1.727
L0 = 0.2647 * L
ETA = math.radians(30.0)
R_ACT = 0.0186 * L
R_TOP = 0.11765 * L
ALPHA_MIN = math.asin(0.324 / L)
ALPHA_MAX = math.asin(1.619 / L)
G = (1.0 - (L / L0) ** 2) / 4.0
C2E = math.cos(2.0 * ETA)

BETA = np.array([0.0, 2.0 * math.pi / 3.0, 4.0 * math.pi / 3.0])
E_R = np.stack([np.cos(BETA), np.sin(BETA), np.zeros(3)], axis=1)     # rows: scissor i
E_T = np.stack([-np.sin(BETA), np.cos(BETA), np.zeros(3)], axis=1)
ORIGIN = R_ACT * E_R
DIR_A = math.cos(ETA) * E_T + math.sin(ETA) * E_R
DIR_B = -math.cos(ETA) * E_T + math.sin(ETA) * E_R


# Per scissor, as plain floats: slide origin O_i (x, y) and slide directions a_i, b_i (x, y).
FRAMES = [(float(ORIGIN[i, 0]), float(ORIGIN[i, 1]), float(DIR_A[i, 0]), float(DIR_A[i, 1]),
           float(DIR_B[i, 0]), float(DIR_B[i, 1]), math.cos(BETA[i]), math.sin(BETA[i])) for i in range(3)]
LL = L * L


def rotation(roll, pitch, yaw):
    """R = Rz(yaw) Ry(pitch) Rx(roll) (numpy; used by the checks, not in the timed loop)."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    rz = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
    ry = np.array([[cp, 0.0, sp], [0.0, 1.0, 0.0], [-sp, 0.0, cp]])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cr, -sr], [0.0, sr, cr]])
    return rz @ ry @ rx


def scissor_terms(pose):
    """u, v, rho2 of the three scissors (lists of 3 floats) for pose (X, Y, Z, roll, pitch, yaw).

    Plain Python floats: on 3-vectors they are several times faster than numpy, and the point is
    to time fsolve, not array overhead.  Only the first two columns of R are needed, since
    C_i = P + r_top (cos b_i R e_x + sin b_i R e_y)."""
    x, y, z, roll, pitch, yaw = (float(t) for t in pose)
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    n = (cy * cp, sy * cp, -sp)                                  # R e_x
    t = (cy * sp * sr - sy * cr, sy * sp * sr + cy * cr, cp * sr)  # R e_y
    us, vs, rs = [], [], []
    for ox, oy, ax, ay, bx, by, cb, sb in FRAMES:
        dx = x + R_TOP * (cb * n[0] + sb * t[0]) - ox
        dy = y + R_TOP * (cb * n[1] + sb * t[1]) - oy
        dz = z + R_TOP * (cb * n[2] + sb * t[2])
        us.append(dx * ax + dy * ay)
        vs.append(dx * bx + dy * by)
        rs.append(dx * dx + dy * dy + dz * dz)
    return us, vs, rs


def residual(q, u, v, rho2):
    """F1, F2 of scissors 1..3 (kinematics.md, "Constraint equations of one scissor")."""
    q = q.tolist()
    f = [0.0] * 6
    for i in range(3):
        sa, sb = q[2 * i], q[2 * i + 1]
        t = sa * sa - 2.0 * u[i] * sa
        f[2 * i] = t - sb * sb + 2.0 * v[i] * sb
        f[2 * i + 1] = t + rho2[i] - LL - G * (sa * sa + sb * sb + 2.0 * C2E * sa * sb)
    return f


def jacobian(q, u, v, rho2):
    """dF/dq: block diagonal, the 2x2 blocks M of the three scissors."""
    q = q.tolist()
    J = np.zeros((6, 6))
    for i in range(3):
        sa, sb = q[2 * i], q[2 * i + 1]
        J[2 * i, 2 * i] = 2.0 * (sa - u[i])
        J[2 * i, 2 * i + 1] = -2.0 * (sb - v[i])
        J[2 * i + 1, 2 * i] = 2.0 * (sa - u[i]) - 2.0 * G * (sa + C2E * sb)
        J[2 * i + 1, 2 * i + 1] = -2.0 * G * (sb + C2E * sa)
    return J


def home_slides():
    """Slides of the symmetric home (zero orientation, X = Y = 0, Z = L sin((a_min + a_max)/2)):
    the larger root of the quadratic F2(s, s) = 0 with F1 = 0 automatically (u = v there)."""
    u, v, rho2 = scissor_terms([0.0, 0.0, L * math.sin(0.5 * (ALPHA_MIN + ALPHA_MAX)), 0, 0, 0])
    # s^2 - 2us + rho2 - L^2 - G s^2 (2 + 2c) = 0
    a, b, c = 1 - 2 * G * (1 + C2E), -2 * u[0], rho2[0] - L * L
    return max((-b + sgn * math.sqrt(b * b - 4 * a * c)) / (2 * a) for sgn in (1, -1))


HOME = np.full(6, home_slides())


XTOL = 1.49012e-08  # scipy's default; --xtol changes it


def solve(pose, seed, analytic):
    u, v, rho2 = scissor_terms(pose)
    q, info, ier, _ = fsolve(residual, seed, args=(u, v, rho2), fprime=jacobian if analytic else None,
                             full_output=True, xtol=XTOL)
    return q, ier == 1


def trajectory(n):
    t = 0.002 * np.arange(n)
    return np.stack([0.15 * np.sin(t), 0.12 * np.sin(1.7 * t), 1.0 + 0.3 * np.sin(0.5 * t),
                     0.08 * np.sin(1.3 * t), 0.06 * np.sin(0.9 * t), 0.2 * np.sin(0.7 * t)], axis=1)


def on_physical_sheet(q, pose):
    """det M > 0 and positive slides for every scissor (the contract's branch)."""
    u, v, _ = scissor_terms(pose)
    J = jacobian(q, u, v, None)
    return all(np.linalg.det(J[2 * i:2 * i + 2, 2 * i:2 * i + 2]) > 0 for i in range(3)) and bool(np.all(q > 0))


def run(poses, warm, analytic, repeats):
    times, bad = [], 0
    for _ in range(repeats):
        seed = HOME
        for p in poses:
            t0 = time.perf_counter_ns()
            q, ok = solve(p, seed, analytic)
            times.append(time.perf_counter_ns() - t0)
            if warm:
                seed = q
            bad += not ok
    return statistics.median(times) / 1e3, statistics.fmean(times) / 1e3, bad


def check_against_oracle(poses, count):
    """Largest |q_fsolve - q_exact| over `count` poses spread along the trajectory, warm and cold."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "oracle"))
    import tse_oracle
    P = tse_oracle.Params()
    idx = np.linspace(0, len(poses) - 1, count).astype(int)
    worst, off_sheet = 0.0, 0
    seed = HOME
    for k in idx:
        exact = tse_oracle.solve(P, [float(x) for x in poses[k]])
        if exact.status != "ok":
            print(f"note: pose {k} is {exact.status},{exact.scissor} by the oracle; not compared")
            continue
        for s in (HOME, seed):
            q, ok = solve(poses[k], s, False)
            off_sheet += not on_physical_sheet(q, poses[k])
            worst = max(worst, max(abs(float(a) - float(b)) for a, b in zip(q, exact.q)))
        seed = q
    return worst, len(idx), off_sheet


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=2000, help="trajectory poses (default 2000, as tse-kin bench)")
    ap.add_argument("--repeats", type=int, default=5, help="batches over the trajectory (default 5)")
    ap.add_argument("--stdin", action="store_true", help="read poses as CSV from standard input")
    ap.add_argument("--check", type=int, default=8, help="poses checked against the mpmath oracle")
    ap.add_argument("--tse-kin", metavar="PATH", help="run PATH bench and print the speed ratios")
    ap.add_argument("--xtol", type=float, default=1.49012e-08, help="fsolve's xtol (default scipy's, 1.49012e-08)")
    a = ap.parse_args()
    globals()["XTOL"] = a.xtol

    if a.stdin:
        poses = np.array([[float(x) for x in line.split(",")] for line in sys.stdin if line.strip()])
    else:
        poses = trajectory(a.n)
    if a.check > 0:
        worst, n, off = check_against_oracle(poses, min(a.check, len(poses)))
        print(f"fsolve against the mpmath oracle on {n} poses (warm and cold): max |dq| {worst:.2e} m, "
              f"{off} solutions off the det M > 0 sheet")
        if worst > 1e-7 or off:
            print("warning: fsolve does not reproduce the oracle; the timing below compares unequal work")

    fig = {}
    for analytic in (False, True):
        tag = "analytic_" if analytic else ""
        label = "analytic Jacobian" if analytic else "finite-difference Jacobian (default)"
        for mode in ("warm", "cold"):
            med, mean, bad = run(poses, mode == "warm", analytic, a.repeats)
            fig[tag + mode] = med
            print(f"fsolve {mode}, {label}: median {med:.1f} us/pose, mean {mean:.1f} us/pose, "
                  f"{len(poses)} poses x {a.repeats} batches, {bad} solves not converged")
            print(f"fsolve,{tag}{mode}_us,{med:.2f}")

    if a.tse_kin:
        # Same answers? fsolve (warm, default Jacobian) against `tse-kin ik` on every pose.
        text = "".join(",".join(repr(float(x)) for x in p) + "\n" for p in poses)
        ik = subprocess.run([a.tse_kin, "ik"], input=text, capture_output=True, text=True, check=True)
        worst, seed, not_ok = 0.0, HOME, 0
        for p, line in zip(poses, ik.stdout.splitlines()):
            q, _ = solve(p, seed, False)
            seed = q
            f = line.split(",")
            if f[0] != "ok":
                not_ok += 1
                continue
            worst = max(worst, max(abs(x - float(y)) for x, y in zip(q, f[2:])))
        print(f"fsolve (warm) against tse-kin ik on the {len(poses)} poses: max |dq| {worst:.2e} m"
              + (f", {not_ok} poses not ok by tse-kin" if not_ok else ""))
        cmd = [a.tse_kin, "bench"] + ([] if a.stdin else ["--n", str(a.n)])
        out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
        tk = {}
        for line in out.splitlines():
            f = line.split(",")
            if len(f) == 3 and f[0] == "bench":
                tk[f[1]] = float(f[2])
        for mode in ("warm", "cold"):
            key = f"ik_double_{mode}_ns"
            if key not in tk:
                print(f"tse-kin bench printed no {key} line")
                continue
            ns = tk[key]
            for tag, label in (("", "default"), ("analytic_", "analytic Jacobian")):
                ratio = fig[tag + mode] * 1e3 / ns
                print(f"{mode}: fsolve ({label}) {fig[tag + mode]:.1f} us vs tse-kin double {ns:.1f} ns: "
                      f"{ratio:.0f}x")
                print(f"ratio,fsolve_{tag}{mode}_over_tse_kin_double,{ratio:.1f}")


if __name__ == "__main__":
    main()
