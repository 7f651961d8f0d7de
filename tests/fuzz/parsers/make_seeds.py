#!/usr/bin/env python3
"""Writes the parsers target's seeds: the files the tools write themselves (tse-kin's parameter
template, tse-sim's SI parameter file, the demos' pose and trajectory rows) and hand-made edge
cases (BOM, CRLF, comments, headers, empty and long fields, NUL bytes, lines at the readers'
bounds), each behind the byte that picks its parser (fuzz_parsers.c).  Run it again when a format
changes, then minimise into the corpus:
    make_seeds.py build/host/host_tools/tse-kin build/host/host_tools/tse-sim /tmp/seeds
    build/fuzz/tests/fuzz/parsers/fuzz_parsers -merge=1 tests/fuzz/parsers/corpus /tmp/seeds"""
import hashlib
import math
import os
import subprocess
import sys
import tempfile

CSV_ROW, KIN_STREAM, TRAJ, KIN_PARAMS, PARAM_FILE = range(5)
BOM = b"\xef\xbb\xbf"


def pick(parser, opt=0):
    return bytes([parser + 5 * opt])


def demo_poses():
    """scripts/demo_kinematics.sh's poses."""
    rows = []
    for i in range(8):
        t = i / 7
        a = 2 * math.pi * t
        rows.append("%.6f,%.6f,%.6f,%.6f,%.6f,%.6f" % (0.15 * math.cos(a), 0.15 * math.sin(a), 0.5 + 0.9 * t,
                                                     0.05 * math.sin(a), 0.05 * math.cos(a), 0.1 * t))
    return rows


def demo_traj():
    """scripts/demo_scenario.sh's trajectory."""
    return ["%.3f,%.6f,%.6f,1.40,0,0,0" % (1.0 + 0.02 * i, 0.03 * math.sin(i / 10), 0.02 * math.cos(i / 10))
            for i in range(12)]


def seeds(tse_kin, tse_sim):
    out = []
    poses = demo_poses()
    # one CSV row, at several maxima
    for opt, row in [(5, poses[1]), (5, " 1 ,\t2,3,4,5,6\r\n"), (0, "nan"), (2, "inf,-inf,1e308"),
                     (3, "1,,3"), (3, "1,2x,3"), (0, "  \t"), (1, "0x1p-3,1e-320"), (2, "1,2\x003"),
                     (5, ",".join(["1"] * 8)), (0, "1" * 130), (0, "\v1"), (11, "1,2,3,4,5,6,7,8,9,10,11,12")]:
        out.append(pick(CSV_ROW, opt) + row.encode("latin-1"))
    # tse-kin's stdin: ik (opt 0), fk (opt 1), jacobian (opt 2)
    out.append(pick(KIN_STREAM, 0) + ("x,y,z,roll,pitch,yaw\n" + "\n".join(poses) + "\n").encode())
    out.append(pick(KIN_STREAM, 0) + BOM + ("\r\n".join(poses[:3])).encode())
    out.append(pick(KIN_STREAM, 0) + (poses[0] + "\nx,y,z,roll,pitch,yaw\n").encode())
    out.append(pick(KIN_STREAM, 1) + b"s_a1,s_b1,s_a2,s_b2,s_a3,s_b3\n0.4,0.4,0.4,0.4,0.4,0.4\n"
               + b"0.4,0.4,0.4,0.4,0.4,0.4,0,0,1,0,0,0\nnan,inf,1,2,3,4\n\n1,2,3\n")
    out.append(pick(KIN_STREAM, 2) + b"nan,inf,nan,inf,nan,inf\n\x00\n" + b"1," * 2100 + b"\n1,2,3,4,5,6")
    # trajectory files
    traj = demo_traj()
    out.append(pick(TRAJ) + ("\n".join(traj) + "\n").encode())
    out.append(pick(TRAJ) + BOM + ("# a comment\n\r\n  \nT, X ,y,Z,roll,PITCH,yaw\r\n" + "\r\n".join(traj[:3])).encode())
    out.append(pick(TRAJ) + b"0.5,0,0,1,0,0,0\n0.5005,0,0,1,0,0,0\n")
    out.append(pick(TRAJ) + b"60,4,-4,4,3.141593,-3.141593,0\n120.000001,0,0,1,0,0,0\n")
    out.append(pick(TRAJ) + b"t,x,y,z,roll,pitch,yaw\n# only a header\n")
    out.append(pick(TRAJ) + b"0.1,0,0,1,0,0\n")
    out.append(pick(TRAJ) + b"0.1,0,0,1,0,0,0,0\n0.2,abc,0,1,0,0,0\n")
    out.append(pick(TRAJ) + b"0.1,4.5,0,1,0,0,0\n")
    out.append(pick(TRAJ) + b"0.1,nan,0,1,0,0,0\n")
    out.append(pick(TRAJ) + b"hello\n")
    out.append(pick(TRAJ) + b"0.1,0,0,1,0,0,0\n" + b"#" * 4100 + b"\n")
    out.append(pick(TRAJ) + b"0.0000005,0,0,1,0,0,0\n")
    # tse-kin parameter files
    template = subprocess.run([tse_kin, "params"], check=True, capture_output=True).stdout
    out.append(pick(KIN_PARAMS, 0) + template)
    out.append(pick(KIN_PARAMS, 1) + BOM + template.replace(b"\n", b"\r\n"))
    for text in [b"eta_deg = 30\nalpha_min_deg = 10.8\nalpha_max_deg=69.6 # degrees\n",
                 b"eta = 0.5\neta_deg = 30\n", b"L = 1.727\nL = 1.8\n", b"k1 = 1.5\n", b"s_max = -1\n",
                 b"alpha_min = 1.3\n", b"mu_min = 1e-400\n", b"L = nan\n", b"L 1.7\n", b"unknown = 1\n",
                 b"slide_vmax = 0.2\nwatchdog_ms = 0\nslide_vmax = 0.1\n", b"can_kbps = 1e999\n",
                 b"L = " + b"1" * 510 + b"\n", b"#" + b" " * 511 + b"\nL = 2\n", b"L = 2\x00\n", b"=\n", b""]:
        out.append(pick(KIN_PARAMS, len(out) % 2) + text)
    # the controller's SI parameter file, as tse-sim writes it
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "sim.params")
        subprocess.run([tse_sim, "--write-params", path], check=True, capture_output=True)
        with open(path, "rb") as f:
            written = f.read()
    out.append(pick(PARAM_FILE, 0) + written)
    out.append(pick(PARAM_FILE, 1) + BOM + written.replace(b"\n", b"\r\n"))
    for text in [b"ETA_DEG = 30\nalpha_min_deg = 10\n", b"eta = 0.5\neta_deg = 30\n", b"L = 0.05\n",
                 b"can_kbps = 300\n", b"can_kbps = 250 # slower\n", b"home_sw_3 = 0.95\n",
                 b"s_max = 0.1\n", b"alpha_min = 1.3\n", b" = 1\n", b"watchdog_ms\n", b"L = 1.8e\n",
                 b"slide_vmax = 0.0000005\n", b"L = 1.7270005\n", b"k1 = 0.0000015\n", b"home_sw_1 = 0x1p-3\n",
                 b"L = 1\x00\n", b"steps_per_m = 1280000.5\n", b"eta = -1.570796\n", b""]:
        out.append(pick(PARAM_FILE, len(out) % 4) + text)
    return out


def main(tse_kin, tse_sim, out_dir):
    os.makedirs(out_dir, exist_ok=True)
    for data in seeds(tse_kin, tse_sim):
        with open(os.path.join(out_dir, hashlib.sha1(data).hexdigest()), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
