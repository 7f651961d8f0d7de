"""Compares `tse-kin ik` (double and float) with the mpmath oracle on random poses.

Contract (kinematics.md): where the oracle finds the pose reachable with every mu >= 0.1, the
tool says ok and its slides are within 1e-9 m (double) and 2e-6 m (float) of the exact ones;
where the oracle's verdict is not within a margin of a threshold, status and scissor agree;
noconverge never appears.  Usage: check_ik.py TSE_KIN [--n N] [--seed S]
"""
import argparse
import os
import random
import subprocess
import sys
import tempfile
import time

import mpmath as mp

import tse_oracle as oracle

BOUNDS = {"double": (mp.mpf("1e-9"), mp.mpf("1e-7")), "float": (mp.mpf("2e-6"), mp.mpf("1e-3"))}


def poses(n, seed):
    rnd = random.Random(seed)
    out = []
    for _ in range(n):
        if rnd.random() < 0.8:  # mostly inside the workspace
            p = [rnd.uniform(-0.35, 0.35), rnd.uniform(-0.35, 0.35), rnd.uniform(0.35, 1.6),
                 rnd.uniform(-0.25, 0.25), rnd.uniform(-0.25, 0.25), rnd.uniform(-0.6, 0.6)]
        else:
            p = [rnd.uniform(-0.9, 0.9), rnd.uniform(-0.9, 0.9), rnd.uniform(-0.2, 1.9),
                 rnd.uniform(-0.8, 0.8), rnd.uniform(-0.8, 0.8), rnd.uniform(-3, 3)]
        out.append(p)
    # One of each status the contract names, chosen by hand and confirmed by the oracle below.
    out += [[0.8, 0, 1.0, 0, 0, 0],            # unreachable
            [0, 0, -0.3, 0, 0, 0],             # below
            [0, 0, 1.65, 0, 0, 0],             # alpha (above the extended stop)
            [0, 0, 0.25, 0, 0, 0],             # alpha (below the retracted stop)
            [float("nan"), 0, 1, 0, 0, 0]]     # invalid
    return out


def run(tool, precision, rows, params=None):
    text = "".join(",".join(repr(v) for v in p) + "\n" for p in rows)
    cmd = [tool, "ik", "--precision", precision] + (["--params", params] if params else [])
    r = subprocess.run(cmd, input=text, capture_output=True, text=True, check=False, timeout=600)
    if r.returncode != 0:
        sys.exit(f"tse-kin exited {r.returncode}: {r.stderr}")
    lines = r.stdout.splitlines()
    if len(lines) != len(rows):
        sys.exit(f"tse-kin wrote {len(lines)} lines for {len(rows)} poses")
    out = []
    for line in lines:
        f = line.split(",")
        out.append((f[0], int(f[1]), [float(x) for x in f[2:]]))
    return out


def compare(D, tool, rows, params, tally):
    """Adds to tally: passed, failed, skipped per precision, worst errors, statuses, failures."""
    verdicts = [oracle.inverse(D, p) for p in rows]
    got = {prec: run(tool, prec, rows, params) for prec in ("double", "float")}
    for idx, (p, (st, sc, q, margin, mus)) in enumerate(zip(rows, verdicts)):
        tally["seen"][st] = tally["seen"].get(st, 0) + 1
        good = True
        for prec in ("double", "float"):
            qtol, mtol = BOUNDS[prec]
            gst, gsc, gq = got[prec][idx]
            if gst == "noconverge":
                good = False
                tally["failures"].append(f"{prec} noconverge on {p}")
                continue
            if margin <= mtol:
                tally["skipped"][prec] += 1
                continue
            if gst != st or (st not in ("ok", "degenerate") and gsc != sc):
                good = False
                tally["failures"].append(f"{prec}: {p} ({params}): oracle {st},{sc} tool {gst},{gsc}")
                continue
            if st == "ok" and all(mu >= mp.mpf("0.1") for mu in mus):
                err = max(abs(mp.mpf(g) - e) for g, e in zip(gq, q))
                tally["worst"][prec] = max(tally["worst"][prec], float(err))
                if err > qtol:
                    good = False
                    tally["failures"].append(f"{prec}: {p}: slide error {mp.nstr(err, 3)} m")
        tally["passed" if good else "failed"] += 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("tool")
    ap.add_argument("--n", type=int, default=800)
    ap.add_argument("--seed", type=int, default=2026)
    a = ap.parse_args()
    t0 = time.time()
    tally = {"passed": 0, "failed": 0, "skipped": {"double": 0, "float": 0},
             "worst": {"double": 0.0, "float": 0.0}, "seen": {}, "failures": []}
    compare(oracle.Design(), a.tool, poses(a.n, a.seed), None, tally)
    # The limits the prototype never reaches, made to bind by tighter parameters (the same values
    # go to the tool through --params and to the oracle).
    tight = [({"s_max": "0.41"}, "s_max = 0.41\n"),
             ({"mu_min": "0.995"}, "mu_min = 0.995\n"),
             ({"nu_min": "0.7"}, "nu_min = 0.7\n")]
    rnd = random.Random(a.seed + 1)
    with tempfile.TemporaryDirectory() as tmp:
        for k, (limits, text) in enumerate(tight):
            path = os.path.join(tmp, f"tight{k}.params")
            with open(path, "w") as f:
                f.write(text)
            rows = [[rnd.uniform(-0.1, 0.1), rnd.uniform(-0.1, 0.1), rnd.uniform(0.8, 1.3),
                     rnd.uniform(-0.1, 0.1), rnd.uniform(-0.1, 0.1), rnd.uniform(-0.3, 0.3)] for _ in range(60)]
            compare(oracle.Design(**limits), a.tool, rows, path, tally)
    for f in tally["failures"][:20]:
        print("FAIL", f)
    print(f"statuses by the oracle: {dict(sorted(tally['seen'].items()))}")
    print(f"near a boundary, not compared: double {tally['skipped']['double']}, float {tally['skipped']['float']}")
    print(f"worst slide error where mu >= 0.1: double {tally['worst']['double']:.3g} m, "
          f"float {tally['worst']['float']:.3g} m (bounds 1e-9, 2e-6)")
    print(f"time {time.time() - t0:.1f} s")
    print(f"{tally['passed']} passed, {tally['failed']} failed")
    return 1 if tally["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
