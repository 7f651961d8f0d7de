"""How fast the emulator runs the production image: virtual seconds per real second, and the
host CPU the emulator takes, while the controller is idle (disabled) and while it is moving
(homing, six slides stepping).  Prints figures; asserts nothing.

    time_ratio.py ELF [SECONDS] [--icount SPEC] [-- qemu arguments, e.g. -global tse-f407-soc.wfi-nop=off]
"""
import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))

import tse.can as tc  # noqa: E402
from emu_session import Emulator  # noqa: E402


def cpu_seconds(pid):
    """User + system CPU of pid and its children (run.sh execs QEMU: the same pid)."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def measure(em, pid, seconds):
    v0, t0, c0 = em.time_ns(), time.monotonic(), cpu_seconds(pid)
    time.sleep(seconds)
    v1, t1, c1 = em.time_ns(), time.monotonic(), cpu_seconds(pid)
    return (v1 - v0) / 1e9 / (t1 - t0), (c1 - c0) / (t1 - t0)


def main():
    args = sys.argv[1:]
    extra, icount = [], None
    if "--" in args:
        extra = args[args.index("--") + 1:]
        args = args[:args.index("--")]
    if "--icount" in args:
        i = args.index("--icount")
        icount = args[i + 1]
        del args[i:i + 2]
    if not args:
        print(__doc__, file=sys.stderr)
        return 2
    elf, seconds = args[0], float(args[1]) if len(args) > 1 else 10.0
    with tempfile.TemporaryDirectory() as d:
        with Emulator(elf, d, icount=icount, extra=tuple(extra)) as em:
            pid = em._proc.pid
            bus = em.bus()
            c = tc.Controller(bus=bus, node=1, timeout=60.0)
            c.status()
            ratio, cpu = measure(em, pid, seconds)
            print(f"idle (disabled): virtual/real {ratio:.3f}, host CPU {cpu:.2f} cores")
            c.enable()
            c.home(wait=False)
            ratio, cpu = measure(em, pid, seconds)
            print(f"homing (six slides stepping, state {c.status().state}): virtual/real {ratio:.3f}, "
                  f"host CPU {cpu:.2f} cores")
            load = os.getloadavg()
            print(f"host load average {load[0]:.1f} on {os.cpu_count()} cores")
            c.close()
            bus.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
