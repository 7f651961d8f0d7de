"""An independent high-precision statement of kinematics.md, in mpmath.

Written from the contract alone: ball joints from the pose, each scissor's two conics reduced to
a quartic in m = (s_A - u) + (s_B - v), every real root polished on the original pair by
mpmath.findroot, the det M > 0 sheet with positive slides, then the checks in the contract's
order.  It reports, with the verdict, how far each checked quantity is from its threshold, so
that a comparison can leave out poses that sit on a boundary.
"""
import mpmath as mp

mp.mp.dps = 40

STATUSES = ["ok", "invalid", "unreachable", "below", "alpha", "stroke", "singular", "degenerate", "noconverge"]


class Design:
    def __init__(self, **limits):
        self.L = mp.mpf("1.727")
        self.k1 = mp.mpf("0.2647")
        self.eta = mp.pi / 6
        self.k3 = mp.mpf("0.0186")
        self.k4 = mp.mpf("0.11765")
        self.alpha_min = mp.asin(mp.mpf("0.324") / self.L)
        self.alpha_max = mp.asin(mp.mpf("1.619") / self.L)
        self.s_min = mp.mpf(0)
        self.s_max = mp.mpf("0.90")
        self.mu_min = mp.mpf("0.05")
        self.nu_min = mp.mpf("1e-3")
        for key, value in limits.items():
            setattr(self, key, mp.mpf(value))
        self.l0 = self.k1 * self.L
        self.r_act = self.k3 * self.L
        self.r_top = self.k4 * self.L
        self.g = (1 - (self.L / self.l0) ** 2) / 4
        self.c = mp.cos(2 * self.eta)
        self.frames = []
        for i in range(3):
            beta = i * 2 * mp.pi / 3
            er = (mp.cos(beta), mp.sin(beta))
            et = (-mp.sin(beta), mp.cos(beta))
            a = tuple(mp.cos(self.eta) * et[k] + mp.sin(self.eta) * er[k] for k in range(2))
            b = tuple(-mp.cos(self.eta) * et[k] + mp.sin(self.eta) * er[k] for k in range(2))
            self.frames.append((beta, (self.r_act * er[0], self.r_act * er[1]), a, b))


def rotation(roll, pitch, yaw):
    cr, sr, cp, sp, cy, sy = mp.cos(roll), mp.sin(roll), mp.cos(pitch), mp.sin(pitch), mp.cos(yaw), mp.sin(yaw)
    Rz = mp.matrix([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    Ry = mp.matrix([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    Rx = mp.matrix([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    return Rz * Ry * Rx


def joints(D, pose):
    x, y, z, roll, pitch, yaw = [mp.mpf(v) for v in pose]
    R = rotation(roll, pitch, yaw)
    out = []
    for beta, _, _, _ in D.frames:
        v = R * mp.matrix([mp.cos(beta), mp.sin(beta), 0])
        out.append((x + D.r_top * v[0], y + D.r_top * v[1], z + D.r_top * v[2]))
    return out


def local(D, i, C):
    _, O, a, b = D.frames[i]
    d = (C[0] - O[0], C[1] - O[1], C[2])
    u = d[0] * a[0] + d[1] * a[1]
    v = d[0] * b[0] + d[1] * b[1]
    return d, u, v, d[0] ** 2 + d[1] ** 2 + d[2] ** 2


def residual(D, u, v, rho2, sa, sb):
    w2 = sa ** 2 + sb ** 2 + 2 * D.c * sa * sb
    return (sa ** 2 - 2 * u * sa - sb ** 2 + 2 * v * sb,
            sa ** 2 - 2 * u * sa + rho2 - D.L ** 2 - D.g * w2)


def jac(D, u, v, sa, sb):
    return [[2 * (sa - u), -2 * (sb - v)],
            [2 * (sa - u) - 2 * D.g * (sa + D.c * sb), -2 * D.g * (sb + D.c * sa)]]


def polymul(p, q):
    out = [mp.mpf(0)] * (len(p) + len(q) - 1)
    for i, x in enumerate(p):
        for j, y in enumerate(q):
            out[i + j] += x * y
    return out


def polyadd(*ps):
    n = max(len(p) for p in ps)
    return [sum((p[k] if k < len(p) else 0) for p in ps) for k in range(n)]


def branch_solutions(D, i, C):
    """Every solution with det M > 0 and positive slides, as (s_A, s_B, det, mu)."""
    d, u, v, rho2 = local(D, i, C)
    delta = u ** 2 - v ** 2
    P = [delta, 2 * u, mp.mpf(1)]           # 2 m s_A, ascending powers of m
    Q = [-delta, 2 * v, mp.mpf(1)]          # 2 m s_B
    A = polymul([delta, 0, 1], [delta, 0, 1])  # (m^2 + delta)^2 = 4 m^2 a^2
    B = [0, 0, 4 * (rho2 - D.L ** 2 - u ** 2)]
    W = polyadd(polymul(P, P), polymul(Q, Q), [2 * D.c * t for t in polymul(P, Q)])
    quartic = polyadd(A, B, [-D.g * t for t in W])
    roots = mp.polyroots(list(reversed(quartic)), maxsteps=200, extraprec=80)
    out = []
    for m in roots:
        if abs(mp.im(m)) > mp.mpf("1e-20") * (1 + abs(m)):
            continue
        m = mp.re(m)
        if m == 0:
            continue
        sa = (m ** 2 + 2 * u * m + delta) / (2 * m)
        sb = (m ** 2 + 2 * v * m - delta) / (2 * m)
        try:
            sa, sb = mp.findroot(lambda x, y: residual(D, u, v, rho2, x, y), (sa, sb))
        except (ZeroDivisionError, ValueError):
            continue
        M = jac(D, u, v, sa, sb)
        det = M[0][0] * M[1][1] - M[0][1] * M[1][0]
        if det > 0 and sa > 0 and sb > 0:
            mu = det / (mp.sqrt(M[0][0] ** 2 + M[0][1] ** 2) * mp.sqrt(M[1][0] ** 2 + M[1][1] ** 2))
            out.append((sa, sb, det, mu))
    return out


def constraint_rows(D, pose, q):
    """dF/dp by central differences in 40-digit arithmetic (independent of any analytic form),
    rotation columns divided by r_top."""
    h = mp.mpf("1e-15")
    rows = []
    for i in range(3):
        sa, sb = q[2 * i], q[2 * i + 1]
        cols = [[], []]
        for k in range(6):
            pp = list(pose)
            pm = list(pose)
            pp[k] = mp.mpf(pp[k]) + h
            pm[k] = mp.mpf(pm[k]) - h
            fp = residual(D, *local(D, i, joints(D, pp)[i])[1:], sa, sb)
            fm = residual(D, *local(D, i, joints(D, pm)[i])[1:], sa, sb)
            for r in range(2):
                der = (fp[r] - fm[r]) / (2 * h)
                cols[r].append(der / D.r_top if k >= 3 else der)
        rows.extend(cols)
    return rows


def hadamard(rows):
    M = mp.matrix(rows)
    prod = mp.mpf(1)
    for r in rows:
        prod *= mp.sqrt(sum(x ** 2 for x in r))
    return abs(mp.det(M)) / prod


def inverse(D, pose):
    """(status, scissor, q, margin, mus): margin is the smallest distance of any quantity that
    decided the verdict from its threshold (large means far from every boundary); mus are the
    type-1 margins of the solutions taken."""
    pose = [mp.mpf(v) for v in pose]
    if any(not mp.isfinite(v) for v in pose):
        return "invalid", 1, None, mp.inf, []
    C = joints(D, pose)
    q = []
    mus = []
    margin = mp.inf
    first = None
    w_hi = 2 * D.l0 * mp.cos(D.alpha_min)
    w_lo = 2 * D.l0 * mp.cos(D.alpha_max)
    for i in range(3):
        sols = branch_solutions(D, i, C[i])
        if not sols:
            q += [mp.nan, mp.nan]
            if first is None:
                first = ("unreachable", i + 1)
            continue
        def inside(s):
            w = mp.sqrt(s[0] ** 2 + s[1] ** 2 + 2 * D.c * s[0] * s[1])
            return D.s_min <= s[0] <= D.s_max and D.s_min <= s[1] <= D.s_max and w_lo <= w <= w_hi
        good = [s for s in sols if inside(s)]
        pick = sorted(good or sols, key=lambda s: (s[0] - 0.40294) ** 2 + (s[1] - 0.40294) ** 2)[0]
        if len(good) > 1:
            margin = min(margin, mp.mpf(0))  # ambiguous: the seed decides; not compared
        sa, sb, det, mu = pick
        q += [sa, sb]
        mus.append(mu)
        # Margins of every check this scissor passed or failed.
        for s in sols:
            margin = min(margin, abs(s[2]) / (1 + abs(s[2])), s[0], s[1])
        w = mp.sqrt(sa ** 2 + sb ** 2 + 2 * D.c * sa * sb)
        checks = [
            ("below", C[i][2] > 0, abs(C[i][2])),
            ("alpha", w_lo <= w <= w_hi, min(abs(w - w_lo), abs(w - w_hi)) / w_hi),
            ("stroke", D.s_min <= sa <= D.s_max and D.s_min <= sb <= D.s_max,
             min(abs(sa - D.s_min), abs(sa - D.s_max), abs(sb - D.s_min), abs(sb - D.s_max))),
            ("singular", mu >= D.mu_min, abs(mu - D.mu_min)),
        ]
        for name, passed, dist in checks:
            margin = min(margin, dist)
            if not passed:
                if first is None:
                    first = (name, i + 1)
                break
    if first is not None:
        return first[0], first[1], q, margin, mus
    nu = hadamard(constraint_rows(D, pose, q))
    margin = min(margin, abs(nu - D.nu_min) / D.nu_min)
    if nu < D.nu_min:
        return "degenerate", 0, q, margin, mus  # the scissor of a type-2 failure is a diagnosis
    return "ok", 0, q, margin, mus


def self_check():
    """The contract's worked values, to the digits given."""
    D = Design()
    st, _, q, _, _ = inverse(D, [0, 0, 1.0, 0, 0, 0])
    assert st == "ok", st
    for v in q:
        assert abs(v - mp.mpf("0.43015083911167")) < mp.mpf("5e-15"), v
    st, _, q, _, _ = inverse(D, ["0.1", "-0.05", "1.1", "0.1", "-0.05", "0.2"])
    want = ["0.39127069075903", "0.41631844093909", "0.38241559603276", "0.42099161248302",
            "0.56558364785006", "0.23697220292616"]
    assert st == "ok", st
    for v, w in zip(q, want):
        assert abs(v - mp.mpf(w)) < mp.mpf("5e-15"), (v, w)
    return True


if __name__ == "__main__":
    self_check()
    print("worked values: 1 passed, 0 failed")
