"""The trajectory files of stream.sh, laid out as README says: the first row at the current pose
(PLATE, the simulator's last 'at rest' pose), rows 20 ms apart, no hold row.
  circle.csv  a circle of 2 cm radius in 3 s, minimum-jerk in its angle, back to the start
  fast.csv    the same circle in 2.4 s: a row in its first half asks a slide for more than its
              acceleration limit, which tsectl and tse.can refuse before sending
  long.csv    the circle in 6 s, for a STOP from another terminal while it streams
Usage: python3 stream_files.py X Y Z ROLL PITCH YAW"""
import math
import sys


def circle(p0, radius, seconds, dt=0.02):
    n, rows = round(seconds / dt), []
    for i in range(1, n + 1):
        s = i / n
        e = s * s * s * (10 - 15 * s + 6 * s * s)
        a = 2 * math.pi * e
        rows.append((dt * i, p0[0] + radius * math.sin(a), p0[1] + radius * (1 - math.cos(a)), *p0[2:]))
    return rows


def write(path, rows):
    with open(path, "w") as f:
        f.write("t,x,y,z,roll,pitch,yaw\n")
        for r in rows:
            f.write(",".join(f"{v:.6f}" for v in r) + "\n")


p0 = [float(v) for v in sys.argv[1:7]]
write("circle.csv", circle(p0, 0.02, 3.0))
write("fast.csv", circle(p0, 0.02, 2.4))
write("long.csv", circle(p0, 0.02, 6.0))
