#!/usr/bin/python3
"""The design study's figures against the mpmath oracle (tests/oracle/tse_oracle.py).

Usage: study_oracle.py PATH/TO/tse-kin

For a few designs (the prototype, k1 = 0.5, k2 = -30 and +60 degrees, k3 = 0.15, k4 = 0.05):
  * `profile`: the six singular values of dp/dq, sigma_z, mu_min and nu at heights on the axis,
    from the oracle's own branch solution, dF/dp and M (dq/dp = -M^-1 dF/dp per scissor) and
    mpmath's SVD, 40 digits;
  * `margins`: each scissor's mu and the type-2 ratio nu of random poses, where the oracle finds
    exactly one branch solution per scissor (none: the first such scissor is named, mu nan);
  * `sweep`: the HAF column, sigma_z / sigma_z(k1 = 1) from the oracle at tse-kin haf's default
    heights.
And `workspace`'s volume (the reachable volume of the plate's centre, summed over the grid's
cells) against an estimate that shares nothing with it but tse-kin ik's verdicts: a Monte Carlo of
points drawn uniformly in the cylinder r <= L/2, 0 <= Z <= L, the cylinder's volume times the
share ik answers ok, for the prototype and a smaller design (L = 1.4 m, a 0.6 m stroke).
Tolerances: relative 1e-9 in double, 1e-4 in float (kinematics.md's slide accuracy carried to
these figures).  Last line `P passed, F failed`; exit 1 on any failure.
"""
import math
import os
import random
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "oracle"))
import mpmath as mp  # noqa: E402
import tse_oracle as oracle  # noqa: E402

TOOL = sys.argv[1]
TOL = {"double": 1e-9, "float": 1e-4}
DESIGNS = [("prototype", {}), ("k1 = 0.5", {"k1": "0.5"}), ("k2 = -30 deg", {"eta_deg": -30}),
           ("k2 = 60 deg", {"eta_deg": 60}), ("k3 = 0.15", {"k3": "0.15"}), ("k4 = 0.05", {"k4": "0.05"})]
passes, failures = 0, []
tmp = tempfile.mkdtemp(prefix="tse_study_oracle_")


def check(name, cond, detail=""):
    global passes
    if cond:
        passes += 1
    else:
        failures.append(name)
        print(f"FAIL: {name}" + (f": {detail}" if detail else ""))


def run(args, stdin=""):
    r = subprocess.run([TOOL] + args, input=stdin, capture_output=True, text=True, timeout=300)
    if r.returncode != 0:
        print(r.stderr)
    return r.returncode, r.stdout


def rows(out):
    lines = [l for l in out.splitlines() if l and not l.startswith("#")]
    head = lines[0].split(",")
    return [dict(zip(head, l.split(","))) for l in lines[1:]]


def params_file(name, over):
    path = os.path.join(tmp, name.replace(" ", "_").replace("=", "") + ".params")
    with open(path, "w") as fh:
        fh.write("".join(f"{k} = {v}\n" for k, v in over.items()))
    return path


def close(a, b, tol):
    a, b = mp.mpf(a), mp.mpf(b)
    return abs(a - b) <= tol * max(abs(b), mp.mpf(1e-300))


def vertical_figures(P, z):
    """(singular values of dp/dq descending, sigma_z, mu_min, nu) at (0, 0, z, 0, 0, 0), or None."""
    pose = [0, 0, z, 0, 0, 0]
    C = oracle.apex_points(P, pose)
    sols = []
    for i in range(3):
        cands = oracle.scissor_candidates(P, i, C[i])
        if len(cands) != 1:
            return None
        sols.append(cands[0])
    Fp = oracle.constraint_pose_jacobian(P, pose, C, sols)
    nu = oracle.hadamard_ratio(Fp)
    J = mp.matrix(6, 6)
    for i, s in enumerate(sols):
        M = oracle.jacobian_M(P, s["u"], s["v"], s["sa"], s["sb"])
        det = M[0][0] * M[1][1] - M[0][1] * M[1][0]
        for col in range(6):
            scale = 1 if col < 3 else P.r_top  # the oracle divides rotation columns by r_top
            f1, f2 = Fp[2 * i][col] * scale, Fp[2 * i + 1][col] * scale
            J[2 * i, col] = -(M[1][1] * f1 - M[0][1] * f2) / det
            J[2 * i + 1, col] = -(M[0][0] * f2 - M[1][0] * f1) / det
    sv = sorted((1 / x for x in mp.svd_r(J, compute_uv=False)), reverse=True)
    sigma_z = 1 / mp.sqrt(sum(J[k, 2] ** 2 for k in range(6)))
    return sv, sigma_z, min(s["mu"] for s in sols), nu


mp.mp.dps = oracle.DPS
# tse-kin haf's default heights (its help): 9, 5 % inside L sin(alpha_min) .. L sin(alpha_max).
Z_LO, Z_HI = mp.mpf("0.324"), mp.mpf("1.619")
HAF_Z = [float(Z_LO + (Z_HI - Z_LO) * (mp.mpf("0.05") + mp.mpf("0.9") * i / 8)) for i in range(9)]
rnd = random.Random(20261111)

for name, over in DESIGNS:
    P = oracle.Params(**over)
    P1 = oracle.Params(**dict(over, k1="1"))
    path = params_file(name, over)
    for prec, tol in TOL.items():
        # profile
        zs = [0.4, 0.8, 1.2, 1.55]
        rc, out = run(["profile", "--design", path, "--precision", prec, "--z", ",".join(map(str, zs))])
        got = rows(out) if rc == 0 else []
        for z, r in zip(zs, got):
            want = vertical_figures(P, mp.mpf(z))
            if want is None:
                continue
            sv, sig, mu, nu = want
            check(f"{name} {prec} profile z={z}: the six singular values",
                  all(close(r[f"sv{k + 1}"], sv[k], 10 * tol) for k in range(6)),
                  f"{[r[f'sv{k + 1}'] for k in range(6)]} vs {[mp.nstr(x, 12) for x in sv]}")
            check(f"{name} {prec} profile z={z}: sigma_z, mu_min, nu",
                  close(r["sigma_z"], sig, tol) and abs(float(r["mu_min"]) - float(mu)) < tol
                  and abs(float(r["nu"]) - float(nu)) < tol, f"{r} vs {sig} {mu} {nu}")
        check(f"{name} {prec} profile: a row per height", len(got) == len(zs), out)
        # margins
        poses = [[rnd.uniform(-0.5, 0.5), rnd.uniform(-0.5, 0.5), rnd.uniform(0.15, 1.7), rnd.uniform(-0.3, 0.3),
                  rnd.uniform(-0.3, 0.3), rnd.uniform(-0.6, 0.6)] for _ in range(25)]
        rc, out = run(["margins", "--design", path, "--precision", prec],
                      "".join(",".join(repr(x) for x in p) + "\n" for p in poses))
        lines = out.splitlines()
        compared = 0
        for p, line in zip(poses, lines):
            f = line.split(",")
            C = oracle.apex_points(P, p)
            cands = [oracle.scissor_candidates(P, i, C[i]) for i in range(3)]
            if any(len(c) > 1 for c in cands):
                continue
            compared += 1
            missing = [i + 1 for i, c in enumerate(cands) if not c]
            ok = all((math.isnan(float(f[2 + i])) if not c else abs(float(f[2 + i]) - float(c[0]["mu"])) < tol)
                     for i, c in enumerate(cands))
            if missing:
                ok = ok and f[5] == "nan"
            else:
                nu = oracle.hadamard_ratio(oracle.constraint_pose_jacobian(P, p, C, [c[0] for c in cands]))
                ok = ok and abs(float(f[5]) - float(nu)) < tol
            check(f"{name} {prec} margins of {[round(x, 3) for x in p]}", ok,
                  f"{line} vs {[mp.nstr(c[0]['mu'], 10) if c else None for c in cands]}")
        check(f"{name} {prec} margins: most poses compared", compared >= 20, f"{compared}")
        # sweep's HAF: sigma_z ratio at haf's default heights
        k1 = over.get("k1", "0.2647")
        rc, out = run(["sweep", "k1", k1, k1, "1", "--grid", "2,1,2", "--design", path, "--precision", prec])
        r = rows(out)[0] if rc == 0 else {"haf": "nan"}
        ratios = []
        for z in HAF_Z:
            a, b = vertical_figures(P, mp.mpf(z)), vertical_figures(P1, mp.mpf(z))
            if a and b:
                ratios.append(a[1] / b[1])
        want = sum(ratios) / len(ratios)
        check(f"{name} {prec} sweep: HAF the oracle's mean sigma_z ratio", close(r["haf"], want, tol),
              f"{r['haf']} vs {mp.nstr(want, 17)}")

# The workspace's volume against a Monte Carlo by tse-kin ik.  N = 100,000 points from a fixed
# seed (the same points every run: the test cannot be flaky); the estimate's standard error
# V_cyl sqrt(p (1 - p) / N) is 1.3 % of the smaller design's volume.  The grid's own error: on
# 31 x 72 x 61 both designs' volumes are within 0.5 % of those of a grid twice as fine (0.5346 and
# 0.5345 m^3, 0.1156 and 0.1151 m^3, measured when this test was written).  Allowed: four standard
# errors plus 2 % of the volume; the fraction of the points times the cylinder (what a volume that
# ignored the cells' sizes would give) is 2.5 to 4 times too large, far outside.
MC_N, MC_GRID = 100000, "31,72,61"
for name, text, L in (("prototype", "", 1.727), ("L = 1.4 m, stroke 0.6 m", "L = 1.4\ns_max = 0.6\nk1 = 0.35\n"
                                                 "eta_deg = 20\nk3 = 0.03\n", 1.4)):
    path = os.path.join(tmp, f"mc_{len(text)}.params")
    with open(path, "w") as fh:
        fh.write(text)
    mc = random.Random(21)
    R, cyl = L / 2, math.pi * (L / 2) ** 2 * L
    pts = []
    for _ in range(MC_N):
        r, phi, z = R * math.sqrt(mc.random()), 2 * math.pi * mc.random(), L * mc.random()
        pts.append(f"{r * math.cos(phi)!r},{r * math.sin(phi)!r},{z!r},0,0,0\n")
    rc, out = run(["ik", "--design", path], "".join(pts))
    p = sum(1 for l in out.splitlines() if l.startswith("ok,")) / MC_N
    est, se = p * cyl, cyl * math.sqrt(p * (1 - p) / MC_N)
    for prec in ("double", "float"):
        rc, out = run(["workspace", "--design", path, "--grid", MC_GRID, "--precision", prec])
        last = out.strip().splitlines()[-1].split(",") if rc == 0 else ["0"] * 4
        vol = float(last[3])
        print(f"volume {name} {prec}: grid {vol:.5f}, Monte Carlo {est:.5f} +- {se:.5f} m^3")
        check(f"{name} {prec}: workspace volume {vol:.4f} m^3 is the Monte Carlo's {est:.4f} +- {se:.4f} m^3",
              abs(vol - est) <= 4 * se + 0.02 * est and abs(float(last[2]) * cyl - est) > 4 * se + 0.02 * est,
              f"{out[-400:]}")

print(f"{passes} passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
