#!/usr/bin/python3
"""scripts/study.sh end to end on tiny grids: the PNGs and CSVs it promises, well formed.

Usage: study_check.py PATH/TO/tse-kin

Runs the study twice into temporary folders, for the prototype and for a design given by a
parameter file (a shorter stroke and shorter scissors, other k1, k2, k3, and a controller
parameter, as a real file would have), with --quick (grids of a few points, five designs a sweep),
and checks: exit 0 and the printed time of the four sweeps; every PNG (signature, size, a
plausible picture size); every CSV (its header, as many rows as asked, numbers where numbers
belong); the design's own values in the sweeps and the summary.  What is said comes from the
design (issue 21): for the file's design no line of the output, the summary, the CSVs or the
figures' titles, labels and legends (each PNG carries them as its Description) names the paper
or a value of the prototype, and they carry the design's values; every summary line is labelled
(no bare CSV); the quoted volume is tse-kin workspace's.  For the prototype the paper's figures
are there.  Then the refusals: a parameter file tse-kin refuses (exit 1, its message shown) and a
missing one (exit 2).  Checks what the script makes, not how it looks: the figures' content is
tse-kin's, tested by cli_contract.py and study_oracle.py (which also checks the volume against a
Monte Carlo estimate).
"""
import csv
import os
import re
import struct
import subprocess
import sys
import tempfile
import zlib

TOOL = os.path.abspath(sys.argv[1])
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SCRIPT = os.path.join(ROOT, "scripts", "study.sh")
PNGS = ["haf_k1.png", "workspace_k1.png", "haf_k2.png", "workspace_k2.png", "sweeps_k3_k4.png",
        "singular_values.png", "sigma_z_k1.png", "profile_k2.png", "profile_k3.png", "profile_k4.png",
        "status_k2.png", "workspace_level.png", "workspace_pitch20.png", "singularities_k2.png"]
# --quick's sizes (scripts/study.py, QUICK): 5 designs, grids 4,6,5 (sweeps) and 4,8,5 (points),
# a 15 x 15 margin map, 8 heights, 3 slide angles sorted by status, the volume on 6,12,9.
DESIGNS, POINTS, MAP, HEIGHTS, STATUS_ROWS, VOLUME_GRID = 5, 4 * 8 * 5, 15 * 15, 8, 3, "6,12,9"
# What only the prototype may be labelled with: the paper, its figures, the prototype's values.
PROTO_MARKS = [r"paper", r"[Pp]rototype", r"11\.487", r"(?<![\d.])0\.28(?!\d)", r"would need", r"nearest to",
               r"1\.727", r"0\.2647", r"(?<![\d.])0\.9 m", r"Fig\."]
NUMBER = re.compile(r"^(nan|-?inf|-?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)$")
passes, failures = 0, []


def check(name, cond, detail=""):
    global passes
    if cond:
        passes += 1
    else:
        failures.append(name)
        print(f"FAIL: {name}" + (f": {detail}" if detail else ""))


def study(out, *extra):
    r = subprocess.run(["bash", SCRIPT, "--tse-kin", TOOL, "--quick", "--out", out] + list(extra),
                       capture_output=True, text=True, timeout=300)
    return r.returncode, r.stdout, r.stderr


def table(path):
    with open(path) as fh:
        lines = [l for l in fh.read().splitlines() if l and not l.startswith("#")]
    return lines[0].split(",") if lines else [], list(csv.DictReader(lines))


def png_size(path):
    with open(path, "rb") as fh:
        head = fh.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def png_texts(path):
    """The PNG's text chunks (tEXt, zTXt, iTXt) as {keyword: text}."""
    with open(path, "rb") as fh:
        data = fh.read()
    out, at = {}, 8
    while at + 8 <= len(data):
        n, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        at += 12 + n
        if kind == b"tEXt":
            k, v = body.split(b"\0", 1)
            out[k.decode("latin-1")] = v.decode("latin-1")
        elif kind == b"zTXt":
            k, v = body.split(b"\0", 1)
            out[k.decode("latin-1")] = zlib.decompress(v[1:]).decode("latin-1")
        elif kind == b"iTXt":
            k, rest = body.split(b"\0", 1)
            compressed, rest = rest[0], rest[2:]
            _lang, _tk, v = rest.split(b"\0", 2)
            out[k.decode("latin-1")] = (zlib.decompress(v) if compressed else v).decode("utf-8")
    return out


def proto_marks(text):
    return [m for m in PROTO_MARKS if re.search(m, text)]


def numbers(row, keys):
    return all(NUMBER.match(row[k] or "") for k in keys)


def check_outputs(tag, out, k1):
    for name in PNGS:
        path = os.path.join(out, name)
        size = png_size(path) if os.path.isfile(path) else None
        check(f"{tag}: {name} is a PNG of a plausible size",
              size is not None and size[0] >= 400 and size[1] >= 300 and os.path.getsize(path) > 5000,
              f"{size} {os.path.getsize(path) if os.path.isfile(path) else 'missing'}")
    c = os.path.join(out, "csv")
    for sweep in ("k1", "k2", "k3", "k4", "k1_free_stroke"):
        head, rows = table(os.path.join(c, f"sweep_{sweep}.csv"))
        check(f"{tag}: sweep_{sweep}.csv has the header and {DESIGNS} rows of numbers",
              head == ["param", "value", "haf", "workspace", "volume_m3"] and len(rows) == DESIGNS and
              all(numbers(r, ("value", "haf", "workspace", "volume_m3")) for r in rows), f"{head} {len(rows)}")
    head, rows = table(os.path.join(c, "sweep_k1.csv"))
    values = [float(r["value"]) for r in rows]
    check(f"{tag}: the k1 sweep spans the design's k1 = {k1}", min(values) <= k1 <= max(values), repr(values))
    for name in ["profile.csv"] + [f for f in os.listdir(c) if f.startswith("profile_")]:
        head, rows = table(os.path.join(c, name))
        check(f"{tag}: {name} has the profile header and {HEIGHTS} rows",
              head == ["z", "sv1", "sv2", "sv3", "sv4", "sv5", "sv6", "sigma_z", "mu_min", "nu"] and
              len(rows) == HEIGHTS and all(numbers(r, head) for r in rows), f"{head} {len(rows)}")
    for name in ("points_level.csv", "points_pitch20.csv"):
        head, rows = table(os.path.join(c, name))
        check(f"{tag}: {name} has x,y,z,status,scissor for {POINTS} points",
              head == ["x", "y", "z", "status", "scissor"] and len(rows) == POINTS and
              all(numbers(r, ("x", "y", "z")) and r["status"].isalpha() for r in rows), f"{head} {len(rows)}")
    for eta in ("-30", "60"):
        head, rows = table(os.path.join(c, f"margins_eta_{eta}.csv"))
        check(f"{tag}: margins_eta_{eta}.csv has the map's {MAP} poses with their margins",
              head == ["x", "z", "status", "scissor", "mu1", "mu2", "mu3", "nu"] and len(rows) == MAP and
              all(numbers(r, ("x", "z", "mu1", "mu2", "mu3", "nu")) for r in rows), f"{head} {len(rows)}")
    head, rows = table(os.path.join(c, "status_k2.csv"))
    check(f"{tag}: status_k2.csv counts every grid point once per slide angle",
          head[:2] == ["eta_deg", "ok"] and len(rows) == STATUS_ROWS and
          all(sum(int(r[k]) for k in head[1:]) == 4 * 6 * 5 for r in rows), f"{head} {rows}")
    for name in os.listdir(c):
        if name.endswith(".csv"):
            head, rows = table(os.path.join(c, name))
            check(f"{tag}: {name} starts with a header of names", head and not any(NUMBER.match(h) for h in head),
                  repr(head))
    with open(os.path.join(out, "summary.txt")) as fh:
        summary = fh.read()
    check(f"{tag}: summary.txt names the design", f"k1 = {k1:g}" in summary, summary)
    check(f"{tag}: every summary line is labelled: no bare CSV (digit,digit)",
          not re.search(r"\d,\d", summary), [l for l in summary.splitlines() if re.search(r"\d,\d", l)])
    return summary


def texts_of(out):
    """Every text the study leaves behind: its CSV folder's files and each PNG's labels."""
    found = {}
    for root, _dirs, files in os.walk(os.path.join(out, "csv")):
        for name in files:
            with open(os.path.join(root, name), encoding="utf-8") as fh:
                found[os.path.relpath(os.path.join(root, name), out)] = fh.read()
    for name in PNGS:
        found[name] = png_texts(os.path.join(out, name)).get("Description", "")
    return found


def kin_volume(params, grid):
    args = [TOOL, "workspace", "--grid", grid] + (["--design", params] if params else [])
    r = subprocess.run(args, capture_output=True, text=True)
    last = r.stdout.strip().splitlines()[-1].split(",") if r.returncode == 0 and r.stdout.strip() else []
    return float(last[3]) if len(last) == 4 else float("nan")


with tempfile.TemporaryDirectory(prefix="tse_study_") as tmp:
    out = os.path.join(tmp, "prototype")
    rc, so, se = study(out)
    check("study of the prototype exits 0", rc == 0, f"rc {rc}\n{se}")
    check("study prints the time of the paper's four sweeps",
          re.search(r"study: 4 sweeps \(k1, k2, k3, k4\) x 5 designs on the 4 x 6 x 5 grid \(\d+ threads\): "
                    r"\d+\.\d+ s", so) is not None, so)
    if rc == 0:
        summary = check_outputs("prototype", out, 0.2647)
        check("prototype: the paper's figures beside ours, and the readings of its HAF",
              "(the paper's prototype)" in summary and "; paper 11.487" in summary and "; paper 0.28" in summary
              and "HAF readings" in summary and "nearest to 11.487" in summary, summary)
        said = png_texts(os.path.join(out, "haf_k1.png")).get("Description", "")
        check("prototype: its HAF figure marks the paper's 11.487 and names the paper's figure and the design",
              "paper, prototype (11.487)" in said and "Fig. 10" in said and
              "prototype: L = 1.727 m, k1 = 0.2647" in said and "stroke 0 .. 0.9 m" in said, said)
        vol = kin_volume(None, VOLUME_GRID)
        check("prototype: the volume quoted is tse-kin workspace's on the volume grid",
              f"workspace volume, plate level: {vol:.4g} m^3" in summary, f"{vol:.4g} {summary}")

    # Issue 21: a 0.6 m stroke and 1.4 m scissors, other k1, k2 and k3, and a controller key.
    params = os.path.join(tmp, "narrow.params")
    with open(params, "w") as fh:
        fh.write("# a smaller, narrower design\nL = 1.4\ns_max = 0.6\nk1 = 0.35   # l0 / L\neta_deg = 20\n"
                 "k3 = 0.03\nslide_vmax = 0.1\n")
    out = os.path.join(tmp, "narrow")
    rc, so, se = study(out, "--params", params, "--jobs", "1")
    check("study of a design given by a parameter file exits 0", rc == 0, f"rc {rc}\n{se}")
    if rc == 0:
        summary = check_outputs("narrow", out, 0.35)
        check("narrow: the design is read from the file (L, stroke, k1, k2, k3), the controller's key ignored",
              "design: L = 1.4 m, k1 = 0.35, k2 = eta = 20 deg, k3 = 0.03, k4 = 0.11765; stroke 0 .. 0.6 m" in so, so)
        check("narrow: neither the printed lines nor the summary name the paper or a prototype value",
              not proto_marks(so) and not proto_marks(summary),
              [l for l in (so + summary).splitlines() if proto_marks(l)])
        check("narrow: the workspace readings are labelled with the design's stroke",
              "this design (stroke 0 .. 0.6 m" in summary and "stroke 0 .. 0.6667 m" in summary, summary)
        check("narrow: the HAF readings of the paper's figure are the prototype's only", "HAF readings" not in summary)
        for name, text in texts_of(out).items():
            check(f"narrow: {name} names neither the paper nor a prototype value", not proto_marks(text),
                  [l for l in text.splitlines() if proto_marks(l)])
        for name in PNGS:
            said = png_texts(os.path.join(out, name)).get("Description", "")
            check(f"narrow: {name} is labelled with the design",
                  "narrow.params: L = 1.4 m, k1 = 0.35, k2 = 20 deg" in said and "stroke 0 .. 0.6 m" in said, said)
        vol = kin_volume(params, VOLUME_GRID)
        check("narrow: the volume quoted is tse-kin workspace's for the design on the volume grid, in m^3",
              f"workspace volume, plate level: {vol:.4g} m^3" in summary, f"{vol:.4g} {summary}")

    bad = os.path.join(tmp, "bad.params")
    with open(bad, "w") as fh:
        fh.write("k1 = 2\n")
    rc, so, se = study(os.path.join(tmp, "bad"), "--params", bad)
    check("study of a design tse-kin refuses exits 1 with its message naming the line",
          rc == 1 and f"{bad}:1: k1 = 2 is invalid" in se, f"rc {rc} {se}")
    rc, so, se = study(os.path.join(tmp, "none"), "--params", os.path.join(tmp, "none.params"))
    check("study of a missing parameter file exits 2 naming it", rc == 2 and "none.params" in se, f"rc {rc} {se}")
    rc, so, se = study(os.path.join(tmp, "x"), "--frobnicate")
    check("study with an unknown option exits 2", rc == 2 and "frobnicate" in se, f"rc {rc} {se}")

print(f"{passes} passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
