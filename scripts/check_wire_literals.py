#!/usr/bin/env python3
"""Finds the wire's facts written as literals instead of by their names (issue 27: one source).

STATUS's flag bits, the wire's units and its ranges are named once, in the message table
(firmware/include/fw/proto_wire.h: PROTO_STATUS_*, PROTO_UM_PER_M, ...), and printed into
python/tse/_protocol.py by protogen.  Everywhere else they are used by name; a literal is a copy that
can drift.  This script looks, line by line, in the C of the firmware and the host tools and in the
Python package (the table's own files and the generated ones excepted) for
  - a number masked against a STATUS flags value (`flags & 4`, `v[2] & 0x01`);
  - a power of ten that scales a wire field (`m->v[0] * 1e-9`, `raw["where"] / 1000.0`);
  - a wire range (4000000 um, 3141593 urad, 60000000 us, 3600000).
and prints each as FILE:LINE: what.  Exit 0 when there is none, 1 otherwise.

  scripts/check_wire_literals.py [ROOT | FILE...]   (default: the tree this script is in)
"""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WHERE = ["firmware/src", "firmware/doc", "host_tools", "python/tse", "planner", "hal"]
EXEMPT = {"python/tse/_protocol.py"}

NUM = r"(?:0x[0-9A-Fa-f]+|[0-9]+)\b"
FLAG = re.compile(r"(?:\bflags\w*|\bfl|\bv\[2\]|\[\"flags\"\])\s*&\s*" + NUM)
FIELD = re.compile(r"(?:\bv\[|\braw\[|\bstage_v\[|\back\[)")
SCALE = re.compile(r"[*/]\s*(?:TSE_R\()?\s*(?:1e-?0?[369]|1000000000|1000000|1000(?:\.0)?|1e3)\b")
RANGE = re.compile(r"(?<![\w.])(?:4000000|3141593|60000000|3600000)[uUlL]*(?![\w.])")


def strip_comment(line, python):
    """The line without its comment (a rough cut: enough for code written as ours is)."""
    if python:
        return line.split("#", 1)[0]
    line = re.sub(r"/\*.*?\*/", "", line)
    return line.split("//", 1)[0]


def check_file(path, shown):
    python = path.suffix == ".py"
    found = []
    in_block = False
    for n, raw in enumerate(path.read_text(errors="replace").splitlines(), 1):
        line = raw
        if not python:
            if in_block:
                if "*/" not in line:
                    continue
                line = line.split("*/", 1)[1]
                in_block = False
            if "/*" in line and "*/" not in line.split("/*", 1)[1]:
                line = line.split("/*", 1)[0]
                in_block = True
        code = strip_comment(line, python)
        flagged = FLAG.search(code)  # (before strings go: Python names the field in one)
        code = re.sub(r'"(?:[^"\\]|\\.)*"', '""', code)  # strings say numbers in words
        if flagged:
            found.append(f"{shown}:{n}: a STATUS flag bit as a number (use PROTO_STATUS_* / STATUS_FLAGS)")
        if FIELD.search(code) and SCALE.search(code):
            found.append(f"{shown}:{n}: a wire field scaled by a literal (use PROTO_*_PER_* / _protocol's units)")
        if RANGE.search(code):
            found.append(f"{shown}:{n}: a wire range as a number (use PROTO_*_MAX_* / _protocol's ranges)")
    return found


def files(root):
    for d in WHERE:
        base = root / d
        if not base.exists():
            continue
        for p in sorted(base.rglob("*")):
            rel = p.relative_to(root).as_posix()
            if p.suffix in (".c", ".h", ".py") and rel not in EXEMPT and "protogen" not in rel:
                yield p, rel


def main(argv):
    targets = [Path(a) for a in argv[1:]] or [ROOT]
    found = []
    for t in targets:
        if t.is_dir():
            for p, rel in files(t):
                found += check_file(p, rel)
        else:
            found += check_file(t, str(t))
    for f in found:
        print(f)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
