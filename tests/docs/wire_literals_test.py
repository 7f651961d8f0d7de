#!/usr/bin/env python3
"""scripts/check_wire_literals.py finds the tree clean, and finds each kind of literal planted in a
copy of a real host source (C and Python), naming its line; the same copies unplanted pass, so it
is the planting that fails them.  Usage: wire_literals_test.py CHECKER ROOT"""
import subprocess
import sys
import tempfile
from pathlib import Path

checker, root = sys.argv[1], Path(sys.argv[2])


def run(*args):
    return subprocess.run([sys.executable, checker, *map(str, args)], capture_output=True, text=True)


r = run(root)
assert r.returncode == 0, f"the tree has wire literals:\n{r.stdout}"

# (source, what it holds, what to plant in its place, the checker's words)
plants = [
    ("host_tools/tsectl/cmd_status.c", "fl & PROTO_STATUS_HOMED", "fl & 1", "STATUS flag bit"),
    ("python/tse/can.py", 'bool(f & bit["homed"])', 'bool(v["flags"] & 0x01)', "STATUS flag bit"),
    ("host_tools/tsectl/telemetry.c", "(double)m->v[0] / PROTO_NM_PER_M", "m->v[0] * 1e-9", "scaled by a literal"),
    ("python/tse/can.py", 'raw["where"] / _P.PER_MILLE', 'raw["where"] / 1000.0', "scaled by a literal"),
    ("firmware/src/commands.c", "(tse_real)th->stage_v[k] * (TSE_R(1.0) / (tse_real)proto_pose_units(k))",
     "(tse_real)th->stage_v[k] * TSE_R(1e-6)", "scaled by a literal"),
    ("host_tools/common/traj_file.h", "((long long)PROTO_DT_MAX_US)", "60000000LL", "wire range"),
]
with tempfile.TemporaryDirectory() as tmp:
    for i, (src, holds, planted, words) in enumerate(plants):
        text = (root / src).read_text()
        assert holds in text, f"{src} no longer holds {holds!r}: update this test"
        clean = Path(tmp) / f"clean{i}{Path(src).suffix}"
        clean.write_text(text)
        r = run(clean)
        assert r.returncode == 0, f"a clean copy of {src} fails:\n{r.stdout}"
        bad = Path(tmp) / f"planted{i}{Path(src).suffix}"
        bad.write_text(text.replace(holds, planted, 1))
        line = text[:text.index(holds)].count("\n") + 1
        r = run(bad)
        assert r.returncode == 1 and f"{bad}:{line}: " in r.stdout and words in r.stdout, \
            f"{planted!r} planted in {src}:{line} not found:\n{r.stdout}"
print(f"wire literals: the tree is clean; {len(plants)} planted literals each found at their line")
