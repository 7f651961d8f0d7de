"""docs/protocol.md against the message table, for the typos a reader found: no "1 bytes", no
line ending in "; " (or any trailing space), no unit cell without its scale (`m x `, `- x `), and
MOVE_COMMIT.value's unit saying both ms and um/s.  Every message's heading is checked for its
function, id and length, and every field's unit cell must read "<scale> <unit>" with the table's
scale and unit, or "-" for a plain number.  The table comes from table_dump, not from protogen.
Usage: md_typos.py TABLE_DUMP PROTOCOL_MD"""
import re
import sys

import table_rows


def cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def main():
    dumper, path = sys.argv[1], sys.argv[2]
    messages = table_rows.load(dumper)
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    problems = []

    for number, line in enumerate(lines, 1):
        at = f"{path}:{number}"
        if re.search(r"\b1 bytes\b", line):
            problems.append(f"{at}: '1 bytes'")
        if line.endswith("; "):
            problems.append(f"{at}: the line ends in '; ' (a list left open)")
        elif line != line.rstrip():
            problems.append(f"{at}: trailing space")
        if line.startswith("|"):
            for c in cells(line):
                if re.search(r"(^|\s)x$", c):
                    problems.append(f"{at}: cell '{c}' is a unit without its scale")

    checked = 0
    for msg in messages:
        head = re.compile(rf"^### `{msg.name}`: function 0x([0-9A-F]{{2}}), id 0x([0-9A-F]{{3}}) \+ node, "
                          rf"(\d+) (bytes?), ")
        found = [(i, head.match(l)) for i, l in enumerate(lines) if head.match(l)]
        if len(found) != 1:
            problems.append(f"{path}: {len(found)} headings for {msg.name}, want 1")
            continue
        start, m = found[0]
        at = f"{path}:{start + 1}"
        if int(m.group(1), 16) != msg.function or int(m.group(2), 16) != msg.function << 4:
            problems.append(f"{at}: {msg.name}'s function or id differs from the table's 0x{msg.function:02X}")
        if int(m.group(3)) != msg.dlc or m.group(4) != ("byte" if msg.dlc == 1 else "bytes"):
            problems.append(f"{at}: '{m.group(3)} {m.group(4)}' for a {msg.dlc}-byte message")
        end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("#")), len(lines))
        rows = [(i, cells(lines[i])) for i in range(start + 1, end) if lines[i].startswith("|")]
        if not rows:
            problems.append(f"{at}: no field table for {msg.name}")
            continue
        header = rows[0][1]
        unit_col = next((k for k, c in enumerate(header) if "unit" in c or "raw count" in c), None)
        if unit_col is None or "field" not in header:
            problems.append(f"{path}:{rows[0][0] + 1}: no field or unit column in {msg.name}'s table")
            continue
        by_field = {r[header.index("field")].strip("`"): (i, r) for i, r in rows[2:]}
        for f in msg.fields:
            if f.name not in by_field:
                problems.append(f"{at}: {msg.name}.{f.name} has no row")
                continue
            i, row = by_field[f.name]
            cell = row[unit_col] if unit_col < len(row) else ""
            good = cell == "-" if not f.unit else False
            if f.unit:
                m = re.match(r"^(\S+) (.+)$", cell)
                try:
                    good = bool(m) and float(m.group(1)) == f.scale and m.group(2) == f.unit
                except ValueError:
                    good = False
            if not good:
                want = "-" if not f.unit else f"{f.scale!r} {f.unit}"
                problems.append(f"{path}:{i + 1}: {msg.name}.{f.name} unit cell '{cell}', want '{want}'")
            if msg.name == "MOVE_COMMIT" and f.name == "value":
                for unit in ("ms", "um/s"):
                    if unit not in cell or unit not in row[-1]:
                        problems.append(f"{path}:{i + 1}: MOVE_COMMIT.value does not say '{unit}' in its unit "
                                        f"and its meaning")
            checked += 1

    for p in problems:
        print("FAIL", p)
    print(f"{checked} fields checked, {len(problems)} problems")
    return 1 if problems or not checked else 0


if __name__ == "__main__":
    sys.exit(main())
