#!/usr/bin/python3
"""The design study of docs/analysis.md for one design: runs tse-kin, writes CSVs, draws PNGs.

Run through scripts/study.sh, which builds tse-kin and finds Debian's python3 with matplotlib.
Every figure is tse-kin's; this script only chooses the designs, reads the CSV and draws.  The
design's kinematic values (to label every line and figure, mark it on the sweeps and size the
margin maps) are read from its parameter file by the one reader (tse.kin.Params.from_file, as
tse-kin --design reads it) and confirmed against tse-kin before use.  The paper's figures and the readings that try to explain
them are printed and drawn only when the design is the paper's prototype (every kinematic value
the default); every other label carries the design's own values.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import time

# The paper's figures for its prototype (its sections V and VI), drawn beside ours only when the
# design is the prototype.
PAPER = {"haf": 11.487, "workspace": 0.28}
# The four sweeps of the paper's study: (name, key, from, to), the range widened to the design.
SWEEPS = [("k1", "k1", 0.1, 1.0), ("k2", "eta_deg", -85.0, 85.0), ("k3", "k3", 0.0, 0.2),
          ("k4", "k4", 0.02, 0.3)]
# Designs whose vertical profiles are compared (the design under study is added to each list).
PROFILE_VARIANTS = {"k1": [0.15, 0.4, 0.7, 1.0], "eta_deg": [-60.0, -30.0, 0.0, 60.0, 75.0],
                    "k3": [0.0, 0.05, 0.1, 0.15], "k4": [0.05, 0.2, 0.3]}
# The slide angles of the paper's figure of internal singularities (its Fig. 7: a negative and a
# positive one; 60 degrees is where it sees the singular behaviour begin).
MARGIN_ETAS = [-30.0, 60.0]
PITCH_DEG = 20.0   # the tilted workspace drawn (the paper tilts by 75 degrees; see docs/analysis.md)
PAPER_PITCH_DEG = 75.0  # the paper's Fig. 8-d tilt, counted only: the plate nearly in a scissor's plane
# The stroke taken out of the picture: s_max = FREE_STROKE_L L / cos(eta), ten times the scale of a
# slide's travel for a scissor of length L at the slide angle eta (on the axis s = l0 cos(alpha) /
# cos(eta) with l0 <= L), so that no design of the k1 sweep reaches it.
FREE_STROKE_L = 10.0
# The stroke readings of the workspace: the design's s_max times these (the prototype's 0.9 m gives
# 0.8, 0.85, 0.95 and 1 m, where the paper's 0.28 is found).
STROKE_SCALES = [8 / 9, 8.5 / 9, 9.5 / 9, 10 / 9]

# Slide angles whose grid points are sorted by status: why the workspace changes with k2.
STATUS_ETAS = [float(e) for e in range(-80, 81, 10)]
STATUSES = ["ok", "unreachable", "below", "alpha", "stroke", "singular", "degenerate", "noconverge"]

# "volume": the grid the workspace's volume is quoted on, finer than the paper's (whose cells,
# 5.8 cm x 5.6 cm with 23 cm of arc at the rim for the prototype, put its volume 7 % high).
FULL = {"grid": "16,24,32", "designs": 50, "draw": "21,60,41", "map": 161, "heights": 100, "status_etas": STATUS_ETAS,
        "volume": "31,72,61"}
QUICK = {"grid": "4,6,5", "designs": 5, "draw": "4,8,5", "map": 15, "heights": 8,
         "status_etas": [-60.0, 0.0, 60.0], "volume": "6,12,9"}


# The kinematics package (python/tse), for the design's values, its parameters' names and their
# spellings: the one reader tse-kin uses, not a copy.  Set by load_kin.
tse_kin = None
KIN_KEYS = []    # the kinematic parameters' SI names, in the library's order
ANGLES = []      # those that a file may also give in degrees
SPELLINGS = {}   # every key a file takes -> (SI name, in degrees)


def load_kin(root, tse_kin_path):
    """tse.kin over the libtse_kin.so built beside tse-kin (<build>/python), unless TSE_KIN_LIB says."""
    global tse_kin, KIN_KEYS, ANGLES, SPELLINGS
    if "TSE_KIN_LIB" not in os.environ:
        build = os.path.dirname(os.path.dirname(os.path.abspath(tse_kin_path)))
        os.environ["TSE_KIN_LIB"] = os.path.join(build, "python", "libtse_kin.so")
    if not os.path.isfile(os.environ["TSE_KIN_LIB"]):
        fail(f"no kinematics library at {os.environ['TSE_KIN_LIB']} (build the tse_kin_py target, or set "
             "TSE_KIN_LIB)", 2)
    sys.path.insert(0, os.path.join(root, "python"))
    import tse.kin
    tse_kin = tse.kin
    KIN_KEYS = list(tse_kin.Params().as_dict())
    SPELLINGS = tse_kin.spellings()
    ANGLES = [name for name, deg in SPELLINGS.values() if deg]


def fail(msg, code=1):
    print(f"study: {msg}", file=sys.stderr)
    sys.exit(code)


class Kin:
    """tse-kin, its failures turned into the study's (exit 1 with its message)."""

    def __init__(self, path):
        self.path = path

    def run(self, args, stdin=None):
        r = subprocess.run([self.path] + args, input=stdin, capture_output=True, text=True)
        if r.returncode != 0:
            fail(f"tse-kin {' '.join(args)} failed (exit {r.returncode}):\n{r.stderr.strip()}", 1)
        return r.stdout


def table(text):
    """Rows of a tse-kin CSV ('#' lines skipped, the first other line the header) as dicts; numbers
    become floats, words (statuses) stay."""
    lines = [l for l in text.splitlines() if l and not l.startswith("#")]
    out = []
    for rec in csv.DictReader(lines):
        row = {}
        for k, v in rec.items():
            try:
                row[k] = float(v)
            except ValueError:
                row[k] = v
        out.append(row)
    return out


def key_of(line):
    """The key a parameter-file line sets, or None (comment, blank)."""
    body = line.lstrip("\ufeff").split("#", 1)[0]
    if "=" not in body:
        return None
    return body.split("=", 1)[0].strip()


def design_values(kin, path):
    """The design's kinematic values (the prototype's, then the file's, read by the one reader as
    tse-kin --design reads it), with the angles also in degrees."""
    try:
        v = (kin.Params.from_file(path, design=True) if path else kin.Params()).as_dict()
    except (OSError, ValueError) as e:
        fail(str(e), 1)
    for k in ANGLES:
        v[k + "_deg"] = math.degrees(v[k])
    return v


def same(a, b):
    return abs(a - b) <= 1e-12 * abs(b)


def variant(base_text, key, value):
    """The base file with `key` (in any of its parameter's spellings and cases) set to value."""
    name = SPELLINGS[key][0]
    drop = {k.lower() for k, (n, _) in SPELLINGS.items() if n == name}
    kept = [l for l in base_text.splitlines() if (key_of(l) or "").lower() not in drop]
    return "\n".join(kept + [f"{key} = {value!r}", ""])


def fmt(x):
    return "nan" if x != x else f"{x:.4g}"


class Study:
    def __init__(self, a):
        self.a = a
        self.kin = Kin(a.tse_kin)
        self.out = a.out
        self.csv = os.path.join(a.out, "csv")
        os.makedirs(os.path.join(self.csv, "params"), exist_ok=True)
        self.base_text = ""
        if a.params:
            try:
                with open(a.params, encoding="utf-8") as fh:
                    self.base_text = fh.read()
            except OSError as e:
                fail(f"cannot read the parameter file: {e}", 1)
        # The user's own file where tse-kin reads the design itself, so that its messages name it.
        self.design_file = a.params or os.path.join(self.csv, "params", "prototype.params")
        if not a.params:
            self.write(self.design_file, "")
        self.summary = []
        self.jobs = ["--jobs", str(a.jobs)] if a.jobs else []
        self.name = os.path.basename(a.params) if a.params else "prototype"

    @property
    def free_stroke(self):
        return FREE_STROKE_L * self.values["L"] / math.cos(self.values["eta"])

    def write(self, path, text):
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(text)

    def note(self, line):
        print(line)
        self.summary.append(line)

    def params_file(self, name, key=None, value=None):
        if key is None:
            return self.design_file
        path = os.path.join(self.csv, "params", f"{name}.params")
        self.write(path, variant(self.base_text, key, value))
        return path

    def save(self, name, text):
        self.write(os.path.join(self.csv, name), text)
        return table(text)

    # ------------------------------------------------------------------ the runs
    def workspace_figures(self, path, grid, orientation=None):
        """tse-kin workspace's summary: reachable points, total, fraction, volume [m^3]."""
        args = ["workspace", "--design", path, "--grid", grid]
        if orientation is not None:
            args += ["--orientation", orientation]
        last = self.kin.run(args).strip().splitlines()[-1].split(",")
        reach, total = int(last[0]), int(last[1])
        return reach, total, reach / total, float(last[3])

    def design(self):
        """The design's own figures, and its parameter values confirmed by tse-kin."""
        defaults = tse_kin.Params().as_dict()
        self.values = design_values(tse_kin, self.a.params)
        self.is_proto = all(same(self.values[k], defaults[k]) for k in KIN_KEYS)
        haf_text = self.kin.run(["haf", "--design", self.design_file])
        self.write(os.path.join(self.csv, "haf.txt"), haf_text)  # tse-kin haf's own report, its columns in a '#' line
        self.haf_mean = float(haf_text.strip().splitlines()[-1].split(",")[1])
        self.ws_reach, self.ws_total, self.ws, self.ws_volume_grid = self.workspace_figures(self.design_file,
                                                                                            self.a.grid)
        self.volume = self.workspace_figures(self.design_file, self.a.volume)[3]
        # A one-design sweep at the value read must be the design itself, to the last digit.
        for key in KIN_KEYS:
            v = self.values[key]
            row = table(self.kin.run(["sweep", key, repr(v), repr(v), "1", "--design", self.design_file,
                                      "--grid", self.a.grid]))[0]
            got = (row["haf"], row["workspace"], row["volume_m3"])
            want = (self.haf_mean, self.ws, self.ws_volume_grid)
            if any(not (a == b or (a != a and b != b)) for a, b in zip(got, want)):
                fail(f"could not read {key} from the parameter file (read {v!r}; the design's HAF, workspace and "
                     f"volume {want} are not those of the design with {key} = {v!r}: {got})")

    def label(self):
        """The design in one line, for titles: its name and the values the study varies or is bound by."""
        v = self.values
        return (f"{self.name}: L = {v['L']:g} m, k1 = {v['k1']:g}, k2 = {v['eta_deg']:.4g} deg, k3 = {v['k3']:g}, "
                f"k4 = {v['k4']:g}, stroke {v['s_min']:g} .. {v['s_max']:g} m, "
                f"stops {v['alpha_min_deg']:.4g} .. {v['alpha_max_deg']:.4g} deg")

    def sweeps(self):
        n = self.a.designs
        self.sweep = {}
        t0 = time.monotonic()
        for name, key, lo, hi in SWEEPS:
            v = self.values[key]
            lo, hi = min(lo, v), max(hi, v)
            self.sweep[name] = self.save(f"sweep_{name}.csv", self.kin.run(
                ["sweep", key, repr(lo), repr(hi), str(n), "--design", self.design_file, "--grid", self.a.grid]
                + self.jobs))
        self.sweep_seconds = time.monotonic() - t0
        g = self.a.grid.replace(",", " x ")
        jobs = self.a.jobs or os.cpu_count()
        self.note(f"study: 4 sweeps (k1, k2, k3, k4) x {n} designs on the {g} grid "
                  f"({jobs} threads): {self.sweep_seconds:.2f} s")
        # The stroke taken out of the picture: the workspace trend of k1 from the scissors alone.
        free = self.params_file("free_stroke", "s_max", self.free_stroke)
        lo, hi = min(0.1, self.values["k1"]), max(1.0, self.values["k1"])
        self.sweep["k1_free"] = self.save("sweep_k1_free_stroke.csv", self.kin.run(
            ["sweep", "k1", repr(lo), repr(hi), str(n), "--design", free, "--grid", self.a.grid] + self.jobs))

    def profiles(self):
        h = str(self.a.heights)
        self.profile = self.save("profile.csv", self.kin.run(["profile", "--design", self.design_file, "--n", h]))
        self.variants = {}
        for key, values in PROFILE_VARIANTS.items():
            vals = sorted(set(values + [self.values[key]]))
            self.variants[key] = []
            for v in vals:
                f = self.params_file(f"{key}_{v:g}", key, v)
                rows = self.save(f"profile_{key}_{v:g}.csv", self.kin.run(["profile", "--design", f, "--n", h]))
                self.variants[key].append((v, rows))

    def workspace(self):
        self.points, self.points_volume = {}, {}
        for name, pitch in (("level", 0.0), (f"pitch{PITCH_DEG:g}", PITCH_DEG)):
            o = f"0,{math.radians(pitch)!r},0"
            text = self.kin.run(["workspace", "--points", "--design", self.design_file, "--grid", self.a.draw,
                                 "--orientation", o])
            self.points[name] = (pitch, self.save(f"points_{name}.csv", text))
            # Its last line: "# reachable,total,fraction,volume_m3: R,T,F,V[ (paper ...)]".
            self.points_volume[name] = float(text.strip().splitlines()[-1].split(":", 1)[1].split(",")[3].split()[0])
        # Every point of the paper's grid by status, for a range of slide angles.
        lines = ["eta_deg," + ",".join(STATUSES)]
        self.status_k2 = []
        for eta in self.a.status_etas:
            f = self.params_file(f"eta_{eta:g}", "eta_deg", eta)
            rows = table(self.kin.run(["workspace", "--points", "--design", f, "--grid", self.a.grid]))
            counts = [sum(1 for r in rows if r["status"] == st) for st in STATUSES]
            self.status_k2.append((eta, [c / len(rows) for c in counts]))
            lines.append(f"{eta:g}," + ",".join(str(c) for c in counts))
        self.write(os.path.join(self.csv, "status_k2.csv"), "\n".join(lines) + "\n")
        # The paper's own tilt, counted only: at 75 degrees the plate lies almost in a scissor's plane.
        self.ws_tilted = self.workspace_figures(self.design_file, self.a.grid,
                                                f"0,{math.radians(PAPER_PITCH_DEG)!r},0")
        self.volume_tilted = self.workspace_figures(self.design_file, self.a.volume,
                                                    f"0,{math.radians(PAPER_PITCH_DEG)!r},0")[3]

    def margins(self):
        L = self.values["L"]
        m = self.a.map
        xs = [-L / 2 + L * i / (m - 1) for i in range(m)]
        zs = [L * (k + 1) / m for k in range(m)]
        poses = [(x, z) for z in zs for x in xs]
        # A header line in, the output's header line out (tse-kin's row rules).
        stdin = "x,y,z,roll,pitch,yaw\n" + "".join(f"{x!r},0,{z!r},0,0,0\n" for x, z in poses)
        self.maps = {}
        for eta in MARGIN_ETAS:
            f = self.params_file(f"eta_{eta:g}", "eta_deg", eta)
            rows = table(self.kin.run(["margins", "--design", f], stdin))
            lines = ["x,z,status,scissor,mu1,mu2,mu3,nu"]
            for (x, z), r in zip(poses, rows):
                lines.append(f"{x!r},{z!r},{r['status']},{int(r['scissor'])},{r['mu1']!r},{r['mu2']!r},"
                             f"{r['mu3']!r},{r['nu']!r}")
            self.write(os.path.join(self.csv, f"margins_eta_{eta:g}.csv"), "\n".join(lines) + "\n")
            self.maps[eta] = (xs, zs, rows)

    def haf_readings(self):
        """What the paper's 11.487 could have been: HAF read other ways, at tse-kin haf's heights.

        tse-kin gives sigma_z and the singular values of each reference design; the readings that
        change an equation (the coefficient as the paper prints it) or compare other things than
        heights (slide travel, equal slides) use the closed form of the vertical axis
        (docs/analysis.md derives it): F2 there is D s^2 - 2 u0 s + r^2 + Z^2 - L^2 = 0 with
        r = (k4 - k3) L, u0 = r sin(eta), D = 1 - 2 g (1 + cos 2 eta)."""
        rows = [l.split(",") for l in open(os.path.join(self.csv, "haf.txt")).read().splitlines()
                if l and not l.startswith("#") and not l.startswith("haf")]
        z = [float(r[0]) for r in rows]
        sig = [float(r[1]) for r in rows]
        sig_r = [float(r[2]) for r in rows]
        zs = ",".join(repr(x) for x in z)
        v = self.values
        L, k1, eta = v["L"], v["k1"], math.radians(v["eta_deg"])
        rigid = self.params_file("ref_k1_1", "k1", 1.0)
        ref2_path = os.path.join(self.csv, "params", "ref_k1_1_k2_0.params")
        self.write(ref2_path, variant(variant(self.base_text, "k1", 1.0), "eta_deg", 0.0))

        def profile(path):
            return table(self.kin.run(["profile", "--design", path, "--z", zs]))

        mine, ref1, ref2 = profile(self.design_file), profile(rigid), profile(ref2_path)
        mean = lambda xs: sum(xs) / len(xs)
        r = (v["k4"] - v["k3"]) * L
        u0 = r * math.sin(eta)

        def closed(k1_, coef):
            g = coef(k1_)
            D = 1 - 2 * g * (1 + math.cos(2 * eta))
            out = []
            for zz in z:
                K = L * L - r * r - zz * zz
                out.append(math.sqrt((u0 * u0 + D * K) / (u0 * u0 + K)) if u0 * u0 + D * K > 0 else float("nan"))
            return out

        contract = lambda k: (1 - 1 / (k * k)) / 4
        printed = lambda k: 1 - 1 / (4 * k * k)

        # Equal slide positions: dz/ds = (D s - u0) / z on the axis, design over k1 = 1, over the
        # design's slides between the stops' heights.
        def dz_ds(D, s):
            zz2 = L * L - r * r + 2 * u0 * s - D * s * s
            return (D * s - u0) / math.sqrt(zz2) if zz2 > 0 else float("nan")
        Dd = 1 - 2 * contract(k1) * (1 + math.cos(2 * eta))
        s_lo = (u0 + math.sqrt(u0 * u0 - Dd * (r * r + z[-1] ** 2 - L * L))) / Dd
        s_hi = (u0 + math.sqrt(u0 * u0 - Dd * (r * r + z[0] ** 2 - L * L))) / Dd
        eq_s = [dz_ds(Dd, s) / dz_ds(1.0, s) for s in (s_lo + (s_hi - s_lo) * i / 20 for i in range(21))]
        eq_s = [x for x in eq_s if x == x]

        # The k1 at which the squared reading would give the paper's figure (bisection: HAF falls with k1).
        lo, hi = 0.05, 1.0
        for _ in range(60):
            mid = (lo + hi) / 2
            if mean([h * h for h in closed(mid, contract)]) > PAPER["haf"]:
                lo = mid
            else:
                hi = mid
        readings = [
            ("sigma_z / sigma_z(k1 = 1) at the same Z (ours, docs/kinematics.md)",
             [a / b for a, b in zip(sig, sig_r)]),
            ("the same, squared", [(a / b) ** 2 for a, b in zip(sig, sig_r)]),
            ("reference k1 = 1 and k2 = 0 (the paper's k_i,0 for both)",
             [a["sigma_z"] / b["sigma_z"] for a, b in zip(mine, ref2)]),
            ("reference k1 = 1 and k2 = 0, squared", [(a["sigma_z"] / b["sigma_z"]) ** 2 for a, b in zip(mine, ref2)]),
            ("largest singular value sv1 instead of sigma_z", [a["sv1"] / b["sv1"] for a, b in zip(mine, ref1)]),
            ("|ds/dZ| ratio (dq/dp instead of dp/dq)", [b / a for a, b in zip(sig, sig_r)]),
            ("the coefficient as the paper prints it, 1 - (L/l0)^2 / 4 (its k1 = 1 reference has no "
             "solution on the axis; the contract's is kept there)", closed(k1, printed)),
            ("equal slide positions instead of equal heights (dZ/ds ratio over the design's slides)", eq_s),
            ("slide travel over the stops' height range, k1 = 1 over the design (= 1/k1)", [1 / k1]),
            ("the same, squared (= 1/k1^2)", [1 / (k1 * k1)]),
        ]
        self.note(f"HAF readings at tse-kin haf's {len(z)} heights (paper: {PAPER['haf']} for the prototype):")
        self.haf_table = []
        for name, vals in readings:
            vals = [x for x in vals if x == x]
            m, a, b = mean(vals), min(vals), max(vals)
            self.haf_table.append((name, m, a, b))
            span = f" ({a:.4g} .. {b:.4g})" if b - a > 1e-9 * abs(m) else ""
            self.note(f"  {m:8.4f}{span}  {name}")
        near = min(self.haf_table, key=lambda t: abs(t[1] - PAPER["haf"]))
        self.note(f"  nearest to {PAPER['haf']}: {near[1]:.4f} ({100 * (near[1] / PAPER['haf'] - 1):+.1f} %), "
                  f"{near[0]}; the squared reading would need k1 = {lo:.4f} to give {PAPER['haf']}")

    def workspace_readings(self):
        """The workspace with one limit changed, to see which one bounds it: the grid, the
        singularity margins, the angle stops, the stroke (for the prototype, the assumptions the
        paper leaves open behind its 0.28: the stroke is not given, its workspace test names
        neither the margins nor the stops)."""
        v = self.values
        free = self.free_stroke
        strokes = sorted({float(f"{v['s_max'] * k:.4g}") for k in STROKE_SCALES} | {free})
        readings = [
            (f"this design (stroke {v['s_min']:g} .. {v['s_max']:g} m, stops {v['alpha_min_deg']:.4g} .. "
             f"{v['alpha_max_deg']:.4g} deg, mu >= {v['mu_min']:g}, nu >= {v['nu_min']:g})", {}, self.a.grid),
            ("on tse-kin workspace's default grid 21 x 36 x 41", {}, "21,36,41"),
            ("no singularity margins (mu_min = nu_min = 0)", {"mu_min": 0.0, "nu_min": 0.0}, self.a.grid),
            ("no angle stops (alpha 0.01 .. 89.99 deg)", {"alpha_min_deg": 0.01, "alpha_max_deg": 89.99},
             self.a.grid),
        ] + [(f"stroke {v['s_min']:g} .. {sm:.4g} m" + (" (not binding)" if sm == free else ""), {"s_max": sm},
              self.a.grid) for sm in strokes if sm > v["s_min"]]
        g = self.a.grid.replace(",", " x ")
        self.note(f"workspace with one limit changed (fraction of the {g} grid's points, unless another grid is "
                  f"named; volume on the same points)" + (f"; paper {PAPER['workspace']}" if self.is_proto else "")
                  + ":")
        self.ws_table = []
        for n, (name, over, grid) in enumerate(readings):
            text = self.base_text
            for k, val in over.items():
                text = variant(text, k, val)
            path = os.path.join(self.csv, "params", f"ws_reading_{n}.params")
            self.write(path, text)
            reach, total, frac, vol = self.workspace_figures(path, grid)
            self.ws_table.append((name, frac, vol))
            self.note(f"  {frac:8.4f}  {vol:8.4g} m^3  {name}")

    def stop_heights(self):
        """Where the plate's centre is on the axis when a scissor is at a stop.  The paper's 0.324 and
        1.619 m are the scissor's height L sin(alpha) at the stops; the ball joint is at that
        distance from the midpoint of A and B but not above it (h^2 = b^2 + z^2, b the horizontal
        offset), so the plate is a little lower.  Found from tse-kin ik's verdicts on a fine row of
        heights, then on a finer one across each edge (two runs, a resolution of ~1e-7 m)."""
        L = self.values["L"]
        n = 2000

        def verdicts(lo, hi):
            zs = [lo + (hi - lo) * i / (n - 1) for i in range(n)]
            out = self.kin.run(["ik", "--design", self.design_file], "".join(f"0,0,{z!r},0,0,0\n" for z in zs))
            return zs, [line.split(",")[0] == "ok" for line in out.splitlines()]

        zs, ok = verdicts(0.0, L)
        edges = [i for i in range(1, n) if ok[i] != ok[i - 1]]
        if len(edges) != 2:
            self.note(f"on the axis the reachable heights are not one interval ({len(edges)} edges)")
            return
        found = []
        for i in edges:
            fz, fok = verdicts(zs[i - 1], zs[i])
            j = next(k for k in range(1, n) if fok[k] != fok[k - 1])
            found.append((fz[j - 1] + fz[j]) / 2)
        z = [r["z"] for r in self.profile]
        self.note(f"on the axis the plate reaches Z = {found[0]:.4f} .. {found[1]:.4f} m (tse-kin ik); the stops' "
                  f"scissor heights L sin(alpha) are {z[0]:.4f} and {z[-1]:.4f} m")

    # ------------------------------------------------------------------ the numbers of the report
    def resolution(self, grid):
        """The cells of tse-kin workspace's volume on a grid: r, Z and the arc at the rim [m]."""
        nr, nphi, nz = (int(x) for x in grid.split(","))
        L = self.values["L"]
        return f"cells {L / (2 * (nr - 1)):.3g} m in r, {L / (nz - 1):.3g} m in Z, {math.pi * L / nphi:.3g} m of arc at the rim"

    def numbers(self):
        v = self.values
        self.note(f"design: L = {v['L']:g} m, k1 = {v['k1']:g}, k2 = eta = {v['eta_deg']:g} deg, "
                  f"k3 = {v['k3']:g}, k4 = {v['k4']:g}; stroke {v['s_min']:g} .. {v['s_max']:g} m, scissor stops "
                  f"{v['alpha_min_deg']:.4g} .. {v['alpha_max_deg']:.4g} deg, margins mu >= {v['mu_min']:g}, "
                  f"nu >= {v['nu_min']:g}" + (" (the paper's prototype)" if self.is_proto else ""))
        self.note(f"HAF (mean over tse-kin haf's heights) {self.haf_mean:.4f}"
                  + (f"; paper {PAPER['haf']}" if self.is_proto else ""))
        g = self.a.grid.replace(",", " x ")
        self.note(f"workspace, plate level: {self.ws_reach} of the {self.ws_total} points of the {g} grid reachable, "
                  f"fraction {self.ws:.4f}" + (f"; paper {PAPER['workspace']}" if self.is_proto else ""))
        cyl = math.pi * v["L"] ** 3 / 4
        self.note(f"workspace volume, plate level: {self.volume:.4g} m^3 ({100 * self.volume / cyl:.1f} % of the "
                  f"cylinder r <= L/2, 0 <= Z <= L, {cyl:.4g} m^3): the reachable volume of the plate's centre, the "
                  f"sum of the cells of the reachable points of a {self.a.volume.replace(',', ' x ')} grid "
                  f"({self.resolution(self.a.volume)}); {self.ws_volume_grid:.4g} m^3 on the {g} grid "
                  f"({self.resolution(self.a.grid)})")
        r75, t75, f75, _ = self.ws_tilted
        self.note(f"workspace, plate pitched {PAPER_PITCH_DEG:g} deg"
                  + (" (the paper's Fig. 8-d)" if self.is_proto else "")
                  + f": {r75} of the {t75} points of the {g} grid reachable, fraction {f75:.4f}; volume "
                  f"{self.volume_tilted:.4g} m^3 ({self.a.volume.replace(',', ' x ')} grid)")
        z = [r["z"] for r in self.profile]
        self.note(f"heights of the alpha stops: {z[0]:.4f} m .. {z[-1]:.4f} m")
        for name, (pitch, rows) in self.points.items():
            ok = [r for r in rows if r["status"] == "ok"]
            if ok:
                xs, ys = [r["x"] for r in ok], [r["y"] for r in ok]
                self.note(f"reachable points, plate pitched {pitch:g} deg ({self.a.draw.replace(',', ' x ')} grid): "
                          f"{len(ok)} of {len(rows)}; X {min(xs):.3f} .. {max(xs):.3f} m ({max(xs) - min(xs):.2f} m), "
                          f"Y {min(ys):.3f} .. {max(ys):.3f} m ({max(ys) - min(ys):.2f} m)")
        k2 = [r for r in self.sweep["k2"] if r["haf"] == r["haf"]]
        best = max(k2, key=lambda r: r["haf"])
        self.note(f"k2: HAF largest at k2 = {best['value']:.3g} deg ({best['haf']:.4f}); "
                  + ", ".join(f"k2 = {r['value']:.3g}: HAF {fmt(r['haf'])} workspace {fmt(r['workspace'])}"
                              for r in (k2[0], k2[len(k2) // 4], k2[len(k2) // 2], k2[3 * len(k2) // 4], k2[-1])))
        for key in ("k1", "k1_free", "k3", "k4"):
            rows = [r for r in self.sweep[key] if r["haf"] == r["haf"]]
            wmax = max(rows, key=lambda r: r["workspace"])
            name = f"k1 with the stroke not binding (s_max = {self.free_stroke:.3g} m)" if key == "k1_free" else key
            self.note(f"{name}: HAF {fmt(rows[0]['haf'])} .. {fmt(rows[-1]['haf'])}, workspace "
                      f"{fmt(rows[0]['workspace'])} .. {fmt(rows[-1]['workspace'])} (largest {fmt(wmax['workspace'])} "
                      f"at {fmt(wmax['value'])}) over {key.split('_')[0]} = {fmt(rows[0]['value'])} .. "
                      f"{fmt(rows[-1]['value'])}")
        for key in ("k3", "k4", "eta_deg"):
            for val, rows in self.variants[key]:
                ok = [r for r in rows if r["sigma_z"] == r["sigma_z"]]
                mid = ok[len(ok) // 2] if ok else None
                if mid is None:
                    self.note(f"profile {key} = {val:g}: no branch solution on the axis")
                    continue
                sv = ", ".join(f"{mid[f'sv{k}']:.4g}" for k in range(1, 7))
                self.note(f"profile {key} = {val:g}: at z = {mid['z']:.3f} sigma_z {mid['sigma_z']:.4g}, sv {sv}; "
                          f"smallest mu on the axis {min(r['mu_min'] for r in ok):.3g}, smallest nu "
                          f"{min(r['nu'] for r in ok):.3g}")
        for eta, (xs, zs, rows) in self.maps.items():
            sing = [(abs(x), z, min(r["mu1"], r["mu2"], r["mu3"])) for (x, z), r in
                    zip([(x, z) for z in zs for x in xs], rows)
                    if min(r["mu1"], r["mu2"], r["mu3"]) < 0.05]
            ok = sum(1 for r in rows if r["status"] == "ok")
            if sing:
                near = min(s[0] for s in sing)
                self.note(f"k2 = {eta:g} deg, plane y = 0: {len(sing)} of {len(rows)} points with mu < 0.05, the "
                          f"nearest {near:.3f} m from the axis; {ok} points reachable")
            else:
                self.note(f"k2 = {eta:g} deg, plane y = 0: no point with mu < 0.05; {ok} points reachable")


# ---------------------------------------------------------------------- drawing
def draw(st):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from matplotlib.text import Text

    out = st.out
    v = st.values
    paper = st.is_proto

    def title(text, ref=None):
        """A figure's title: what it shows, the paper's figure it answers (the prototype only), and
        the design on a second line."""
        return text + (f" (paper {ref})" if paper and ref else "") + "\n" + st.label()

    def save(fig, name, top=1.0):
        fig.tight_layout(rect=(0, 0, 1, top))  # top < 1 leaves room for a suptitle
        # Every title, axis label and legend entry also as the PNG's Description (before drawing,
        # tick labels are still empty): what the figure says, readable without looking at it.
        said = [t.get_text() for t in fig.findobj(Text) if t.get_text()]
        fig.savefig(os.path.join(out, name), dpi=100, bbox_inches="tight",
                    metadata={"Title": name, "Description": "\n".join(said)})
        plt.close(fig)

    def col(rows, key):
        return [r[key] for r in rows]

    grid = st.a.grid.replace(",", " x ")

    def volume_axis(ax, rows, extra=None, short=False):
        """The reachable volume on a right-hand axis: the size, which the fraction is not."""
        ax2 = ax.twinx()
        ax2.plot(col(rows, "value"), col(rows, "volume_m3"), "-.", color="C1", lw=1,
                 label="reachable volume (right)")
        if extra:
            ax2.plot(col(extra, "value"), col(extra, "volume_m3"), ":", color="C1", lw=1,
                     label="reachable volume, stroke not binding (right)")
        ax2.set_ylabel("volume [m^3]" if short else f"reachable volume [m^3] ({grid} grid)", color="C1")
        ax2.set_ylim(bottom=0)
        return ax2

    def sweep_plot(name, key, label, fig_title, ref, extra=None):
        rows = st.sweep[name]
        fig, ax = plt.subplots(figsize=(6.5, 4.3))
        ax.plot(col(rows, "value"), col(rows, key), "-", color="C0", label="tse-kin sweep")
        if extra:
            ax.plot(col(extra[0], "value"), col(extra[0], key), "--", color="C2", label=extra[1])
        x = v[SWEEP_KEY[name]]
        y = st.haf_mean if key == "haf" else st.ws
        ax.axvline(x, color="C3", lw=0.8, ls=":")
        ax.plot([x], [y], "o", color="C3", label=f"design under study ({fmt(y)})")
        if paper:
            ax.plot([x], [PAPER[key]], "kx", ms=9, mew=2, label=f"paper, prototype ({PAPER[key]})")
        handles, labels = ax.get_legend_handles_labels()
        if key == "workspace":
            ax2 = volume_axis(ax, rows, extra[0] if extra else None)
            h2, l2 = ax2.get_legend_handles_labels()
            handles, labels = handles + h2, labels + l2
        ax.set_xlabel(label)
        ax.set_ylabel("HAF" if key == "haf" else f"workspace fraction ({grid} grid's points)")
        ax.set_title(title(fig_title, ref), fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(handles, labels, fontsize=8)
        save(fig, f"{key}_{name}.png")

    sweep_plot("k1", "haf", "k1 = l0 / L", "HAF against k1", "Fig. 10")
    sweep_plot("k1", "workspace", "k1 = l0 / L", "Workspace against k1", "Fig. 11",
               extra=(st.sweep["k1_free"], f"stroke not binding (s_max = {st.free_stroke:.3g} m)"))
    sweep_plot("k2", "haf", "k2 = eta [deg]", "HAF against k2", "Fig. 12")
    sweep_plot("k2", "workspace", "k2 = eta [deg]", "Workspace against k2", "Fig. 13")

    fig, axes = plt.subplots(2, 2, figsize=(9, 6))
    for c, (name, label) in enumerate((("k3", "k3 = r_act / L"), ("k4", "k4 = r_top / L"))):
        for r, key in enumerate(("haf", "workspace")):
            ax = axes[r][c]
            rows = st.sweep[name]
            ax.plot(col(rows, "value"), col(rows, key), "-")
            ax.axvline(v[name], color="C3", lw=0.8, ls=":")
            ax.plot([v[name]], [st.haf_mean if key == "haf" else st.ws], "o", color="C3")
            if key == "workspace":
                volume_axis(ax, rows, short=True)
            ax.set_xlabel(label)
            ax.set_ylabel("HAF" if key == "haf" else "workspace fraction")
            ax.grid(alpha=0.3)
    fig.suptitle(title("HAF and workspace (solid; reachable volume dash-dotted, right) against k3 and k4"
                       + (" (the paper states these trends in words)" if paper else "")), fontsize=10)
    save(fig, "sweeps_k3_k4.png", top=0.93)

    # Singular values along the axis (the paper's singular-value figures).
    rows = [r for r in st.profile if r["sigma_z"] == r["sigma_z"]]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    z = col(rows, "z")
    for k in range(1, 7):
        ax.plot(z, col(rows, f"sv{k}"), lw=1, label=f"sv{k}")
    ax.plot(z, col(rows, "sigma_z"), "k--", lw=2, label="sigma_z")
    ax.set_yscale("log")
    ax.set_xlabel("Z [m] (plate on the axis, level)")
    ax.set_ylabel("singular values of dp/dq")
    ax.set_title(title("Singular values and sigma_z against height", "Fig. 9"), fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, ncol=2)
    save(fig, "singular_values.png")

    def variant_plot(key, label, fname, text, all_sv=False, ref=None):
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        for n, (val, rows) in enumerate(st.variants[key]):
            rows = [r for r in rows if r["sigma_z"] == r["sigma_z"]]
            if not rows:
                continue
            mine = abs(val - v[key]) < 1e-12
            colr = f"C{n}"
            tag = f"{label} = {val:g}" + (" (design)" if mine else "")
            ax.plot(col(rows, "z"), col(rows, "sigma_z"), "-", color=colr, lw=2.2 if mine else 1.4, label=tag)
            if all_sv:
                for k in range(1, 7):
                    ax.plot(col(rows, "z"), col(rows, f"sv{k}"), ":", color=colr, lw=0.9)
        ax.set_yscale("log")
        ax.set_xlabel("Z [m]")
        ax.set_ylabel("sigma_z (solid)" + ("; all six singular values (dotted)" if all_sv else ""))
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
        ax.set_title(title(text, ref), fontsize=9)
        save(fig, fname)

    variant_plot("k1", "k1", "sigma_z_k1.png", "sigma_z against height for several k1", ref="Fig. 9")
    variant_plot("eta_deg", "k2", "profile_k2.png", "sigma_z against height for several k2 [deg]")
    variant_plot("k3", "k3", "profile_k3.png", "Singular values against height for several k3", all_sv=True)
    variant_plot("k4", "k4", "profile_k4.png", "Singular values against height for several k4", all_sv=True)

    fig, ax = plt.subplots(figsize=(7, 4.2))
    etas = [e for e, _ in st.status_k2]
    bottom = [0.0] * len(etas)
    for n, name in enumerate(STATUSES):
        share = [sh[n] for _, sh in st.status_k2]
        if not any(share):
            continue
        ax.bar(etas, share, width=(etas[1] - etas[0]) * 0.8 if len(etas) > 1 else 8, bottom=bottom, label=name)
        bottom = [b + x for b, x in zip(bottom, share)]
    ax.set_xlabel("k2 = eta [deg]")
    ax.set_ylabel(f"share of the {grid} grid")
    ax.set_title(title("Why the workspace changes with k2: every grid point by the first check it fails"),
                 fontsize=9)
    ax.legend(fontsize=8, loc="upper center", ncol=4)
    ax.set_ylim(0, 1.25)
    save(fig, "status_k2.png")

    # The workspace as the paper renders it (its Fig. 8): angled, top and side views.
    for name, (pitch, rows) in st.points.items():
        ok = [r for r in rows if r["status"] == "ok"]
        fig = plt.figure(figsize=(13, 4.3))
        ax = fig.add_subplot(1, 3, 1, projection="3d")
        if ok:
            ax.scatter(col(ok, "x"), col(ok, "y"), col(ok, "z"), c=col(ok, "z"), s=3, cmap="viridis")
        ax.set_xlabel("X [m]")
        ax.set_ylabel("Y [m]")
        ax.set_zlabel("Z [m]")
        ax.set_title("angled view", fontsize=10)
        for i, (a, b, lbl) in enumerate((("x", "y", "top view (X, Y)"), ("x", "z", "side view (X, Z)"))):
            ax = fig.add_subplot(1, 3, 2 + i)
            if ok:
                ax.scatter(col(ok, a), col(ok, b), c=col(ok, "z"), s=3, cmap="viridis")
            ax.set_xlabel(f"{a.upper()} [m]")
            ax.set_ylabel(f"{b.upper()} [m]")
            ax.set_aspect("equal")
            ax.grid(alpha=0.3)
            ax.set_title(lbl, fontsize=10)
        frac = len(ok) / len(rows) if rows else float("nan")
        vol = st.points_volume[name]
        fig.suptitle(title(f"Reachable grid points, plate pitched {pitch:g} deg: {len(ok)} of {len(rows)} "
                           f"({frac:.3f}); reachable volume {vol:.4g} m^3", "Fig. 8"), fontsize=10)
        save(fig, f"workspace_{name}.png", top=0.88)

    # Where the type-1 singularities lie (the paper's Fig. 7).
    fig, axes = plt.subplots(1, len(st.maps), figsize=(12, 5.8))
    for ax, (eta, (xs, zs, rows)) in zip(axes, st.maps.items()):
        m = len(xs)
        mu = [[min(rows[k * m + i]["mu1"], rows[k * m + i]["mu2"], rows[k * m + i]["mu3"]) for i in range(m)]
              for k in range(len(zs))]
        mu = [[x if x == x else float("nan") for x in line] for line in mu]
        ok = [[1.0 if rows[k * m + i]["status"] == "ok" else 0.0 for i in range(m)] for k in range(len(zs))]
        im = ax.pcolormesh(xs, zs, mu, cmap="magma", vmin=0, vmax=1, shading="nearest")
        if any(x < 0.05 for line in mu for x in line if x == x):
            ax.contour(xs, zs, mu, levels=[0.05], colors="cyan", linewidths=1.2)
        if any(any(line) for line in ok):
            ax.contour(xs, zs, ok, levels=[0.5], colors="white", linewidths=1.0, linestyles="dashed")
        ax.axvline(0, color="w", lw=0.6, ls=":")
        ax.set_xlabel("X [m] (Y = 0, level plate)")
        ax.set_ylabel("Z [m]")
        ax.set_aspect("equal")
        ax.set_title(f"the design at k2 = {eta:g} deg: smallest type-1 margin mu\n"
                     f"(cyan: mu = 0.05, white dashed: reachable)",
                     fontsize=10)
        fig.colorbar(im, ax=ax, shrink=0.8)
    fig.suptitle(title("Where the type-1 singularities lie (white: no branch solution)"
                       + ("; the paper (its Fig. 7) has them near the axis for negative k2, away from it for positive"
                          if paper else "")), fontsize=10)
    save(fig, "singularities_k2.png", top=0.88)


SWEEP_KEY = {"k1": "k1", "k2": "eta_deg", "k3": "k3", "k4": "k4"}


def main():
    p = argparse.ArgumentParser(prog="study.sh", description=__doc__)
    p.add_argument("--tse-kin", required=True)
    p.add_argument("--params", help="the design (a tse-kin parameter file); default the prototype")
    p.add_argument("--out", help="output folder (default build/study/NAME)")
    p.add_argument("--grid", help="workspace grid of the sweeps (default the paper's 16,24,32)")
    p.add_argument("--designs", type=int, help="designs per sweep (default 50)")
    p.add_argument("--jobs", type=int, help="tse-kin sweep --jobs (default every core)")
    p.add_argument("--quick", action="store_true", help="tiny grids and few designs (tests)")
    a = p.parse_args()
    base = QUICK if a.quick else FULL
    a.grid = a.grid or base["grid"]
    a.designs = a.designs or base["designs"]
    a.draw, a.map, a.heights, a.status_etas = base["draw"], base["map"], base["heights"], base["status_etas"]
    a.volume = base["volume"]
    if a.designs < 2:
        fail("--designs takes 2 or more", 2)
    if a.jobs is not None and a.jobs < 1:
        fail("--jobs takes 1 or more", 2)
    name = os.path.splitext(os.path.basename(a.params))[0] if a.params else "prototype"
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    a.out = a.out or os.path.join(root, "build", "study", name)
    if a.params and not os.path.isfile(a.params):
        fail(f"no parameter file '{a.params}'", 2)

    load_kin(root, a.tse_kin)
    st = Study(a)
    t0 = time.monotonic()
    st.design()
    st.sweeps()
    st.profiles()
    st.workspace()
    st.margins()
    st.numbers()
    if st.is_proto:
        st.haf_readings()  # what the paper's 11.487 could have been: the prototype's figure only
    st.workspace_readings()
    st.stop_heights()
    st.write(os.path.join(a.out, "summary.txt"), "\n".join(st.summary) + "\n")
    t1 = time.monotonic()
    draw(st)
    t2 = time.monotonic()
    print(f"study: {name}: every run {t1 - t0:.1f} s, drawing {t2 - t1:.1f} s; CSVs in {st.csv}, PNGs in {a.out}")


if __name__ == "__main__":
    main()
