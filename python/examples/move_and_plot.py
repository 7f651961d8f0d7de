#!/usr/bin/env python3
"""Drives a TSE controller (or tse-sim) through a move and plots its telemetry.

    python3 move_and_plot.py [--channel vcan0] [--node 1] [--csv FILE] [--png FILE]
    python3 move_and_plot.py --plot-from FILE.csv --png FILE.png

Enables and homes the controller if it is not homed, moves the plate to a pose and back while
recording every telemetry period (the six commanded slides and the plate pose from the
controller's forward kinematics), writes the samples as CSV and plots them with matplotlib: slide
positions against time above, plate position below.  --plot-from plots a CSV written earlier (for
a machine where the bus is and matplotlib is not, or the other way round).

Try it with the simulator:   tse-sim --iface vcan0 --node 1 &
                             PYTHONPATH=python python3 python/examples/move_and_plot.py --png move.png
"""
import argparse
import csv
import sys
import threading

COLUMNS = ["t", "s_a1", "s_b1", "s_a2", "s_b2", "s_a3", "s_b3", "x", "y", "z", "roll", "pitch", "yaw", "state"]
POSES = ([0.12, -0.06, 1.25, 0.08, -0.05, 0.15], [0.0, 0.0, 1.2, 0.0, 0.0, 0.0])


def record(channel, node, duration):
    """Runs the moves and returns the telemetry samples (rows of COLUMNS, t from the first)."""
    from tse.can import Controller

    samples = []
    with Controller(channel, node=node) as ctl:
        st = ctl.status()
        if st.state in ("fault", "estop"):
            ctl.clear()
            st = ctl.status()
        if not st.enabled:
            ctl.enable()
        if not st.homed:
            print("homing ...", flush=True)
            ctl.home(wait=True)
        done = threading.Event()

        def watch():
            for tel in ctl.watch(timeout=1.0):
                if tel.pose is not None:
                    samples.append([tel.time, *tel.slides, *tel.pose, tel.state])
                if done.is_set():
                    return

        watcher = threading.Thread(target=watch, daemon=True)
        watcher.start()
        for pose in POSES:
            planned = ctl.move(pose, duration=duration)
            print(f"moved to {pose} ({planned:.2f} s planned)", flush=True)
        done.set()
        watcher.join(timeout=3.0)
    t0 = samples[0][0] if samples else 0.0
    for s in samples:
        s[0] -= t0
    print(f"{len(samples)} telemetry samples over {samples[-1][0] if samples else 0:.2f} s")
    return samples


def write_csv(path, samples):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for s in samples:
            w.writerow([f"{v:.9g}" for v in s[:-1]] + [s[-1]])


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows or rows[0] != COLUMNS:
        sys.exit(f"{path}: not a telemetry file of this script (header {','.join(COLUMNS)})")
    out = []
    for n, r in enumerate(rows[1:], start=2):
        try:
            out.append([float(v) for v in r[:-1]] + [r[-1]])
        except (ValueError, IndexError):
            sys.exit(f"{path}:{n}: not {len(COLUMNS)} values")
    return out


def plot(path, samples):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = [s[0] for s in samples]
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    for k, name in enumerate(COLUMNS[1:7]):
        top.plot(t, [s[1 + k] for s in samples], label=name.replace("s_", "").upper())
    top.set_ylabel("slide position [m]")
    top.legend(ncol=6, fontsize="small")
    top.set_title("TSE: commanded slides and plate pose (controller telemetry)")
    for k, name in enumerate("xyz"):
        bottom.plot(t, [s[7 + k] for s in samples], label=name)
    bottom.set_ylabel("plate position [m]")
    bottom.set_xlabel("time [s]")
    bottom.legend(fontsize="small")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    print(f"plot written to {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--channel", default="vcan0")
    ap.add_argument("--node", type=int, default=1)
    ap.add_argument("--duration", type=float, default=1.5, help="seconds per move (default 1.5)")
    ap.add_argument("--csv", help="write the samples here")
    ap.add_argument("--png", help="plot them here (needs matplotlib)")
    ap.add_argument("--plot-from", metavar="CSV", help="plot a CSV written earlier instead of moving")
    a = ap.parse_args()
    if a.plot_from:
        if not a.png:
            ap.error("--plot-from needs --png")
        samples = read_csv(a.plot_from)
    else:
        if not (a.csv or a.png):
            ap.error("give --csv FILE, --png FILE or both")
        samples = record(a.channel, a.node, a.duration)
        if not samples:
            sys.exit("no telemetry arrived (telemetry_ms is 0?)")
        if a.csv:
            write_csv(a.csv, samples)
    if a.png:
        plot(a.png, samples)


if __name__ == "__main__":
    main()
