#!/usr/bin/python3
"""tse-kin's command-line contract, as a script sees it, run against the real binary.

Usage: cli_contract.py PATH/TO/tse-kin

Exit codes, one output line per input line, malformed rows answered `invalid` without stopping the
stream, order independence, --help everywhere, parameter files, and the figures.  Every expected
number comes from kinematics.md (its worked values, its prototype) or from hand algebra on its
equations, never from tse-kin's own output (or, for `tse-kin params`, from the defaults it must
reproduce):

On the vertical axis (X = Y = 0, zero orientation) C_i = r_top e_r + Z e_z and O_i = r_act e_r, so
u = v = u0 = (r_top - r_act) sin(eta) and rho2 = (r_top - r_act)^2 + Z^2.  By the scissor's mirror
symmetry s_A = s_B = s, F1 vanishes, and F2 becomes A s^2 - 2 u0 s + rho2 - L^2 = 0 with
A = 1 - 2 g (1 + cos 2 eta); the physical root (det M > 0) is the larger one.  Differentiating,
ds/dZ = -Z / (A s - u0) for all six slides, and sigma_z = 1 / (sqrt(6) |ds/dZ|).
"""
import math
import os
import random
import re
import subprocess
import sys
import tempfile
import time

TOOL = sys.argv[1]
failures = []
passes = 0

# kinematics.md, "Design parameters" and "Worked values".
PROTO = dict(L=1.727, k1=0.2647, eta=math.pi / 6, k3=0.0186, k4=0.11765)
WORKED1 = ([0, 0, 1.0, 0, 0, 0], [0.43015083911167] * 6)
WORKED2 = ([0.1, -0.05, 1.1, 0.1, -0.05, 0.2],
           [0.39127069075903, 0.41631844093909, 0.38241559603276, 0.42099161248302, 0.56558364785006,
            0.23697220292616])
# kinematics.md, "Accuracy of an accepted pose".
TOL = {"double": 1e-9, "float": 2e-6}
STATUSES = {"ok", "invalid", "unreachable", "below", "alpha", "stroke", "singular", "degenerate", "noconverge"}
NUMBER = re.compile(r"^(nan|-?inf|-?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)$")


def check(name, cond, detail=""):
    global passes
    if cond:
        passes += 1
    else:
        failures.append(name)
        print(f"FAIL: {name}" + (f": {detail}" if detail else ""))


def run(args, stdin=b"", timeout=120):
    if isinstance(stdin, str):
        stdin = stdin.encode()
    r = subprocess.run([TOOL] + args, input=stdin, capture_output=True, timeout=timeout)
    return r.returncode, r.stdout.decode(), r.stderr.decode()


def vertical(z, L=PROTO["L"], k1=PROTO["k1"], eta=PROTO["eta"], k3=PROTO["k3"], k4=PROTO["k4"]):
    """(s, ds/dZ, sigma_z) on the vertical axis, by the hand algebra of the module docstring."""
    l0 = k1 * L
    g = (1 - (L / l0) ** 2) / 4
    d = (k4 - k3) * L
    u0 = d * math.sin(eta)
    A = 1 - 2 * g * (1 + math.cos(2 * eta))
    s = (u0 + math.sqrt(u0 * u0 - A * (d * d + z * z - L * L))) / A
    dsdz = -z / (A * s - u0)
    return s, dsdz, 1 / (math.sqrt(6) * abs(dsdz))


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def csv(p):
    return ",".join(repr(float(x)) for x in p)


def fields(line):
    return line.split(",")


def well_formed(line, numbers):
    f = fields(line)
    return (len(f) == 2 + numbers and f[0] in STATUSES and re.fullmatch(r"[0-3]", f[1]) is not None
            and all(NUMBER.match(x) for x in f[2:]))


def invalid_line(line, numbers):
    return line == "invalid,0" + ",nan" * numbers


tmp = tempfile.mkdtemp(prefix="tse_kin_cli_")


def write(name, text):
    path = os.path.join(tmp, name)
    with open(path, "w") as fh:
        fh.write(text)
    return path


# ---------------------------------------------------------------- exit codes and usage errors
rc, out, err = run(["ik"])
check("ik on empty input exits 0 with no output", rc == 0 and out == "", f"rc {rc} out {out!r}")
for args, name in [([], "no command"), (["frobnicate"], "unknown command"), (["ik", "--bogus"], "unknown option"),
                   (["ik", "stray"], "stray argument"), (["ik", "--precision", "quad"], "bad precision"),
                   (["ik", "--params"], "option without value"), (["ik", "--grid", "2,1,2"], "option of another command"),
                   (["workspace", "--grid", "1,2"], "grid with two counts"),
                   (["workspace", "--grid", "1,36,41"], "grid with NR < 2"),
                   (["workspace", "--grid", "21,0,41"], "grid with NPHI < 1"),
                   (["workspace", "--grid", "21,36,x"], "grid not a number"),
                   (["workspace", "--grid", "21.5,36,41"], "grid not whole"),
                   (["workspace", "--orientation", "0,0"], "orientation with two angles"),
                   (["haf", "--z", "abc"], "haf heights not numbers"), (["bench", "--n", "1"], "bench n too small"),
                   (["bench", "--precision", "float"], "bench takes both precisions")]:
    rc, out, err = run(args)
    check(f"{name} exits 2", rc == 2, f"rc {rc}")
    check(f"{name} says why on stderr only", out == "" and err.strip() != "", f"out {out!r} err {err!r}")
rc, out, err = run(["ik", "--bogus"])
check("the unknown option is named", "--bogus" in err, err)
rc, out, err = run(["frobnicate"])
check("the unknown command is named", "frobnicate" in err, err)

# ---------------------------------------------------------------- --help
for cmd in ["", "ik", "fk", "jacobian", "haf", "workspace", "bench", "params"]:
    for form in (([cmd] if cmd else []) + ["--help"], ([cmd] if cmd else []) + ["-h"],
                 ["help"] + ([cmd] if cmd else [])):
        rc, out, err = run(form)
        check(f"{' '.join(form)} exits 0", rc == 0, f"rc {rc}")
        check(f"{' '.join(form)} prints usage to stdout", out.startswith("usage: tse-kin") and err == "",
              f"{out[:60]!r} {err!r}")
rc, out, err = run(["jacobian", "--help"])
check("jacobian --help documents its line", "status,scissor,J11" in out and "sv1" in out, out)
rc, out, err = run(["ik", "--help"])
check("ik --help documents blank lines", "blank line" in out, out)
rc, out, err = run(["ik", "--bogus", "--help"])
check("--help wins over a bad option", rc == 0 and out.startswith("usage: tse-kin ik"), f"rc {rc}")
# The contract the help cites ships with the project.
KIN_MD = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "kinematics.md")
for form in (["--help"], ["ik", "--help"], ["haf", "--help"]):
    rc, out, err = run(form)
    check(f"{' '.join(form)} cites docs/kinematics.md", "docs/kinematics.md" in out and
          re.search(r"(?<!docs/)kinematics\.md", out) is None, out)
check("docs/kinematics.md is in the repository", os.path.isfile(KIN_MD), KIN_MD)
rc, out, err = run(["params", "--params", "x"])
check("params takes no options (exit 2)", rc == 2 and out == "", f"rc {rc}")

# ---------------------------------------------------------------- worked values, both precisions
for prec in ("double", "float"):
    for pose, q in (WORKED1, WORKED2):
        rc, out, err = run(["ik", "--precision", prec], csv(pose) + "\n")
        f = fields(out.strip())
        ok = rc == 0 and len(f) == 8 and f[0] == "ok" and f[1] == "0"
        worst = max(abs(float(a) - b) for a, b in zip(f[2:], q)) if ok else math.inf
        check(f"ik worked value {pose} in {prec} within {TOL[prec]}", ok and worst <= TOL[prec],
              f"{out.strip()} (worst {worst:.3g})")
s1, dsdz1, sigma1 = vertical(1.0)
check("hand algebra reproduces the worked value", abs(s1 - 0.43015083911167) < 1e-13, f"{s1!r}")

# ---------------------------------------------------------------- malformed rows, one line out per line in
good = csv(WORKED1[0])
malformed = ["abc", "", "   ", "1,2", "0,0,1,0,0,0,7", "0,,1,0,0,0", "0,0,1,0,0,0,", ",0,0,1,0,0,0",
             "0,0,1,0,0,0 x", "0,0,1x,0,0,0", "0;0;1;0;0;0", "0,0,1,0,0,0\r7", "x" * 5000, "1," * 3000 + "1"]
lines = []
for m in malformed:
    lines += [good, m]
lines.append(good)
text = "\n".join(lines) + "\n"
rc, out, err = run(["ik"], text)
outl = out.split("\n")[:-1]
check("malformed rows: exit 0", rc == 0, f"rc {rc}")
check("malformed rows: one line out per line in", len(outl) == len(lines), f"{len(outl)} for {len(lines)}")
if len(outl) == len(lines):
    for i, (inp, o) in enumerate(zip(lines, outl)):
        if inp == good:
            check(f"good row {i + 1} between malformed ones is solved", fields(o)[0] == "ok", o)
        else:
            check(f"malformed row {inp[:20]!r} answers invalid,0,nan x6", invalid_line(o, 6), o)
check("malformed rows are reported on stderr with their line", "stdin:2:" in err, err)

# A NUL byte inside a line is one malformed line, and does not eat the next one.
rc, out, err = run(["ik"], good.encode() + b"\x00junk\n" + good.encode() + b"\n")
outl = out.split("\n")[:-1]
check("a NUL byte makes one invalid line and no more",
      rc == 0 and len(outl) == 2 and invalid_line(outl[0], 6) and outl[1].startswith("ok,0,"), repr(out))

# Non-finite numbers parse and go to the library, which says invalid.
nonfinite = ["nan,0,1,0,0,0", "0,0,inf,0,0,0", "0,0,1,0,0,-inf", "1e999,0,1,0,0,0", "0,0,1,NaN,0,0"]
rc, out, err = run(["ik"], "\n".join(nonfinite) + "\n")
outl = out.split("\n")[:-1]
check("non-finite rows: one line each", rc == 0 and len(outl) == len(nonfinite), repr(out))
for inp, o in zip(nonfinite, outl):
    check(f"non-finite row {inp} is invalid", fields(o)[0] == "invalid" and well_formed(o, 6), o)

# A UTF-8 BOM before the first row is not part of it.
rc, out, err = run(["ik"], b"\xef\xbb\xbf" + good.encode() + b"\n" + good.encode() + b"\n")
outl = out.split("\n")[:-1]
check("a BOM before the first row is skipped", rc == 0 and len(outl) == 2 and all(o.startswith("ok,0,") for o in outl),
      repr(out))
rc, out, err = run(["ik"], good.encode() + b"\n\xef\xbb\xbf" + good.encode() + b"\n")
outl = out.split("\n")[:-1]
check("a BOM anywhere else makes its line invalid", rc == 0 and len(outl) == 2 and invalid_line(outl[1], 6), repr(out))

# A first line of names is a header, answered by the output's header.
IK_HEAD = "status,scissor,s_a1,s_b1,s_a2,s_b2,s_a3,s_b3"
POSE_HEAD = "status,scissor,x,y,z,roll,pitch,yaw"
JAC_HEAD = ("status,scissor," + ",".join(f"J{i}{j}" for i in range(1, 7) for j in range(1, 7)) + "," +
            ",".join(f"sv{k}" for k in range(1, 7)))
for cmd, head, row, want, numbers in (
        ("ik", "x,y,z,roll,pitch,yaw", good, IK_HEAD, 6),
        ("ik", " X , Y ,Z,Roll,Pitch,Yaw\r", good, IK_HEAD, 6),
        ("fk", "s_a1,s_b1,s_a2,s_b2,s_a3,s_b3", csv(WORKED1[1]), POSE_HEAD, 6),
        ("fk", "s_a1,s_b1,s_a2,s_b2,s_a3,s_b3,x0,y0,z0,roll0,pitch0,yaw0", csv(WORKED1[1] + WORKED1[0]), POSE_HEAD, 6),
        ("jacobian", "x,y,z,roll,pitch,yaw", good, JAC_HEAD, 42)):
    for bom in (b"", b"\xef\xbb\xbf"):
        rc, out, err = run([cmd], bom + (head + "\n" + row + "\n").encode())
        outl = out.split("\n")[:-1]
        check(f"{cmd}: header {head.strip()!r}{' after a BOM' if bom else ''} answered by {want[:40]}...",
              rc == 0 and len(outl) == 2 and outl[0] == want and well_formed(outl[1], numbers)
              and fields(outl[1])[0] == "ok" and err == "", f"{out[:120]!r} {err!r}")
# Not headers: too few or too many names, names mixed with numbers, a header after the first line,
# and a line of nan and inf (numbers, answered by the library).
for text, name in (("x,y,z,roll,pitch\n", "five names"), ("x,y,z,roll,pitch,yaw,w\n", "seven names"),
                   ("x,y,z,1,2,3\n", "names and numbers"), ("x,y,z,roll,pitch,y-aw\n", "a name with '-'"),
                   ("x,y,,roll,pitch,yaw\n", "an empty name"),
                   (good + "\nx,y,z,roll,pitch,yaw\n", "a header on line 2")):
    rc, out, err = run(["ik"], text)
    outl = out.split("\n")[:-1]
    check(f"ik: {name} is a malformed line", rc == 0 and len(outl) == text.count("\n") and invalid_line(outl[-1], 6),
          repr(out))
rc, out, err = run(["ik"], "nan,inf,nan,nan,nan,nan\n")
check("ik: a first line of nan and inf is numbers, not a header",
      rc == 0 and fields(out.strip())[0] == "invalid" and well_formed(out.strip(), 6), repr(out))

# CRLF, spaces, a last line without a newline.
rc, crlf, err = run(["ik"], "0,0,1,0,0,0\r\n 0.1 , -0.05 ,1.1,0.1,-0.05,0.2\r\n0,0,1,0,0,0")
rc2, lf, err2 = run(["ik"], "0,0,1,0,0,0\n0.1,-0.05,1.1,0.1,-0.05,0.2\n0,0,1,0,0,0\n")
check("CRLF, padded fields and a missing final newline read like plain lines", rc == 0 and crlf == lf and
      len(lf.split("\n")) == 4, f"{crlf!r} vs {lf!r}")

# ---------------------------------------------------------------- order independence and format
rnd = random.Random(20261123)
poses = []
for k in range(300):
    if k % 4:
        p = [rnd.uniform(-0.3, 0.3), rnd.uniform(-0.3, 0.3), rnd.uniform(0.35, 1.6), rnd.uniform(-0.25, 0.25),
             rnd.uniform(-0.25, 0.25), rnd.uniform(-0.6, 0.6)]
    else:
        p = [rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(-0.3, 2.0), rnd.uniform(-1.6, 1.6),
             rnd.uniform(-1.6, 1.6), rnd.uniform(-3.2, 3.2)]
    poses.append(csv(p))
for prec in ("double", "float"):
    rc, fwd, err = run(["ik", "--precision", prec], "\n".join(poses) + "\n")
    rc2, rev, err2 = run(["ik", "--precision", prec], "\n".join(reversed(poses)) + "\n")
    fl, rl = fwd.split("\n")[:-1], rev.split("\n")[:-1]
    check(f"{prec}: {len(poses)} poses give {len(poses)} lines", rc == 0 and len(fl) == len(poses), f"{len(fl)}")
    check(f"{prec}: reversing the input reverses the output", fl == list(reversed(rl)))
    bad = [o for o in fl if not well_formed(o, 6)]
    check(f"{prec}: every line is status,scissor + 6 numbers, NaN spelled nan", not bad, repr(bad[:3]))
    check(f"{prec}: ok lines have scissor 0, rejections a scissor 1..3",
          all((f[0] == "ok") == (f[1] == "0") for f in map(fields, fl)), repr(fl[:3]))
    check(f"{prec}: the sample has both outcomes", {fields(o)[0] for o in fl} > {"ok"}, repr(set(fields(o)[0] for o in fl)))

# ---------------------------------------------------------------- fk
for prec, tol in (("double", 1e-9), ("float", 1e-4)):
    for pose, q in (WORKED1, WORKED2):
        for seed in ([], pose):
            rc, out, err = run(["fk", "--precision", prec], csv(q + seed) + "\n")
            f = fields(out.strip())
            ok = rc == 0 and len(f) == 8 and f[0] == "ok" and f[1] == "0"
            worst = max(abs(float(a) - b) for a, b in zip(f[2:], pose)) if ok else math.inf
            check(f"fk {prec} of the worked slides {'with' if seed else 'without'} seed gives {pose}",
                  ok and worst <= tol, f"{out.strip()} (worst {worst:.3g})")
rc, out, err = run(["fk"], "1,1,1,1,1,1\n0.43,0.43,0.43,0.43,0.43\n" + csv(WORKED1[1]) + ",0,0,1,0,0\n"
                   "0.43,0.43,0.43,0.43,0.43,0.43,0.43\n")
outl = out.split("\n")[:-1]
check("fk: one line per line", rc == 0 and len(outl) == 4, repr(out))
# Slides outside the stroke (0..0.9 m, docs/kinematics.md) are a stroke rejection of the first such
# slide's scissor, whether or not a pose would exist, seeded or not.
for q, sc in (([1.0] * 6, 1), ([0.43] * 5 + [0.95], 3), ([0.43, 0.43, -0.01, 0.43, 0.43, 0.43], 2),
              ([0.43, 0.43, 0.43, 0.91, 0.43, 0.43] + WORKED1[0], 2)):
    rc, out, err = run(["fk"], csv(q) + "\n")
    check(f"fk of {q}: stroke of scissor {sc}", rc == 0 and out == f"stroke,{sc}" + ",nan" * 6 + "\n", out)

# ---------------------------------------------------------------- jacobian
rc, out, err = run(["jacobian"], "0,0,1,0,0,0\nabc\n0,0,5,0,0,0\n")
outl = out.split("\n")[:-1]
check("jacobian: one line per line", rc == 0 and len(outl) == 3, repr(out))
if len(outl) == 3:
    f = fields(outl[0])
    check("jacobian line: status, scissor, 36 + 6 numbers", well_formed(outl[0], 42) and f[:2] == ["ok", "0"],
          outl[0][:80])
    J = [[float(x) for x in f[2 + 6 * i: 8 + 6 * i]] for i in range(6)]
    sv = [float(x) for x in f[38:44]]
    check("dq/dp: the Z column is ds/dZ of the hand algebra in every row",
          all(rel(J[i][2], dsdz1) < 1e-9 for i in range(6)), f"{[J[i][2] for i in range(6)]} vs {dsdz1}")
    # Three-fold and mirror symmetry: a horizontal move or a rotation raises as many slides as it lowers.
    check("dq/dp: the other columns sum to zero over the six slides (symmetry)",
          all(abs(sum(J[i][c] for i in range(6))) < 1e-9 for c in (0, 1, 3, 4, 5)), repr(J))
    check("singular values of dp/dq are positive and descending",
          all(a >= b > 0 for a, b in zip(sv, sv[1:])), repr(sv))
    check("sigma_z of the hand algebra is a singular value of dp/dq", any(rel(x, sigma1) < 1e-9 for x in sv),
          f"{sv} vs {sigma1}")
    check("jacobian: malformed row is invalid,0 + 42 nan", invalid_line(outl[1], 42), outl[1][:40])
    f = fields(outl[2])
    check("jacobian: a rejected pose has nan numbers", f[0] != "ok" and f[2:] == ["nan"] * 42, outl[2][:40])

# ---------------------------------------------------------------- haf
zs = [0.5, 1.0, 1.4]
for prec, tol in (("double", 1e-9), ("float", 1e-4)):
    rc, out, err = run(["haf", "--precision", prec, "--z", ",".join(map(str, zs))])
    data = [l for l in out.split("\n") if l and not l.startswith("#")]
    check(f"haf {prec}: a line per height and the summary last", rc == 0 and len(data) == len(zs) + 1, out)
    if len(data) != len(zs) + 1:
        continue
    hafs = []
    for z, line in zip(zs, data):
        v = [float(x) for x in fields(line)]
        s, dsdz, sig = vertical(z)
        s_r, dsdz_r, sig_r = vertical(z, k1=1.0)
        hafs.append(sig / sig_r)
        check(f"haf {prec} z={z}: sigma_z, sigma_z(k1=1), HAF as the hand algebra",
              len(v) == 4 and v[0] == z and rel(v[1], sig) < tol and rel(v[2], sig_r) < tol
              and rel(v[3], sig / sig_r) < tol, f"{v} vs {[z, sig, sig_r, sig / sig_r]}")
    last = fields(data[-1])
    check(f"haf {prec}: summary haf,mean,min,max,paper,11.487",
          len(last) == 6 and last[0] == "haf" and last[4:] == ["paper", "11.487"]
          and rel(float(last[1]), sum(hafs) / 3) < tol and rel(float(last[2]), min(hafs)) < tol
          and rel(float(last[3]), max(hafs)) < tol, data[-1])
    check(f"haf {prec}: the paper's figure is beside ours", "paper: 11.487" in out, out)
rc, out, err = run(["haf"])
data = [l for l in out.split("\n") if l and not l.startswith("#")]
lo, hi = 0.324, 1.619  # L sin(alpha_min), L sin(alpha_max) of the prototype
want = [lo + (hi - lo) * (0.05 + 0.9 * i / 8) for i in range(9)]
check("haf default: 9 heights inside the alpha stops, then the summary",
      rc == 0 and len(data) == 10 and all(abs(float(fields(l)[0]) - w) < 1e-12 for l, w in zip(data, want)), out)
rc, out, err = run(["haf", "--z", "5"])
check("haf at an unreachable height: nan, and a nan summary",
      rc == 0 and "5,nan,nan,nan\n" in out and out.rstrip("\n").endswith("haf,nan,nan,nan,paper,11.487"), out)
# The paper's figure is the prototype's: named for it (also when a file spells a default another way),
# never for another design, whose summary is haf,mean,min,max (issue 21).
same_proto = write("haf_proto.params", "eta_deg = 30   # the default, in degrees\nslide_vmax = 0.1\n")
stroke06 = write("stroke06.params", "s_max = 0.6\n")
longer = write("haf_long.params", "L = 2\n")
for path, proto in ((same_proto, True), (stroke06, False), (longer, False)):
    rc, out, err = run(["haf", "--design", path])
    last = fields(out.rstrip("\n").split("\n")[-1])
    if proto:
        check(f"haf --params {os.path.basename(path)}: the paper named, as for the prototype",
              rc == 0 and "(paper: 11.487)" in out and last[0] == "haf" and last[4:] == ["paper", "11.487"], out)
    else:
        check(f"haf --params {os.path.basename(path)}: the paper named nowhere, the summary haf,mean,min,max",
              rc == 0 and "paper" not in out and "11.487" not in out and last[0] == "haf" and len(last) == 4, out)
for args in (["sweep", "k1", "0.2", "0.3", "2", "--grid", "3,3,3"], ["workspace", "--points", "--grid", "3,3,3"]):
    rc, out, err = run(args)
    check(f"{args[0]}: the paper's figures named for the prototype", rc == 0 and "paper" in out and "0.28" in out, out)
    rc, out, err = run(args + ["--design", stroke06])
    check(f"{args[0]}: not for another design", rc == 0 and "paper" not in out and "11.487" not in out
          and not re.search(r"(?<![\d.])0\.28(?!\d)", out), out)

# ---------------------------------------------------------------- workspace
rc, out, err = run(["workspace", "--grid", "2,1,2"])
# Z = 0 puts the ball joints on the base plane (below); Z = L needs alpha = 90 deg, beyond alpha_max.
check("workspace 2,1,2: none of the 4 points is reachable", rc == 0 and out.split("\n")[-2] == "0,4,0.000000,0", out)
for prec in ("double", "float"):
    rc, out, err = run(["workspace", "--grid", "5,4,5", "--precision", prec])
    last = fields(out.split("\n")[-2]) if out.endswith("\n") else []
    ok = rc == 0 and len(last) == 4 and last[1] == "100" and 0 <= int(last[0]) <= 100
    check(f"workspace {prec}: last line reachable,total,fraction,volume_m3 with total = 5*4*5",
          ok and abs(float(last[2]) - int(last[0]) / 100) < 1e-6 and re.fullmatch(r"\d\.\d{6}", last[2])
          and 0 < float(last[3]) < math.pi * PROTO["L"] ** 3 / 4, out)
    check(f"workspace {prec}: the paper's figure is named for the prototype", "paper: 0.28" in out, out)
    rc, out, err = run(["workspace", "--grid", "5,4,5", "--precision", prec, "--design", stroke06])
    check(f"workspace {prec}: not for another design",
          rc == 0 and "paper" not in out and not re.search(r"(?<![\d.])0\.28(?!\d)", out), out)
# The cylinder and the cells, by hand: on a 5,4,5 grid the radii are L/8 apart, the heights L/4, the
# rim arc of a sector pi L / 4.
rc, out, err = run(["workspace", "--grid", "5,4,5"])
L = PROTO["L"]
check("workspace: the comments give the cylinder and the cells' size (the volume's resolution)",
      f"r <= {L / 2:.6g} m, 0 <= Z <= {L:.6g} m ({math.pi * L ** 3 / 4:.6g} m^3)" in out and
      f"{L / 8:.4g} m in r, {L / 4:.4g} m in Z, an arc of {math.pi * L / 4:.4g} m at the rim" in out, out)
rc, out, err = run(["workspace", "--orientation", "0.05,-0.05,0.1", "--grid", "3,3,3"])
check("workspace with an orientation",
      rc == 0 and re.fullmatch(r"\d+,27,\d\.\d{6},[0-9.e-]+", out.split("\n")[-2] or ""), out)
rc, out, err = run(["workspace"])
check("workspace default grid 21,36,41", rc == 0 and out.split("\n")[-2].split(",")[1] == str(21 * 36 * 41), out)

# ---------------------------------------------------------------- bench
rc, out, err = run(["bench", "--n", "40"])
figures = {f[1]: f[2] for f in map(fields, out.split("\n")) if len(f) == 3 and f[0] == "bench"}
for prec in ("double", "float"):
    for key in (f"ik_{prec}_cold_ns", f"ik_{prec}_warm_ns", f"fk_{prec}_ns"):
        check(f"bench prints {key} as a positive number", key in figures and 0 < float(figures[key]) < 1e9,
              repr(figures.get(key)))
    check(f"bench prints labelled {prec} lines",
          f"ik {prec} warm: median" in out and f"ik {prec} cold: median" in out and f"fk {prec} warm: median" in out,
          out)
    check(f"bench {prec}: iterations counted", float(figures.get(f"ik_{prec}_warm_iter_mean", 0)) > 0, out)
    check(f"bench {prec}: the path stays reachable", figures.get(f"{prec}_not_ok") == "0", out)
check("bench exits 0", rc == 0, f"rc {rc} {err}")

# ---------------------------------------------------------------- parameter files
rc, out, err = run(["ik", "--params", os.path.join(tmp, "missing.params")], good + "\n")
check("missing params file exits 1, naming it", rc == 1 and "missing.params" in err and out == "", f"rc {rc} {err}")
rc, out, err = run(["ik", "--params", tmp], good + "\n")
check("a directory as params file exits 1", rc == 1 and out == "", f"rc {rc} {err}")
bad = write("bad.params", "L = 1.7\nk2 = 3\n")
rc, out, err = run(["ik", "--params", bad], good + "\n")
check("unknown key exits 1 naming file and line", rc == 1 and f"{bad}:2: unknown parameter 'k2'" in err, err)
bad = write("dup.params", "# d\ns_max = 0.8\ns_max = 0.7\n")
rc, out, err = run(["workspace", "--params", bad])
check("duplicate key exits 1 naming the line", rc == 1 and f"{bad}:3:" in err and "twice" in err, err)
bad = write("val.params", "k1 = 0.2647x\n")
rc, out, err = run(["haf", "--params", bad])
check("malformed value exits 1 naming the line", rc == 1 and f"{bad}:1:" in err, err)
bad = write("set.params", "k1 = 0.3\neta_deg = 95\n")
rc, out, err = run(["ik", "--params", bad], good + "\n")
check("a value outside the controller's range exits 1 naming the line and the range",
      rc == 1 and f"{bad}:2: eta = 95 deg is outside -89.99998..89.99998 deg" in err, err)
rc, out, err = run(["ik", "--design", bad], good + "\n")
check("an invalid design exits 1 naming the key's line", rc == 1 and f"{bad}:2: eta_deg = 95 is invalid" in err, err)
bad = write("dflt.params", "alpha_min_deg = 75\n")
rc, out, err = run(["bench", "--params", bad, "--n", "10"])
check("a set the controller refuses through a default says the default is in conflict",
      rc == 1 and "alpha_max is not set in the file: its default is what is in conflict" in err and out == "", err)
rc, out, err = run(["bench", "--design", bad, "--n", "10"])
check("an invalid design through a default names the default value",
      rc == 1 and "default value alpha_max = " in err and out == "", err)
# A design no controller takes (L beyond 10 m, and the default homing switches out of reach) is
# still a design: valid in double, but L overflows float, which the float build refuses by name.
big = write("big.params", "L = 1e39\n")
rc, out, err = run(["ik", "--params", big], good + "\n")
check("L = 1e39 is no controller's set", rc == 1 and f"{big}:1: L = 1e39 m is outside 0.1..10 m" in err, err)
rc, out, err = run(["ik", "--design", big], good + "\n")
check("L = 1e39 is a valid double design", rc == 0, f"rc {rc} {err}")
rc, out, err = run(["ik", "--design", big, "--precision", "float"], good + "\n")
check("L = 1e39 in float exits 1 naming line and key", rc == 1 and f"{big}:1: L" in err and "float" in err, err)
rc, out, err = run(["bench", "--design", big, "--n", "10"])
check("bench refuses a set float cannot hold before timing anything", rc == 1 and out == "", f"rc {rc} {out!r}")

# The values are applied: a stroke below the vertical solution at Z = 1 (s = 0.430 m).
short = write("short.params", "# shorter stroke\r\ns_max = 0.40   # metres\r\n")
rc, out, err = run(["ik", "--design", short], good + "\n")
f = fields(out.strip())
check("s_max = 0.40 makes (0,0,1) a stroke rejection of scissor 1", rc == 0 and f[:2] == ["stroke", "1"], out)
# L scales the design; the hand algebra with L = 2 gives the slides at (0, 0, 1).
longer = write("long.params", "L = 2.0\n")
for prec in ("double", "float"):
    rc, out, err = run(["ik", "--design", longer, "--precision", prec], good + "\n")
    f = fields(out.strip())
    s2 = vertical(1.0, L=2.0)[0]
    check(f"L = 2 {prec}: the slides of the hand algebra", rc == 0 and f[0] == "ok" and
          all(abs(float(x) - s2) <= TOL[prec] for x in f[2:]), f"{out.strip()} vs {s2}")
# Every key written out at the prototype's values, angles in degrees: the same answers.
proto = write("proto.params", "\n".join([
    "L = 1.727", "k1 = 0.2647", "eta_deg = 30", "k3 = 0.0186", "k4 = 0.11765",
    f"alpha_min_deg = {math.degrees(math.asin(0.324 / 1.727))!r}",
    f"alpha_max_deg = {math.degrees(math.asin(1.619 / 1.727))!r}",
    "s_min = 0", "s_max = 0.9", "mu_min = 0.05", "nu_min = 0.001"]) + "\n")
sample = "\n".join(poses[:40]) + "\n"
rc, a, err = run(["ik", "--params", proto], sample)
rc2, b, err2 = run(["ik"], sample)
same = rc == 0 and rc2 == 0 and len(a.split("\n")) == len(b.split("\n"))
if same:
    for la, lb in zip(a.split("\n")[:-1], b.split("\n")[:-1]):
        fa, fb = fields(la), fields(lb)
        same = same and fa[:2] == fb[:2] and all(
            (x == y) or abs(float(x) - float(y)) < 1e-12 for x, y in zip(fa[2:], fb[2:]))
check("the prototype written out in a file (degrees) answers as the defaults", same, err)

# ---------------------------------------------------------------- one naming scheme, and the template
# The prototype in SI names (radians): the same answers as the defaults.
si = write("si.params", "\n".join([
    "L = 1.727", "k1 = 0.2647", f"eta = {math.pi / 6!r}", "k3 = 0.0186", "k4 = 0.11765",
    f"alpha_min = {math.asin(0.324 / 1.727)!r}", f"alpha_max = {math.asin(1.619 / 1.727)!r}",
    "s_min = 0", "s_max = 0.9", "mu_min = 0.05", "nu_min = 0.001"]) + "\n")
rc, a, err = run(["ik", "--params", si], sample)
check("the prototype in SI names (radians) answers exactly as the defaults", rc == 0 and a == b, err)
# Radians are radians: eta = 30 is refused, not read as degrees.
bad = write("eta_rad.params", "eta = 30\n")
rc, out, err = run(["ik", "--design", bad], good + "\n")
check("eta = 30 (radians) is an invalid design", rc == 1 and f"{bad}:1: eta = 30 is invalid" in err, err)
rc, out, err = run(["ik", "--params", bad], good + "\n")
check("eta = 30 (radians) is outside the controller's range",
      rc == 1 and f"{bad}:1: eta = 30 rad is outside -1.570796..1.570796 rad" in err, err)
# One parameter in both spellings: both lines named.
both = write("both.params", "alpha_max = 1.2\nL = 1.727\nalpha_max_deg = 69\n")
rc, out, err = run(["ik", "--params", both], good + "\n")
check("both spellings of alpha_max exit 1 naming both lines",
      rc == 1 and f"{both}:3: alpha_max_deg given twice (first on line 1 as alpha_max)" in err and out == "", err)
# The controller's names in SI: checked to be numbers, then ignored.
ctl = write("ctl.params", "\ufeffL = 1.727\r\nslide_vmax = 0.15\r\nplate_jmax = 10\r\nwatchdog_ms = 500\r\n"
            "home_sw_3 = 0.2\r\ncan_kbps = 500\r\nstep_pulse_ns = 2000\r\n")
rc, a, err = run(["ik", "--params", ctl], sample)
check("a file with a BOM and the controller's names answers as the defaults", rc == 0 and a == b, err)
ctl_bad = write("ctl_bad.params", "slide_vmax = 0.15\nwatchdog_ms = half a second\n")
rc, out, err = run(["ik", "--params", ctl_bad], good + "\n")
check("a controller name with a non-number exits 1 naming the line",
      rc == 1 and f"{ctl_bad}:2: watchdog_ms: 'half a second' is not one finite number" in err, err)
# `tse-kin params` writes a file that --params takes unchanged, and that answers as the defaults.
rc, tpl, err = run(["params"])
check("params exits 0 writing a template", rc == 0 and err == "" and "\nL = " in tpl, f"rc {rc} {err}")
tpl_path = write("template.params", tpl)
for prec in ("double", "float"):
    rc, a, err = run(["ik", "--params", tpl_path, "--precision", prec], sample)
    rc2, b2, err2 = run(["ik", "--precision", prec], sample)
    check(f"params > p.txt; ik --params p.txt answers exactly as the defaults ({prec})", rc == 0 and a == b2, err)
rc, a, err = run(["workspace", "--params", tpl_path, "--grid", "3,3,3"])
rc2, b2, err2 = run(["workspace", "--grid", "3,3,3"])
check("the template serves workspace too", rc == 0 and a == b2, err)
keys = [l.split("=")[0].strip() for l in tpl.split("\n") if l and not l.startswith("#")]
for k in ("L", "k1", "eta", "k3", "k4", "alpha_min", "alpha_max", "s_min", "s_max", "mu_min", "nu_min",
          "slide_vmax", "watchdog_ms", "can_kbps"):
    check(f"the template sets {k} once", keys.count(k) == 1, repr(keys))
check("the template speaks SI (no _deg key)", not any(k.endswith("_deg") for k in keys), repr(keys))
eta_line = [l for l in tpl.split("\n") if l.startswith("eta = ")]
check("the template gives eta in radians with degrees in the comment",
      len(eta_line) == 1 and abs(float(eta_line[0].split("=")[1].split("#")[0]) - math.pi / 6) < 1e-15
      and "# rad (30 deg)" in eta_line[0], repr(eta_line))
check("every template line that sets a key has a comment with its unit",
      all("#" in l for l in tpl.split("\n") if l and not l.startswith("#")), tpl)

# ---------------------------------------------------------------- the design study (issue 11)
# sweep, profile, margins and workspace --points: usage, parameter files, output, and the figures
# against the hand algebra of the module docstring; consistency with haf, workspace and ik where
# the commands promise the same figure.  tests/cli/study_oracle.py checks them against mpmath.
DEG = math.pi / 180
Z_LO, Z_HI = 0.324, 1.619  # L sin(alpha_min), L sin(alpha_max) of the prototype


def data_lines(out):
    return [l for l in out.split("\n") if l and not l.startswith("#")]


def table(out):
    lines = data_lines(out)
    head = lines[0].split(",") if lines else []
    return head, [dict(zip(head, l.split(","))) for l in lines[1:]]


def mu_axis(z, L=PROTO["L"], k1=PROTO["k1"], eta=PROTO["eta"], k3=PROTO["k3"], k4=PROTO["k4"]):
    """Type-1 margin on the vertical axis: with s_A = s_B = s and u = v = u0, M has rows
    2 (s - u0) (1, -1) and (2 (s - u0) - 2 G, -2 G), G = g s (1 + cos 2 eta), and
    det M = 4 (s - u0) (D s - u0)."""
    s, _, _ = vertical(z, L, k1, eta, k3, k4)
    l0 = k1 * L
    g = (1 - (L / l0) ** 2) / 4
    u0 = (k4 - k3) * L * math.sin(eta)
    D = 1 - 2 * g * (1 + math.cos(2 * eta))
    G = g * s * (1 + math.cos(2 * eta))
    det = 4 * (s - u0) * (D * s - u0)
    return det / (2 * math.sqrt(2) * abs(s - u0) * 2 * math.sqrt((s - u0 - G) ** 2 + G * G))


def haf_default_mean(**design):
    """tse-kin haf's default heights (9, 5 % inside the stops: its help) and the mean HAF there."""
    zs = [Z_LO + (Z_HI - Z_LO) * (0.05 + 0.9 * i / 8) for i in range(9)]
    return sum(vertical(z, **design)[2] / vertical(z, **dict(design, k1=1.0))[2] for z in zs) / 9


for args, name, says in [
        (["sweep"], "sweep without arguments", "PARAM FROM TO N"),
        (["sweep", "k1", "0", "1"], "sweep with three arguments", "got 3"),
        (["sweep", "k1", "0", "1", "3", "4"], "sweep with five arguments", "'4'"),
        (["sweep", "k2", "0", "1", "3"], "sweep of k2", "eta_deg"),
        (["sweep", "slide_vmax", "0", "1", "3"], "sweep of a controller parameter", "controller"),
        (["sweep", "k9", "0", "1", "3"], "sweep of an unknown key", "'k9'"),
        (["sweep", "k1", "a", "1", "3"], "sweep FROM not a number", "FROM"),
        (["sweep", "k1", "0", "inf", "3"], "sweep TO infinite", "TO"),
        (["sweep", "k1", "0", "1", "0"], "sweep of 0 designs", "N"),
        (["sweep", "k1", "0", "1", "2.5"], "sweep of 2.5 designs", "N"),
        (["sweep", "k1", "0", "1", "1e1"], "sweep N in exponent form", "N"),
        (["sweep", "k1", "0", "1", "100001"], "sweep of too many designs", "100000"),
        (["sweep", "k1", "0", "1", "1"], "one design from a range", "FROM and TO"),
        (["sweep", "k1", "0", "1", "3", "--jobs", "0"], "sweep --jobs 0", "--jobs"),
        (["sweep", "k1", "0", "1", "3", "--jobs", "x"], "sweep --jobs x", "--jobs"),
        (["sweep", "k1", "0", "1", "3", "--jobs", "257"], "sweep --jobs 257", "--jobs"),
        (["sweep", "k1", "0", "1", "3", "--orientation", "0,0,0"], "sweep --orientation", "--orientation"),
        (["sweep", "k1", "0", "1", "3", "--grid", "1,2,3"], "sweep with a bad grid", "--grid"),
        (["profile", "--z", "1", "--n", "5"], "profile --z and --n", "not both"),
        (["profile", "--n", "1"], "profile --n 1", "--n"),
        (["profile", "0.5"], "profile with a stray argument", "'0.5'"),
        (["workspace", "--points=yes"], "--points with a value", "--points"),
        (["ik", "--points"], "ik --points", "--points"),
        (["margins", "--grid", "2,1,2"], "margins --grid", "--grid"),
        (["margins", "x"], "margins with a stray argument", "'x'")]:
    rc, out, err = run(args)
    check(f"{name} exits 2", rc == 2, f"rc {rc}")
    check(f"{name} says why on stderr only, naming {says!r}", out == "" and says in err, f"out {out!r} err {err!r}")
for cmd in ("sweep", "profile", "margins"):
    for form in ([cmd, "--help"], ["help", cmd], [cmd, "k1", "--bogus", "-h"]):
        rc, out, err = run(form)
        check(f"{' '.join(form)} prints its usage", rc == 0 and out.startswith(f"usage: tse-kin {cmd}") and err == "",
              f"rc {rc} {out[:60]!r}")
rc, out, err = run(["--help"])
check("tse-kin --help lists sweep, profile, margins and --points",
      all(f"\n  {c} " in out for c in ("sweep", "profile", "margins")) and "--points" in out and "--jobs" in out, out)
rc, out, err = run(["workspace", "--help"])
check("workspace --help documents --points", "--points" in out and "x,y,z,status,scissor" in out, out)
bad = write("study_bad.params", "k1 = 0.3\nk1 = 0.4\n")
for args in (["sweep", "k1", "0.2", "0.5", "2"], ["profile"], ["margins"]):
    rc, out, err = run(args + ["--params", bad], good + "\n")
    check(f"{args[0]} with a bad parameter file exits 1 naming its line", rc == 1 and f"{bad}:2:" in err and out == "",
          f"rc {rc} {err!r}")
rc, out, err = run(["sweep", "k1", "0", "1", "3", "--params", os.path.join(tmp, "none.params")])
check("sweep with a missing parameter file exits 1 naming it", rc == 1 and "none.params" in err, err)

# sweep: the rows, the spacing, the HAF of the hand algebra, the workspace of `tse-kin workspace`.
for prec, tol in (("double", 1e-9), ("float", 1e-4)):
    rc, out, err = run(["sweep", "k1", "0.2", "1", "5", "--grid", "5,4,5", "--precision", prec])
    lines = out.split("\n")[:-1]
    head_at = [i for i, l in enumerate(lines) if not l.startswith("#")]
    check(f"sweep {prec}: comments, then the header, then 5 rows", rc == 0 and err == "" and len(head_at) == 6
          and head_at[0] == len(lines) - 6 and lines[head_at[0]] == "param,value,haf,workspace,volume_m3", out)
    head, rows = table(out)
    want_v = [0.2, 0.4, 0.6000000000000001, 0.8, 1.0]
    check(f"sweep {prec}: k1 evenly from 0.2 to 1, the ends exact",
          [r.get("param") for r in rows] == ["k1"] * 5 and [r.get("value") for r in rows][-1] == "1"
          and all(abs(float(r["value"]) - w) < 1e-15 for r, w in zip(rows, want_v)), out)
    for r in rows:
        k1 = float(r["value"])
        want = haf_default_mean(k1=k1)
        check(f"sweep {prec}: HAF at k1 = {k1:g} is the hand algebra's mean over haf's heights",
              rel(float(r["haf"]), want) < tol, f"{r['haf']} vs {want}")
        f = write(f"sweep_k1_{k1:g}.params", f"k1 = {k1!r}\n")
        rc2, w, err2 = run(["workspace", "--design", f, "--grid", "5,4,5", "--precision", prec])
        reach, total = (int(x) for x in w.split("\n")[-2].split(",")[:2])
        check(f"sweep {prec}: workspace at k1 = {k1:g} is tse-kin workspace's fraction, unrounded, and its volume",
              float(r["workspace"]) == reach / total and r["volume_m3"] == w.split("\n")[-2].split(",")[3],
              f"{r['workspace']} vs {reach}/{total}, {r['volume_m3']} vs {w}")
rc, one, err = run(["sweep", "k1", "0.2647", "0.2647", "1"])
rc2, w, err2 = run(["workspace", "--grid", "16,24,32"])
reach, total = (int(x) for x in w.split("\n")[-2].split(",")[:2])
head, rows = table(one)
check("sweep's default grid is the paper's 16 x 24 x 32", rc == 0 and "16 x 24 x 32" in one and len(rows) == 1
      and float(rows[0]["workspace"]) == reach / total, one)
rc, a, err = run(["sweep", "k1", "0.1", "1", "7", "--grid", "4,6,5", "--jobs", "1"])
rc2, b, err2 = run(["sweep", "k1", "0.1", "1", "7", "--grid", "4,6,5", "--jobs", "3"])
check("sweep: --jobs 1 and --jobs 3 give the same rows in the same order",
      rc == rc2 == 0 and data_lines(a) == data_lines(b) and "1 thread" in a and "3 threads" in b, f"{a}\n{b}")
rc, out, err = run(["sweep", "k1", "0", "1", "3", "--grid", "3,3,3"])
head, rows = table(out)
check("sweep: an invalid design keeps its row with nan figures, the others go on",
      rc == 0 and len(rows) == 3 and rows[0] == {"param": "k1", "value": "0", "haf": "nan", "workspace": "nan",
                                                 "volume_m3": "nan"}
      and all(NUMBER.match(r["haf"]) and r["haf"] != "nan" for r in rows[1:]), out)
check("sweep: the invalid design's comment names the parameter and its rule",
      "# k1 = 0: not a valid design: k1 = 0, needs 0 < k1 <= 1" in out, out)
rc, out, err = run(["sweep", "eta_deg", "60", "95", "2", "--grid", "3,3,3"])
check("sweep in degrees: the refusal speaks degrees", rc == 0 and "eta_deg = 95" in out and
      "needs -90 < eta_deg < 90" in out and out.rstrip().endswith("eta_deg,95,nan,nan,nan"), out)
rc, out, err = run(["sweep", "alpha_min_deg", "20", "80", "2", "--grid", "3,3,3"])
check("sweep: a design refused for another parameter names that one",
      rc == 0 and "alpha_min_deg = 80: not a valid design: alpha_max = " in out, out)
rc, a, err = run(["sweep", "eta_deg", "-30", "60", "4", "--grid", "4,6,5"])
rc2, b, err2 = run(["sweep", "eta", repr(-math.pi / 6), repr(math.pi / 3), "4", "--grid", "4,6,5"])
ha, ra = table(a)
hb, rb = table(b)
check("sweep of eta_deg and of eta (radians) give the same figures",
      len(ra) == len(rb) == 4 and all(rel(float(x["haf"]), float(y["haf"])) < 1e-12 and x["workspace"] == y["workspace"]
                                      for x, y in zip(ra, rb)), f"{a}\n{b}")
for x in ra:
    eta = float(x["value"]) * DEG
    check(f"sweep: HAF at k2 = {float(x['value']):g} deg is the hand algebra's", rel(float(x["haf"]),
          haf_default_mean(eta=eta)) < 1e-9, x["haf"])
short = write("study_short.params", "s_max = 0.45\nk3 = 0.05\n")
rc, out, err = run(["sweep", "k4", "0.05", "0.2", "3", "--grid", "5,6,7", "--params", short])
head, rows = table(out)
for r in rows:
    k4 = float(r["value"])
    f = write(f"study_k4_{k4:g}.params", f"s_max = 0.45\nk3 = 0.05\nk4 = {k4!r}\n")
    rc2, w, err2 = run(["workspace", "--params", f, "--grid", "5,6,7"])
    reach, total = (int(x) for x in w.split("\n")[-2].split(",")[:2])
    check(f"sweep --params: k4 = {k4:g} on the file's design (stroke, k3) as workspace counts it",
          float(r["workspace"]) == reach / total and rel(float(r["haf"]), haf_default_mean(k3=0.05, k4=k4)) < 1e-9,
          f"{r} vs {reach}/{total}")

# The progress bar: on a terminal's stderr after a second, never on stdout, nothing in a pipe.
import pty  # noqa: E402
long_sweep = ["sweep", "k1", "0.1", "1", "120", "--grid", "16,24,32", "--jobs", "1"]
rc, quiet, quiet_err = run(long_sweep, timeout=600)
master, slave = pty.openpty()
t0 = time.monotonic()
proc = subprocess.run([TOOL] + long_sweep, stdout=subprocess.PIPE, stderr=slave, timeout=600)
elapsed = time.monotonic() - t0
os.close(slave)
bar = b""
while True:
    try:
        chunk = os.read(master, 65536)
    except OSError:
        break
    if not chunk:
        break
    bar += chunk
os.close(master)
check("sweep: no progress bar when stderr is not a terminal", rc == 0 and quiet_err == "", repr(quiet_err[:200]))
check("sweep: the same stdout with a terminal's stderr", proc.returncode == 0 and proc.stdout.decode() == quiet)
if elapsed > 1.5:
    check("sweep: a progress bar on a terminal's stderr, redrawn in place and erased",
          b"\rsweep k1 [" in bar and b"%" in bar and bar.endswith(b"\r"), repr(bar[:300]))
else:
    print(f"note: the long sweep took {elapsed:.2f} s, too short to see its progress bar")

# profile: the hand algebra on the axis.
zs = [0.5, 1.0, 1.4]
for prec, tol in (("double", 1e-9), ("float", 1e-4)):
    rc, out, err = run(["profile", "--z", ",".join(map(str, zs)), "--precision", prec])
    head, rows = table(out)
    check(f"profile {prec}: header and a row per height", rc == 0 and err == "" and head ==
          ["z", "sv1", "sv2", "sv3", "sv4", "sv5", "sv6", "sigma_z", "mu_min", "nu"] and len(rows) == 3, out)
    for z, r in zip(zs, rows):
        sv = [float(r[f"sv{k}"]) for k in range(1, 7)]
        sig = vertical(z)[2]
        check(f"profile {prec} z={z}: sigma_z and mu_min of the hand algebra",
              float(r["z"]) == z and rel(float(r["sigma_z"]), sig) < tol and abs(float(r["mu_min"]) - mu_axis(z)) < tol,
              f"{r} vs {sig}, {mu_axis(z)}")
        check(f"profile {prec} z={z}: six positive singular values, descending, sigma_z one of them",
              all(a >= b > 0 for a, b in zip(sv, sv[1:])) and any(rel(x, sig) < tol for x in sv), repr(sv))
        check(f"profile {prec} z={z}: nu in (0, 1]", 0 < float(r["nu"]) <= 1, r["nu"])
rc, out, err = run(["jacobian"], "0,0,1,0,0,0\n")
jsv = [float(x) for x in out.strip().split(",")[38:44]]
rc, out, err = run(["profile", "--z", "1"])
head, rows = table(out)
check("profile's singular values are jacobian's at the same pose",
      all(rel(float(rows[0][f"sv{k + 1}"]), jsv[k]) < 1e-12 for k in range(6)), f"{rows} vs {jsv}")
rc, out, err = run(["profile"])
head, rows = table(out)
z = [float(r["z"]) for r in rows]
check("profile default: 60 heights from L sin(alpha_min) to L sin(alpha_max), both exact, evenly",
      rc == 0 and len(rows) == 60 and abs(z[0] - Z_LO) < 1e-12 and abs(z[-1] - Z_HI) < 1e-12
      and all(abs(b - a - (Z_HI - Z_LO) / 59) < 1e-12 for a, b in zip(z, z[1:])), out[:300])
rc, out, err = run(["profile", "--n", "5"])
check("profile --n 5: five heights", rc == 0 and len(table(out)[1]) == 5, out)
rc, out, err = run(["profile", "--z", "3"])
check("profile above full extension: nan for every figure", rc == 0 and data_lines(out)[1] == "3" + ",nan" * 9, out)

# margins: the row rules, ik's verdict, the margins of the axis.
rc, out, err = run(["margins"], "abc\n0,0,1,0,0,0\n1,2\n")
outl = out.split("\n")[:-1]
check("margins: one line per line, malformed ones invalid,0 and four nan",
      rc == 0 and len(outl) == 3 and invalid_line(outl[0], 4) and invalid_line(outl[2], 4) and
      outl[1].startswith("ok,0,"), out)
rc, out, err = run(["margins"], "x,y,z,roll,pitch,yaw\n0,0,1,0,0,0\n")
check("margins: a header answered by its own", out.split("\n")[0] == "status,scissor,mu1,mu2,mu3,nu", out)
for prec, tol in (("double", 1e-9), ("float", 1e-4)):
    axis = [0.2, 0.5, 1.0, 1.4, 1.65]  # 0.2 and 1.65 outside the stops: alpha, margins still given
    rc, out, err = run(["margins", "--precision", prec], "".join(f"0,0,{z},0,0,0\n" for z in axis))
    rc2, pr, err2 = run(["profile", "--precision", prec, "--z", ",".join(map(str, axis))])
    nus = [r["nu"] for r in table(pr)[1]]
    for z, line, nu in zip(axis, out.split("\n"), nus):
        f = fields(line)
        want = "ok" if Z_LO < z < Z_HI else "alpha"
        check(f"margins {prec} z={z}: {want}, each mu of the hand algebra whatever the stops say, nu as profile's",
              f[0] == want and all(abs(float(x) - mu_axis(z)) < tol for x in f[2:5]) and
              abs(float(f[5]) - float(nu)) < tol, f"{line} vs {mu_axis(z)}, {nu}")
rc, out, err = run(["margins"], "\n".join(poses[:120]) + "\n")
rc2, ik_out, err2 = run(["ik"], "\n".join(poses[:120]) + "\n")
check("margins: status and scissor are ik's for every pose",
      rc == rc2 == 0 and [l.split(",")[:2] for l in out.split("\n")] == [l.split(",")[:2] for l in ik_out.split("\n")])
check("margins: every line status,scissor and four numbers", all(well_formed(l, 4) for l in out.split("\n")[:-1]))

# workspace --points: the grid itself, and the points workspace counts.
for orient in ("0,0,0", "0,0.3490658503988659,0"):
    rc, out, err = run(["workspace", "--points", "--grid", "4,6,5", "--orientation", orient])
    head, rows = table(out)
    rc2, w, err2 = run(["workspace", "--grid", "4,6,5", "--orientation", orient])
    reach = int(w.split("\n")[-2].split(",")[0])
    check(f"workspace --points ({orient}): header and 4*6*5 rows", rc == 0 and
          head == ["x", "y", "z", "status", "scissor"] and len(rows) == 120, out[:300])
    grid = [(PROTO["L"] / 2 * i / 3, 2 * math.pi * j / 6, PROTO["L"] * k / 4)
            for k in range(5) for i in range(4) for j in range(6)]
    check(f"workspace --points ({orient}): the paper's grid, Z then r then phi",
          len(rows) == 120 and all(abs(float(r["x"]) - ri * math.cos(p)) < 1e-12 and
                                   abs(float(r["y"]) - ri * math.sin(p)) < 1e-12 and abs(float(r["z"]) - zk) < 1e-12
                                   for r, (ri, p, zk) in zip(rows, grid)), out[:400])
    check(f"workspace --points ({orient}): its ok rows are what workspace counts",
          sum(r["status"] == "ok" for r in rows) == reach and reach > 0, f"{reach}")
    check(f"workspace --points ({orient}): statuses named, scissor 0 exactly when ok",
          all(r["status"] in STATUSES and (r["status"] == "ok") == (r["scissor"] == "0") for r in rows))
    check(f"workspace --points ({orient}): no negative zero, the count last",
          "-0," not in out and out.split("\n")[-2].startswith(f"# reachable,total,fraction,volume_m3: {reach},120,"),
          out[-200:])
    # The volume: the cells of the ok rows, each by hand (rings cut halfway between the radii
    # 0, L/6, L/3, L/2 and layers halfway between the heights 0, L/4, .., L; 6 sectors), and
    # workspace's own figure.
    dr, dz = L / 6, L / 4
    def cell(r, z):
        i, k = round(r / dr), round(z / dz)
        r_lo, r_hi = max(0, (i - 0.5) * dr), min(L / 2, (i + 0.5) * dr)
        z_lo, z_hi = max(0, (k - 0.5) * dz), min(L, (k + 0.5) * dz)
        return math.pi / 6 * (r_hi ** 2 - r_lo ** 2) * (z_hi - z_lo)
    by_hand = sum(cell(math.hypot(float(r["x"]), float(r["y"])), float(r["z"])) for r in rows if r["status"] == "ok")
    said = float(out.split("\n")[-2].split(": ")[1].split(",")[3].split()[0])
    check(f"workspace --points ({orient}): its volume is the ok rows' cells by hand, and workspace's",
          rel(said, by_hand) < 1e-12 and rel(float(w.split("\n")[-2].split(",")[3]), by_hand) < 1e-12,
          f"{said} {w.splitlines()[-1]} vs {by_hand}")

# ---------------------------------------------------------------- plan and check (issue 25)
for cmd in ("plan", "check"):
    for form in ([cmd, "--help"], ["help", cmd], [cmd, "x.csv", "--bogus", "-h"]):
        rc, out, err = run(form)
        check(f"{' '.join(form)} prints its usage", rc == 0 and out.startswith(f"usage: tse-kin {cmd}") and err == "",
              f"rc {rc} {out[:60]!r}")
rc, out, err = run(["--help"])
check("tse-kin --help lists plan, check, --blend and --period",
      all(f"\n  {c} " in out for c in ("plan", "check")) and "--blend" in out and "--period" in out, out)
vert = write("vert.csv", "# a straight rise\nx,y,z,roll,pitch,yaw\n0,0,0.9,0,0,0\n\n0,0,1.2,0,0,0\n")
for args, name, says in [(["plan"], "plan without a file", "FILE"), (["plan", vert, vert], "plan with two files", "one FILE"),
                         (["plan", "--blend", "-1", vert], "a negative blend", "--blend"),
                         (["plan", "--period", "0", vert], "a zero period", "--period"),
                         (["plan", "--period", "2", vert], "a period above 1 s", "--period"),
                         (["check", "--blend", "0.1", vert], "check --blend", "--blend"),
                         (["plan", "--precision", "float", vert], "plan --precision", "--precision"),
                         (["plan", "--jerk", "0", vert], "a zero jerk limit", "--jerk"),
                         (["plan", "--jerk", "slides", vert], "a jerk limit that is no number", "--jerk"),
                         (["check", "--jerk", "10", vert], "check --jerk", "--jerk")]:
    rc, out, err = run(args)
    check(f"{name} exits 2 naming {says!r}", rc == 2 and out == "" and says in err, f"rc {rc} {err!r}")
for text, line, says, name in [
        ("x,y,z,roll,pitch,yaw\n0,0,1,0,0,0\n0,0,abc,0,0,0\n", 3, "column 3 (z)", "a non-number"),
        ("0,0,1,0,0,0\n0,0,1.1,0,0\n", 2, "5 columns", "a short row"),
        ("z,y,x,yaw,pitch,roll,t\n1,0,0,0,0,0,\n1.1,0,0,0,0,0,0.5\n1.2,0,0,0,0,0,0.4\n", 4, "does not come after",
         "times out of order"),
        ("x,y,z,roll,pitch,yaw,v\n0,0,1,0,0,0,0\n0,0,1.1,0,0,0,\n", 2, "above 0", "a zero speed cap"),
        ("x,y,z,roll,pitch,yaw,x\n", 1, "named twice", "a column named twice"),
        ("x,y,z,roll,pitch\n", 1, "no column yaw", "a header without yaw"),
        ("0,0,1,0,0,4\n0,0,1,0,0,0\n", 1, "wire's range", "an angle beyond the wire")]:
    path = write("bad_waypoints.csv", text)
    rc, out, err = run(["plan", path])
    check(f"plan of {name} exits 1 naming FILE:LINE and {says!r}, writing nothing",
          rc == 1 and out == "" and f"{path}:{line}:" in err and says in err, f"rc {rc} {err!r}")
rc, out, err = run(["plan", write("one.csv", "0,0,1,0,0,0\n")])
check("plan of one waypoint exits 1", rc == 1 and out == "" and "at least 2" in err, err)
rc, out, err = run(["plan", write("outside.csv", "0,0,1,0,0,0\n0,0,1.1,0,0,0\n0,0,1.7,0,0,0\n")])
check("plan of a waypoint outside the workspace exits 3 naming it, writing nothing",
      rc == 3 and out == "" and "waypoint 3 (line 3)" in err, f"rc {rc} {err!r}")
rc, out, err = run(["plan", write("between.csv", "0.15,0,0.32,0,0,0\n0,0,0.32,0,0,0\n")])
check("plan of a path leaving the workspace between two waypoints names both and the angle stop",
      rc == 3 and out == "" and "waypoint 1 (line 1) to waypoint 2 (line 2)" in err and "alpha" in err, f"rc {rc} {err!r}")
rc, out, err = run(["plan", write("late.csv", "x,y,z,roll,pitch,yaw,t\n0,0,0.9,0,0,0,0\n0,0,1.2,0,0,0,0.2\n")])
check("plan of a time the slides cannot keep exits 3 naming the waypoint and the earliest time",
      rc == 3 and "waypoint 2 (line 3)" in err and "need until" in err, f"rc {rc} {err!r}")
rc, out, err = run(["plan", vert])
traj = write("vert.traj", out)
rows = [r for r in out.splitlines() if r and r[0].isdigit()]
check("plan writes a header and rows of seven numbers, in whole microseconds and micrometres",
      rc == 0 and "\nt,x,y,z,roll,pitch,yaw\n" in out and len(rows) > 10 and
      all(len(r.split(",")) == 7 and all(len(f.split(".")[1]) == 6 for f in r.split(",")) for r in rows), out[:300])
check("plan's first row holds the first waypoint traj_lead (0.2 s) in, its last is the last waypoint",
      rows[0] == "0.200000,0.000000,0.000000,0.900000,0.000000,0.000000,0.000000" and
      rows[-1].endswith(",0.000000,0.000000,1.200000,0.000000,0.000000,0.000000"), f"{rows[0]} {rows[-1]}")
s_lo, s_hi = vertical(0.9)[0], vertical(1.2)[0]
# The step generator's speed limit in effect; the rows' 0.95 of slide_amax (docs/controller.md) x 10 ms /
# 20 ms: rows 20 ms apart, each row's change of speed seen whole over the validator's 10 ms stride (plan.h).
ds, v, a = abs(s_hi - s_lo), 0.1392, 0.95 * 0.5
T = float(rows[-1].split(",")[0]) - 0.2
check("plan of the vertical line takes the bang-bang time of its slides (rows 20 ms apart) within 2 %",
      abs(T / (ds / v + v / a) - 1) < 0.02, f"{T} vs {ds / v + v / a}")
rc, out, err = run(["check", traj])
check("check accepts what plan wrote, saying the peaks", rc == 0 and "accepted" in out and err == "", f"rc {rc} {err!r}")
# With the controller's own slide jerk limit (slide_amax x plate_jmax / plate_amax = 10 m/s^3): the
# law smoothed over at least a / J, so that much longer at least, its jerk said and within it.
rc, out, err = run(["plan", "--jerk", "controller", vert])
jrows = [r for r in out.splitlines() if r and r[0].isdigit()]
jpeak = re.search(r"jerk up to ([0-9.]+)% of 10 m/s\^3", out)
check("plan --jerk controller takes a / J longer or more, its slides' jerk within 10 m/s^3",
      rc == 0 and "slides' jerk within 10 m/s^3" in out and jpeak and float(jpeak.group(1)) <= 100.0 and
      float(jrows[-1].split(",")[0]) - 0.2 >= T + a / 10.0 - 0.002, f"rc {rc} {err!r} {out[:400]!r}")
rc, out, err = run(["check", write("vert_jerk.traj", out)])
check("check accepts the jerk-limited plan", rc == 0, f"rc {rc} {err!r}")
slow = write("slow.params", "slide_amax = 0.5\n")
rc, out, err = run(["check", "--params", slow, traj])
check("check with a lower slide_amax refuses it: exit 3, FILE:LINE, tsectl's words, the slide and how far over",
      rc == 3 and out == "" and f"{traj}:" in err and "rejected: timing" in err and "slide_amax" in err, f"rc {rc} {err!r}")
rc, out, err = run(["plan", "--params", slow, vert])
# The least: the path a trajectory's stop covers from the speed limit (docs/controller.md, "Stops":
# ln 20 / 0.95 (1 / 0.95 - 1 / ln 20) v / slide_amax), two control periods and the planner's 12 ms,
# over the 28 rows the host keeps queued (plan.h), in whole microseconds up (v is given to 4 digits).
reach = math.log(20) / 0.95 * (1 / 0.95 - 1 / math.log(20)) * v / 0.5
least = math.ceil((reach + 0.002 + 0.012) / 28 * 1e6) / 1e6
named = re.search(r"use --period ([0-9.]+)", err)
check("plan under that parameter file refuses rows 20 ms apart (the controller's queue), naming the least",
      rc == 3 and out == "" and named and abs(float(named.group(1)) - least) < 1e-5, f"rc {rc} {err!r} {least}")
rc, out, err = run(["plan", "--params", slow, "--period", "0.03", vert])
check("plan under that parameter file takes longer, and check with it accepts it",
      rc == 0 and float([r for r in out.splitlines() if r and r[0].isdigit()][-1].split(",")[0]) > T + 0.05 and
      run(["check", "--params", slow, write("vert_slow.traj", out)])[0] == 0, f"rc {rc} {err!r}")
rc, out, err = run(["check", write("jump.traj", "t,x,y,z,roll,pitch,yaw\n0.02,0,0,1,0,0,0\n0.04,0,0,1.1,0,0,0\n")])
check("check of a jump exits 3 naming its line and the slide's speed limit",
      rc == 3 and "jump.traj:3: row 2" in err and "speed" in err, f"rc {rc} {err!r}")
rc, out, err = run(["check", write("badrow.traj", "0.02,0,0,1,0,0,0\n0.01,0,0,1,0,0,0\n")])
check("check of a row out of time order exits 1 naming its line", rc == 1 and "badrow.traj:2:" in err, f"rc {rc} {err!r}")
rc, out, err = run(["check", "--params", write("bad.params", "slide_amax = x\n"), traj])
check("check with a bad parameter file exits 1 naming its line", rc == 1 and "bad.params:1:" in err, f"rc {rc} {err!r}")
# The examples README plans: each accepted first time by check, most of its rows near a limit.
EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "planner", "examples")
for name, extra in (("circle", []), ("eight", []), ("helix", []), ("square", ["--blend", "0.002"])):
    rc, out, err = run(["plan"] + extra + [os.path.join(EXAMPLES, f"{name}.csv")])
    near = re.search(r"rows with some slide at >= 90% of a limit: ([0-9.]+)%", out)
    check(f"plan of planner/examples/{name}.csv: rows with a slide near a limit >= 60 %",
          rc == 0 and near and float(near.group(1)) >= 60, f"rc {rc} {err!r} {out[:300]!r}")
    rc, out, err = run(["check", write(f"{name}.traj", out)])
    check(f"check accepts the plan of {name}.csv", rc == 0, f"rc {rc} {err!r}")

print(f"{passes} passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
