"""One parameter file, one answer: tse-kin --params, tse-sim --params, tsectl params dump FILE and
tse.kin.Params.from_file accept and refuse exactly the same files, with the same words.

Each row of FILES says, worked out by hand from the format (README.md, "One reader of parameter files"),
whether a controller takes the file and what its refusal must name; every tool is run on it and
must agree with the row and so with each other.  For a file they take, the values they compute
with agree too: tse-kin's inverse kinematics equals tse.kin's on the file's design to the bit, and
tsectl's dump of the file, read back, gives the same micro-unit values.
"""
import math
import subprocess

import numpy as np
import pytest

from tse import kin

# (name, text, taken, what a refusal names: its line and words).  Text is bytes so that BOMs,
# CRLF and NUL bytes are what the row says.
FILES = [
    ("empty", b"", True, None),
    ("comments and blanks", b"\xef\xbb\xbf# a design\r\n\r\n   L = 1.5   # metres\r\n\t\n# end", True, None),
    ("upper-case keys", b"L = 1.5\nK1 = 0.2647\nSLIDE_VMAX = 0.12\nEta_Deg = 30\n", True, None),
    ("the issue's upper-case key", b"STEPS_PER_M = 1280000\n", True, None),
    ("degrees", b"eta_deg = 25\nalpha_min_deg = 11\nalpha_max_deg = 69\n", True, None),
    ("radians", b"eta = 0.5\nalpha_max = 1.2\n", True, None),
    ("the controller's keys", b"watchdog_ms = 500\nstatus_ms = 20\ncan_kbps = 250\nhome_sw_3 = 0.25\n", True, None),
    ("no space, a value after many blanks", b"k1=0.27" + b" " * 600 + b"\n", True, None),
    ("1e-400 is not 0", b"k3 = 1e-400\n", False, ":1: k3: '1e-400' is not one finite number"),
    ("1e400", b"L = 1.5\nk3 = 1e400\n", False, ":2: k3: '1e400' is not one finite number"),
    ("nan", b"slide_vmax = nan\n", False, ":1: slide_vmax: 'nan' is not one finite number (in m/s)"),
    ("a unit after the value", b"L = 1.5 m\n", False, ":1: L: '1.5 m' is not one finite number (in m)"),
    ("two values", b"L = 1.5 = 2\n", False, ":1: L: '1.5 = 2' is not one finite number"),
    ("unknown key", b"# c\nbogus = 1\n", False, ":2: unknown parameter 'bogus'"),
    ("no name", b"  = 3\n", False, ":1: no parameter name before '='"),
    ("no '='", b"L 1.5\n", False, ":1: expected 'name = value'"),
    ("both spellings of an angle", b"alpha_max_deg = 69\nALPHA_MAX = 1.2\n", False,
     ":2: ALPHA_MAX given twice (first on line 1 as alpha_max_deg)"),
    ("a key twice in two cases", b"L = 1.5\nl = 1.6\n", False, ":2: l given twice (first on line 1 as L)"),
    ("outside a range as written", b"k1 = 1.0000004\n", False, ":1: k1 = 1.0000004 is outside 0.000001..1"),
    ("90 degrees", b"eta_deg = 90\n", False, ":1: eta = 90 deg is outside -89.99998..89.99998 deg"),
    ("a rate the bus has not", b"can_kbps = 300\n", False, "can_kbps = 300 kbit/s is not one of the rates"),
    ("a stroke upside down", b"s_min = 0.5\ns_max = 0.4\n", False, ":2: s_min = 0.5 m must be below s_max = 0.4 m"),
    # A longer scissor: at the default switches (0.2 m each) scissor 1 is 2 x 0.2 x cos(30 deg) =
    # 0.3464 m wide, narrower than its alpha_max stop allows, 2 k1 L cos(alpha_max) =
    # 2 x 0.2647 x 2 x sqrt(1 - (1.619 / 1.727)^2) = 0.3686 m.
    ("homing switches out of reach", b"L = 2\n", False, "home_sw_1 = 0.2 m: the six homing switches cannot be reached"),
    ("a NUL byte", b"L = 1.5\n\0k1 = 0.3\n", False, "contains a NUL byte"),
]


def run(args):
    r = subprocess.run(args, stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=60)
    return r.returncode, r.stderr


def verdicts(path, tse_kin_cli, tse_sim, tsectl):
    """Each tool's (taken, message)."""
    out = {}
    rc, err = run([tse_kin_cli, "ik", "--params", str(path)])
    assert rc in (0, 1), err
    out["tse-kin"] = (rc == 0, err)
    # tse-sim reads its file before it opens the bus: past the file, a bus that is not there.
    rc, err = run([tse_sim, "--iface", "nosuchcan0", "--node", "1", "--params", str(path)])
    assert rc in (1, 2), err
    assert rc == 2 or "cannot open CAN interface nosuchcan0" in err, err
    out["tse-sim"] = (rc == 1, err)
    rc, err = run([tsectl, "params", "dump", str(path)])
    assert rc in (0, 2), err
    out["tsectl"] = (rc == 0, err)
    try:
        kin.Params.from_file(path)
        out["tse.kin"] = (True, "")
    except ValueError as e:
        out["tse.kin"] = (False, str(e))
    return out


@pytest.mark.parametrize("name,text,taken,says", FILES, ids=[f[0] for f in FILES])
def test_every_tool_takes_the_same_files(tmp_path, tse_kin_cli, tse_sim, tsectl, name, text, taken, says):
    path = tmp_path / "f.params"
    path.write_bytes(text)
    for tool, (ok, msg) in verdicts(path, tse_kin_cli, tse_sim, tsectl).items():
        assert ok == taken, f"{tool}: {'took' if ok else 'refused'} it: {msg}"
        if not taken:
            assert f"{path}{says}" in msg or (not says.startswith(":") and says in msg and str(path) in msg), \
                f"{tool}: {msg!r} does not say {says!r}"


def test_taken_files_mean_the_same(tmp_path, tse_kin_cli, tsectl):
    poses = np.array([[0.0, 0.0, 1.0, 0.0, 0.0, 0.0], [0.05, -0.03, 1.1, 0.02, -0.01, 0.1]])
    rows = "".join(",".join("%.17g" % x for x in p) + "\n" for p in poses)
    for name, text, taken, _ in FILES:
        if not taken:
            continue
        path = tmp_path / "f.params"
        path.write_bytes(text)
        p = kin.Params.from_file(path)
        # tse-kin computes with what tse.kin computes with: the same slides to the last bit.
        r = subprocess.run([tse_kin_cli, "ik", "--params", str(path)], input=rows, capture_output=True, text=True,
                           check=True)
        got = np.array([[float(x) for x in line.split(",")[2:]] for line in r.stdout.splitlines()])
        assert np.array_equal(got, kin.ik(poses, params=p).q, equal_nan=True), name
        # tsectl's dump is the controller's set: each kinematic value within half a micro-unit of the
        # written one (a degree's conversion aside), and read back by all alike.
        dump = tmp_path / "dump.params"
        dump.write_text(subprocess.run([tsectl, "params", "dump", str(path)], check=True, capture_output=True,
                                       text=True).stdout)
        q = kin.Params.from_file(dump)
        for key, v in p.as_dict().items():
            assert abs(q.as_dict()[key] - v) <= 0.5e-6 + 1e-15, (name, key)
        assert math.isfinite(q.L)
