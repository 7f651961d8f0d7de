"""The benchmark's baseline: scipy.optimize.fsolve on the same equations as tse-kin.

For each pose of the bench trajectory (the Lissajous of `tse-kin bench`), fsolve solves the six
constraint equations F(q) = 0 (three scissors' F1, F2 of kinematics.md) for q, given the ball
joints, with the analytic Jacobian; warm seeds it with the previous pose's solution, cold with
the home configuration.  With --tse-kin PATH it runs `PATH bench` and prints the speed ratios.
Its answers are checked against the mpmath oracle first, so the comparison is of correct solvers.
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

L, K1, K3, K4, ETA = 1.727, 0.2647, 0.0186, 0.11765, math.pi / 6
L0, R_ACT, R_TOP = K1 * L, K3 * L, K4 * L
G = (1 - (L / L0) ** 2) / 4
C2 = math.cos(2 * ETA)
BETA = [i * 2 * math.pi / 3 for i in range(3)]
ER = [np.array([math.cos(b), math.sin(b)]) for b in BETA]
ET = [np.array([-math.sin(b), math.cos(b)]) for b in BETA]
A = [math.cos(ETA) * ET[i] + math.sin(ETA) * ER[i] for i in range(3)]
B = [-math.cos(ETA) * ET[i] + math.sin(ETA) * ER[i] for i in range(3)]
HOME = 0.40293893420493  # the symmetric home configuration (tse-kin's no-seed start)


def trajectory(n):
    t = 0.002 * np.arange(n)
    return np.stack([0.15 * np.sin(t), 0.12 * np.sin(1.7 * t), 1.0 + 0.3 * np.sin(0.5 * t),
                     0.08 * np.sin(1.3 * t), 0.06 * np.sin(0.9 * t), 0.2 * np.sin(0.7 * t)], axis=1)


def joints(p):
    x, y, z, r, pi, yw = p
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(pi), math.sin(pi), math.cos(yw), math.sin(yw)
    c0 = np.array([cy * cp, sy * cp, -sp])
    c1 = np.array([cy * sp * sr - sy * cr, sy * sp * sr + cy * cr, cp * sr])
    return [np.array([x, y, z]) + R_TOP * (c0 * math.cos(b) + c1 * math.sin(b)) for b in BETA]


def scissor_terms(C):
    out = []
    for i in range(3):
        d = np.array([C[i][0] - R_ACT * ER[i][0], C[i][1] - R_ACT * ER[i][1], C[i][2]])
        out.append((d[:2] @ A[i], d[:2] @ B[i], d @ d))
    return out


def equations(q, terms):
    f = np.empty(6)
    for i, (u, v, rho2) in enumerate(terms):
        sa, sb = q[2 * i], q[2 * i + 1]
        f[2 * i] = sa * sa - 2 * u * sa - sb * sb + 2 * v * sb
        f[2 * i + 1] = sa * sa - 2 * u * sa + rho2 - L * L - G * (sa * sa + sb * sb + 2 * C2 * sa * sb)
    return f


def jacobian(q, terms):
    J = np.zeros((6, 6))
    for i, (u, v, _) in enumerate(terms):
        sa, sb = q[2 * i], q[2 * i + 1]
        J[2 * i, 2 * i], J[2 * i, 2 * i + 1] = 2 * (sa - u), -2 * (sb - v)
        J[2 * i + 1, 2 * i] = 2 * (sa - u) - 2 * G * (sa + C2 * sb)
        J[2 * i + 1, 2 * i + 1] = -2 * G * (sb + C2 * sa)
    return J


def solve(p, seed, analytic=True):
    """fsolve as one would call it: by default with its own finite-difference Jacobian; with
    analytic=True, given ours (which favours fsolve)."""
    terms = scissor_terms(joints(p))
    return fsolve(equations, seed, args=(terms,), fprime=jacobian if analytic else None, xtol=1e-13)


def timed(poses, warm, repeats, analytic):
    per_pose = []
    for _ in range(repeats):
        seed = np.full(6, HOME)
        t0 = time.perf_counter()
        for p in poses:
            q = solve(p, seed, analytic)
            if warm:
                seed = q
        per_pose.append((time.perf_counter() - t0) / len(poses))
    return statistics.median(per_pose) * 1e6


def check_against_oracle(poses):
    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests", "oracle"))
    import tse_oracle as oracle
    D = oracle.Design()
    worst = 0.0
    for p in poses:
        st, _, q, _, _ = oracle.inverse(D, [float(v) for v in p])
        assert st == "ok", st
        worst = max(worst, max(abs(float(a) - float(b)) for a, b in zip(solve(p, np.full(6, HOME)), q)))
    return worst


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=500, help="poses of the trajectory (default 500)")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--tse-kin", help="path of tse-kin, to run its bench and print ratios")
    a = ap.parse_args()
    poses = trajectory(a.n)
    worst = check_against_oracle(poses[:: max(1, a.n // 10)])
    print(f"fsolve agrees with the mpmath oracle within {worst:.2g} m on {len(poses[:: max(1, a.n // 10)])} poses")
    base = {}
    for analytic, label in ((False, "default"), (True, "analytic_jacobian")):
        for mode in ("warm", "cold"):
            base[(label, mode)] = timed(poses, mode == "warm", a.repeats, analytic)
            print(f"fsolve ({label}) {mode}: median {base[(label, mode)]:.1f} us/pose")
            print(f"fsolve,{label}_{mode}_us,{base[(label, mode)]:.2f}")
    if a.tse_kin:
        out = subprocess.run([a.tse_kin, "bench"], capture_output=True, text=True, check=True).stdout
        print(out, end="")
        fig = {k: float(v) for k, v in (line.split(",")[1:] for line in out.splitlines() if line.startswith("bench,"))}
        for label in ("default", "analytic_jacobian"):
            for mode in ("warm", "cold"):
                us = base[(label, mode)]
                ns = fig[f"ik_double_{mode}_ns"]
                print(f"ratio fsolve ({label}) / tse-kin double, {mode}: {us * 1e3 / ns:.0f}x  ({us:.1f} us vs {ns:.1f} ns)")


if __name__ == "__main__":
    main()
