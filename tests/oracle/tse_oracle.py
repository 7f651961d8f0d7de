#!/usr/bin/python3
"""High-precision reference for the TSE inverse kinematics, written from kinematics.md alone.

Per scissor the two constraint conics F1 = F2 = 0 are reduced to a quartic in
m = (s_A - u) + (s_B - v) (the contract's "Notes for the solver"); every real root is polished on
the original pair with mpmath.findroot; the physical solution is the one with det M > 0 and both
slides positive.  The checks follow the contract's order (per scissor 1..3: unreachable, below,
alpha, stroke, singular; then the global type-2 check, degenerate).

Besides the verdict, `solve` reports how far the verdict is from flipping (`margin`, relative
distances of every quantity the decision depended on from its threshold) and whether the
scissor had more than one admissible solution (`ambiguous`), so that a comparison can leave out
poses the contract does not decide sharply.

Run as a script: checks the contract's worked values (to every printed digit) and the quartic's
coefficients against F2, exits non-zero on a mismatch.
"""
import sys

import mpmath as mp
import numpy
from mpmath import mpf

DPS = 40
mp.mp.dps = DPS

STATUS_ORDER = ("ok", "invalid", "unreachable", "below", "alpha", "stroke", "singular",
                "degenerate", "noconverge")


class Params:
    """Design parameters and limits in mpmath; defaults are the prototype of the contract.

    Keyword overrides use the keys of the tse-kin parameter file (L, k1, eta_deg, k3, k4,
    alpha_min_deg, alpha_max_deg, s_min, s_max, mu_min, nu_min), values as strings or numbers.
    """

    def __init__(self, **over):
        L = mpf(over.pop("L", "1.727"))
        self.L = L
        self.k1 = mpf(over.pop("k1", "0.2647"))
        self.eta = mp.radians(mpf(over.pop("eta_deg", 30)))
        self.k3 = mpf(over.pop("k3", "0.0186"))
        self.k4 = mpf(over.pop("k4", "0.11765"))
        self.alpha_min = (mp.radians(mpf(over.pop("alpha_min_deg"))) if "alpha_min_deg" in over
                          else mp.asin(mpf("0.324") / L))
        self.alpha_max = (mp.radians(mpf(over.pop("alpha_max_deg"))) if "alpha_max_deg" in over
                          else mp.asin(mpf("1.619") / L))
        self.s_min = mpf(over.pop("s_min", 0))
        self.s_max = mpf(over.pop("s_max", "0.90"))
        self.mu_min = mpf(over.pop("mu_min", "0.05"))
        self.nu_min = mpf(over.pop("nu_min", "1e-3"))
        if over:
            raise ValueError(f"unknown parameter(s) {sorted(over)}")
        self.l0 = self.k1 * L
        self.r_act = self.k3 * L
        self.r_top = self.k4 * L
        self.g = (1 - (L / self.l0) ** 2) / 4
        self.c = mp.cos(2 * self.eta)
        ce, se = mp.cos(self.eta), mp.sin(self.eta)
        self.frames = []  # per scissor: (unit vector of the ball joint in the plate, O_i, a_i, b_i)
        for i in range(3):
            beta = 2 * mp.pi * i / 3
            er = (mp.cos(beta), mp.sin(beta), mpf(0))
            et = (-mp.sin(beta), mp.cos(beta), mpf(0))
            O = tuple(self.r_act * x for x in er)
            a = tuple(ce * t + se * r for t, r in zip(et, er))
            b = tuple(-ce * t + se * r for t, r in zip(et, er))
            self.frames.append((er, O, a, b))
        # Home: every slide at the vertical-axis solution for the mid-range height, taken as
        # Z = L sin((alpha_min + alpha_max)/2) (the contract does not fix it; it only breaks ties
        # between admissible solutions, which the comparison leaves out anyway).
        self.z_home = L * mp.sin((self.alpha_min + self.alpha_max) / 2)
        self.s_home = None
        sols = scissor_candidates(self, 0, apex_points(self, (0, 0, self.z_home, 0, 0, 0))[0])
        if sols:
            self.s_home = sols[0]["sa"]


# --------------------------------------------------------------------------- geometry

def _dot(x, y):
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]


def _matmul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def _rx(t, d=False):
    c, s = mp.cos(t), mp.sin(t)
    if d:
        return [[0, 0, 0], [0, -s, -c], [0, c, -s]]
    return [[1, 0, 0], [0, c, -s], [0, s, c]]


def _ry(t, d=False):
    c, s = mp.cos(t), mp.sin(t)
    if d:
        return [[-s, 0, c], [0, 0, 0], [-c, 0, -s]]
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]


def _rz(t, d=False):
    c, s = mp.cos(t), mp.sin(t)
    if d:
        return [[-s, -c, 0], [c, -s, 0], [0, 0, 0]]
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


def rotation(roll, pitch, yaw):
    """R = Rz(yaw) Ry(pitch) Rx(roll)."""
    return _matmul(_rz(yaw), _matmul(_ry(pitch), _rx(roll)))


def rotation_derivatives(roll, pitch, yaw):
    """dR/droll, dR/dpitch, dR/dyaw."""
    return (_matmul(_rz(yaw), _matmul(_ry(pitch), _rx(roll, True))),
            _matmul(_rz(yaw), _matmul(_ry(pitch, True), _rx(roll))),
            _matmul(_rz(yaw, True), _matmul(_ry(pitch), _rx(roll))))


def _apply(R, v):
    return tuple(R[k][0] * v[0] + R[k][1] * v[1] + R[k][2] * v[2] for k in range(3))


def apex_points(P, pose):
    """Ball joints C_i = (X, Y, Z) + r_top R (cos beta_i, sin beta_i, 0)."""
    x, y, z, roll, pitch, yaw = [mpf(v) for v in pose]
    R = rotation(roll, pitch, yaw)
    out = []
    for er, _, _, _ in P.frames:
        v = _apply(R, er)
        out.append((x + P.r_top * v[0], y + P.r_top * v[1], z + P.r_top * v[2]))
    return out


def local_terms(P, i, C):
    """d = C_i - O_i, u = d.a_i, v = d.b_i, rho2 = |d|^2."""
    _, O, a, b = P.frames[i]
    d = (C[0] - O[0], C[1] - O[1], C[2] - O[2])
    return d, _dot(d, a), _dot(d, b), _dot(d, d)


def residuals(P, u, v, rho2, sa, sb):
    """(F1, F2) of the contract."""
    f1 = sa * sa - 2 * u * sa - sb * sb + 2 * v * sb
    f2 = sa * sa - 2 * u * sa + rho2 - P.L ** 2 - P.g * (sa * sa + sb * sb + 2 * P.c * sa * sb)
    return f1, f2


def jacobian_M(P, u, v, sa, sb):
    """M = d(F1, F2)/d(s_A, s_B)."""
    return [[2 * (sa - u), -2 * (sb - v)],
            [2 * (sa - u) - 2 * P.g * (sa + P.c * sb), -2 * P.g * (sb + P.c * sa)]]


def quartic(P, u, v, rho2):
    """Coefficients (highest power first) of 4 m^2 F2 after substituting
    2 m s_A = m^2 + 2 u m + delta, 2 m s_B = m^2 + 2 v m - delta (delta = u^2 - v^2).

    Derivation: s_A^2 - 2 u s_A = a^2 - u^2 with a = s_A - u = (m + delta/m)/2, so
    4 m^2 (s_A^2 - 2 u s_A) = (m^2 + delta)^2 - 4 u^2 m^2, and with p = 2 m s_A, q = 2 m s_B,
    4 m^2 w^2 = p^2 + q^2 + 2 c p q; collecting powers of m gives the five terms below."""
    g, c = P.g, P.c
    delta = u * u - v * v
    return [1 - 2 * g * (1 + c),
            -4 * g * (1 + c) * (u + v),
            2 * delta + 4 * (rho2 - P.L ** 2 - u * u) - 4 * g * (u * u + v * v + 2 * c * u * v),
            -4 * g * (1 - c) * delta * (u - v),
            (1 - 2 * g * (1 - c)) * delta * delta]


def _width(P, sa, sb):
    return mp.sqrt(sa * sa + sb * sb + 2 * P.c * sa * sb)


def _mu(M):
    det = M[0][0] * M[1][1] - M[0][1] * M[1][0]
    n1 = mp.sqrt(M[0][0] ** 2 + M[0][1] ** 2)
    n2 = mp.sqrt(M[1][0] ** 2 + M[1][1] ** 2)
    return det, det / (n1 * n2)


def _quartic_roots(coeffs):
    """Every complex root of the polynomial (highest power first).  Exact zero roots are dropped:
    they only occur when delta == 0, on the line a = -b, where det M < 0.

    mpmath.polyroots (Durand-Kerner) is started from the double-precision companion-matrix roots
    so that it needs a few steps, not dozens.  On clustered roots (delta ~ 0 puts two near m = 0)
    it converges slowly; then each start is polished by Newton on the polynomial instead."""
    while len(coeffs) > 1 and coeffs[-1] == 0:
        coeffs = coeffs[:-1]
    if len(coeffs) == 1:
        return []
    seeds = [mp.mpc(complex(z)) for z in numpy.roots([float(c) for c in coeffs])]
    try:
        return mp.polyroots(coeffs, maxsteps=25, extraprec=64, roots_init=seeds)
    except mp.mp.NoConvergence:
        pass
    deriv = [c * (len(coeffs) - 1 - k) for k, c in enumerate(coeffs[:-1])]
    tol = mpf(10) ** (-DPS + 3)
    out = []
    for m in seeds:
        for _ in range(80):
            dp = mp.polyval(deriv, m)
            if dp == 0:
                break
            step = mp.polyval(coeffs, m) / dp
            m -= step
            if abs(step) <= tol * (1 + abs(m)):
                break
        out.append(m)
    return out


def scissor_candidates(P, i, C, report=None):
    """Every solution of F1 = F2 = 0 with det M > 0, s_A > 0, s_B > 0, as dicts.

    If report is a list, appends to it the relative distances from flipping of every quantity
    that decided which roots count (det sign via |mu|, slide signs, near-real complex roots)."""
    d, u, v, rho2 = local_terms(P, i, C)
    delta = u * u - v * v
    coeffs = quartic(P, u, v, rho2)
    scale = P.L
    roots = _quartic_roots(coeffs)
    out = []
    seen = []
    for m in roots:
        im, re = abs(mp.im(m)), mp.re(m)
        if im > mpf(10) ** (-DPS // 2) * (scale + abs(m)):
            if report is not None and im < mpf("1e-3") * (scale + abs(m)):
                report.append(im / (scale + abs(m)))  # a pair about to become real
            continue
        if abs(re) <= mpf(10) ** (-DPS // 2) * scale:
            continue  # m = 0: only when delta = 0, the a = -b line (det M < 0), not a solution
        sa = (re * re + 2 * u * re + delta) / (2 * re)
        sb = (re * re + 2 * v * re - delta) / (2 * re)
        if sa > -mpf("1e-6") * scale and sb > -mpf("1e-6") * scale:
            # polish on the original pair (roots with a clearly negative slide cannot count)
            f = lambda x, y: residuals(P, u, v, rho2, x, y)
            J = lambda x, y: jacobian_M(P, u, v, x, y)
            try:
                sa, sb = mp.findroot(f, (sa, sb), J=J, tol=mpf(10) ** (-2 * DPS + 8), maxsteps=20)
            except (ValueError, ZeroDivisionError):
                pass  # (near-)double root: the quartic's root is as good as it gets
        if any(abs(sa - x) + abs(sb - y) < mpf(10) ** (-DPS // 2) for x, y in seen):
            continue  # a double root counted once
        seen.append((sa, sb))
        M = jacobian_M(P, u, v, sa, sb)
        det, mu = _mu(M)
        if report is not None:
            # only the tests that decide whether this root counts can flip its verdict
            tests = [(det > 0, abs(mu)), (sa > 0, abs(sa) / scale), (sb > 0, abs(sb) / scale)]
            failing = [t for t in tests if not t[0]]
            if not failing:
                report.extend(t[1] for t in tests)
            elif len(failing) == 1:
                report.append(failing[0][1])
        if det > 0 and sa > 0 and sb > 0:
            w = _width(P, sa, sb)
            alpha = mp.acos(w / (2 * P.l0)) if w <= 2 * P.l0 else mpf(0)
            out.append({"sa": sa, "sb": sb, "det": det, "mu": mu, "w": w, "alpha": alpha,
                        "u": u, "v": v, "d": d})
    if P.__dict__.get("s_home") is not None:
        out.sort(key=lambda s: (not _inside(P, s), (s["sa"] - P.s_home) ** 2 + (s["sb"] - P.s_home) ** 2))
    return out


def _inside(P, s):
    return (P.s_min <= s["sa"] <= P.s_max and P.s_min <= s["sb"] <= P.s_max
            and s["w"] <= 2 * P.l0 and P.alpha_min <= s["alpha"] <= P.alpha_max)


def _scissor_status(P, C, s, margins):
    """The per-scissor checks after existence, in the contract's order; appends the relative
    distance of each checked quantity from its threshold to margins."""
    margins.append(abs(C[2]) / P.L)
    if not C[2] > 0:
        return "below"
    a_ok = s["w"] <= 2 * P.l0 and P.alpha_min <= s["alpha"] <= P.alpha_max
    margins.append(min(abs(s["alpha"] - P.alpha_min) / P.alpha_min,
                       abs(s["alpha"] - P.alpha_max) / P.alpha_max))
    if not a_ok:
        return "alpha"
    margins.append(min(abs(s[k] - lim) for k in ("sa", "sb") for lim in (P.s_min, P.s_max)) / P.L)
    if not (P.s_min <= s["sa"] <= P.s_max and P.s_min <= s["sb"] <= P.s_max):
        return "stroke"
    margins.append(abs(s["mu"] - P.mu_min) / P.mu_min)
    if not s["mu"] >= P.mu_min:
        return "singular"
    return "ok"


def constraint_pose_jacobian(P, pose, C, sols):
    """6x6 dF/dp, rows (F1, F2) of scissors 1..3, columns X, Y, Z, roll, pitch, yaw; the rotation
    columns divided by r_top.  dF1/dC = -2 s_A a + 2 s_B b, dF2/dC = -2 s_A a + 2 d (u = d.a,
    v = d.b, rho2 = d.d), dC/d(X,Y,Z) = I, dC/d(angle) = r_top dR/d(angle) (cos beta, sin beta, 0)."""
    roll, pitch, yaw = [mpf(x) for x in pose[3:]]
    dR = rotation_derivatives(roll, pitch, yaw)
    rows = []
    for i, s in enumerate(sols):
        er, _, a, b = P.frames[i]
        sa, sb, d = s["sa"], s["sb"], s["d"]
        g1 = tuple(-2 * sa * a[k] + 2 * sb * b[k] for k in range(3))
        g2 = tuple(-2 * sa * a[k] + 2 * d[k] for k in range(3))
        dirs = [_apply(D, er) for D in dR]  # already divided by r_top
        for gr in (g1, g2):
            rows.append([gr[0], gr[1], gr[2]] + [_dot(gr, t) for t in dirs])
    return rows


def hadamard_ratio(rows):
    prod = mpf(1)
    for r in rows:
        prod *= mp.sqrt(sum(x * x for x in r))
    return abs(mp.det(mp.matrix(rows))) / prod


class Result:
    __slots__ = ("status", "scissor", "q", "mu", "nu", "margin", "ambiguous", "candidates")

    def __repr__(self):
        return (f"Result({self.status},{self.scissor}, q={[mp.nstr(x, 17) for x in self.q]}, "
                f"mu={[mp.nstr(x, 6) for x in self.mu]}, nu={mp.nstr(self.nu, 6) if self.nu is not None else None}, "
                f"margin={mp.nstr(self.margin, 3)}, ambiguous={self.ambiguous})")


def solve(P, pose):
    """Inverse kinematics verdict for pose (X, Y, Z, roll, pitch, yaw); floats are taken exactly."""
    r = Result()
    r.q, r.mu, r.nu, r.ambiguous, r.candidates = [], [], None, False, []
    r.margin = mp.inf
    try:
        pose = [mpf(x) for x in pose]
    except (TypeError, ValueError):
        pose = None
    if pose is None or len(pose) != 6 or not all(mp.isfinite(x) for x in pose):
        r.status, r.scissor = "invalid", 0
        return r
    C = apex_points(P, pose)
    margins = []
    chosen = []
    for i in range(3):
        cands = scissor_candidates(P, i, C[i], margins)
        r.candidates.append(len(cands))
        if not cands:
            r.status, r.scissor, r.margin = "unreachable", i + 1, min(margins, default=mp.inf)
            return r
        s = cands[0]
        inside = [x for x in cands if _inside(P, x)]
        if len(inside) > 1:
            r.ambiguous = True
        elif not inside and len(cands) > 1:
            verdicts = {_scissor_status(P, C[i], x, []) for x in cands}
            if len(verdicts) > 1:
                r.ambiguous = True
        r.q += [s["sa"], s["sb"]]
        r.mu.append(s["mu"])
        chosen.append(s)
        st = _scissor_status(P, C[i], s, margins)
        if st != "ok":
            r.status, r.scissor, r.margin = st, i + 1, min(margins, default=mp.inf)
            return r
    r.nu = hadamard_ratio(constraint_pose_jacobian(P, pose, C, chosen))
    margins.append(abs(r.nu - P.nu_min) / P.nu_min)
    r.margin = min(margins, default=mp.inf)
    r.status, r.scissor = ("ok", 0) if r.nu >= P.nu_min else ("degenerate", 0)
    return r


# --------------------------------------------------------------------------- self-check

WORKED = [
    ((0, 0, "1.0", 0, 0, 0), ["0.43015083911167"] * 6),
    (("0.1", "-0.05", "1.1", "0.1", "-0.05", "0.2"),
     ["0.39127069075903", "0.41631844093909", "0.38241559603276", "0.42099161248302",
      "0.56558364785006", "0.23697220292616"]),
]


def self_check(verbose=True):
    """Returns the number of failures: worked values to every printed digit, the quartic against
    F2 directly, the analytic dF/dp against central differences."""
    fails = 0
    P = Params()
    for pose, want in WORKED:
        r = solve(P, pose)
        # rounded to as many significant digits as the contract prints (14)
        got = [mp.nstr(x, 14) for x in r.q]
        ok = r.status == "ok" and got == want
        fails += not ok
        if verbose:
            print(f"worked value {pose}: {r.status} {got} {'ok' if ok else 'MISMATCH, want ' + str(want)}")
    # quartic coefficients against F2 evaluated through the substitution, at random points
    import random
    rnd = random.Random(1)
    worst = mpf(0)
    for _ in range(20):
        u, v, rho2, m = [mpf(rnd.uniform(-1, 1)) for _ in range(3)] + [mpf(rnd.uniform(0.1, 2))]
        rho2 = abs(rho2) + 1
        delta = u * u - v * v
        sa = (m * m + 2 * u * m + delta) / (2 * m)
        sb = (m * m + 2 * v * m - delta) / (2 * m)
        f1, f2 = residuals(P, u, v, rho2, sa, sb)
        worst = max(worst, abs(f1), abs(mp.polyval(quartic(P, u, v, rho2), m) - 4 * m * m * f2))
    ok = worst < mpf(10) ** (-DPS + 8)
    fails += not ok
    if verbose:
        print(f"quartic == 4 m^2 F2 and F1 == 0 on the substitution: worst {mp.nstr(worst, 3)} {'ok' if ok else 'MISMATCH'}")
    # analytic dF/dp against central differences of F at fixed slides
    pose = [mpf(x) for x in WORKED[1][0]]
    C = apex_points(P, pose)
    sols = [scissor_candidates(P, i, C[i])[0] for i in range(3)]
    rows = constraint_pose_jacobian(P, pose, C, sols)
    h = mpf(10) ** (-DPS // 2)
    worst = mpf(0)
    for k in range(6):
        pp, pm = list(pose), list(pose)
        pp[k] += h
        pm[k] -= h
        Cp, Cm = apex_points(P, pp), apex_points(P, pm)
        for i, s in enumerate(sols):
            fp = residuals(P, *local_terms(P, i, Cp[i])[1:], s["sa"], s["sb"])
            fm = residuals(P, *local_terms(P, i, Cm[i])[1:], s["sa"], s["sb"])
            for j in range(2):
                num = (fp[j] - fm[j]) / (2 * h) / (P.r_top if k >= 3 else 1)
                worst = max(worst, abs(num - rows[2 * i + j][k]))
    ok = worst < mpf(10) ** (-DPS // 2 + 4)
    fails += not ok
    if verbose:
        print(f"analytic dF/dp against central differences: worst {mp.nstr(worst, 3)} {'ok' if ok else 'MISMATCH'}")
    return fails


if __name__ == "__main__":
    if len(sys.argv) > 1:  # tse_oracle.py X Y Z roll pitch yaw [key=value ...]
        nums = [a for a in sys.argv[1:] if "=" not in a]
        over = dict(a.split("=", 1) for a in sys.argv[1:] if "=" in a)
        print(solve(Params(**over), nums))
        sys.exit(0)
    n = self_check()
    print(f"{3 - n} passed, {n} failed" if n <= 3 else f"0 passed, {n} failed")
    sys.exit(1 if n else 0)
