#!/usr/bin/python3
"""The planner through tse.plan against tse-kin's own: the 1,000-waypoint path of `tse-kin bench
plan` (a wandering loop, cmd_bench_plan.c), planned by tse.plan.plan (libtse_kin.so, the same C),
the median of 5 rounds; with --tse-kin PATH it runs `PATH bench plan` and prints the ratio.
A figure, never a test.

Usage: PYTHONPATH=python bench/plan_python.py [--tse-kin build/host/host_tools/tse-kin]
"""
import argparse
import statistics
import subprocess
import time

import numpy as np

from tse import plan


def waypoints(n=1000):
    k = np.arange(n)
    phi, r = 2 * np.pi * k / 100, 0.05 * (1 + 0.2 * np.sin(k / 170))
    return np.column_stack([r * np.cos(phi) - 0.05, r * np.sin(phi), 1.0 + 0.08 * np.sin(2 * np.pi * k / 400),
                            0.03 * np.sin(2 * np.pi * k / 300), 0.03 * np.cos(2 * np.pi * k / 250) - 0.03,
                            0.15 * np.sin(2 * np.pi * k / 500)])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tse-kin")
    args = ap.parse_args()
    wp, times = waypoints(), []
    for _ in range(5):
        t0 = time.perf_counter()
        p = plan.plan(wp)
        times.append(time.perf_counter() - t0)
    ms = statistics.median(times) * 1e3
    print(f"tse.plan: {ms:.1f} ms for a {p.duration:.2f} s trajectory of {len(p.rows)} rows "
          f"(the rows measured against the limits too)")
    print(f"bench,tse_plan_ms,{ms:.3f}")
    if args.tse_kin:
        out = subprocess.run([args.tse_kin, "bench", "plan"], capture_output=True, text=True, check=True).stdout
        figures = dict(line.split(",")[1:] for line in out.splitlines() if line.startswith("bench,"))
        c_ms = float(figures["plan_ms"])
        print(f"tse-kin bench plan: {c_ms:.1f} ms; tse.plan / tse-kin: {ms / c_ms:.2f}")
        print(f"bench,tse_plan_over_tse_kin,{ms / c_ms:.3f}")


if __name__ == "__main__":
    main()
