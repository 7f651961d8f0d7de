"""Every signal of the committed DBC against the message table: bit position, length,
signedness, byte order, factor, offset, range (exactly the raw limits times the scale) and unit,
and a comment (the field's doc) for each.  The DBC is read twice, by python3-canmatrix and by the
small SG_ / CM_ SG_ line reader below, so that neither reader's quirks hide a defect; the table
comes from table_dump (the compiled table), not from protogen.
Usage: dbc_signals.py TABLE_DUMP DBC"""
import re
import sys
from decimal import Decimal

import table_rows

BO = re.compile(r"^BO_ (\d+) (\w+): (\d+) (\w+)$")
SG = re.compile(r'^ SG_ (\w+) : (\d+)\|(\d+)@([01])([+-]) \(([^,()]+),([^,()]+)\) '
                r'\[([^|\]]+)\|([^|\]]+)\] "([^"]*)" (\S+)$')
CM_SG = re.compile(r'^CM_ SG_ (\d+) (\w+) "([^"]*)";$')
INTEGER = re.compile(r"^-?[0-9]+$")


def signal(start, size, signed, little, factor, offset, lo, hi, unit, comment, where, lo_text=None, hi_text=None):
    return dict(start=int(start), size=int(size), signed=signed, little=little, factor=Decimal(factor),
                offset=Decimal(offset), min=Decimal(lo), max=Decimal(hi), unit=unit, comment=comment or "",
                where=where, min_text=lo_text, max_text=hi_text)


def read_lines(path):
    """{id: (name, dlc, {signal: dict})} from the text, with file:line for every signal."""
    frames, current, errors = {}, None, []
    with open(path, encoding="ascii") as f:
        lines = f.read().splitlines()
    for number, line in enumerate(lines, 1):
        at = f"{path}:{number}"
        if line.startswith("BO_ "):
            m = BO.match(line)
            if not m:
                errors.append(f"{at}: cannot read the BO_ line")
                current = None
                continue
            current = int(m.group(1))
            if current in frames:
                errors.append(f"{at}: message id {current} defined twice")
            frames[current] = (m.group(2), int(m.group(3)), {})
        elif line.startswith(" SG_"):
            m = SG.match(line)
            if not m or current is None:
                errors.append(f"{at}: cannot read the SG_ line" if not m else f"{at}: SG_ outside a message")
                continue
            name, start, size, order, sign, factor, offset, lo, hi, unit, _ = m.groups()
            frames[current][2][name] = signal(start, size, sign == "-", order == "1", factor, offset, lo, hi, unit,
                                              None, at, lo, hi)
        elif line.startswith("CM_ SG_"):
            m = CM_SG.match(line)
            sigs = frames.get(int(m.group(1)), (None, None, {}))[2] if m else {}
            if not m or m.group(2) not in sigs:
                errors.append(f"{at}: a CM_ SG_ line that names no signal of the file")
            elif sigs[m.group(2)]["comment"]:
                errors.append(f"{at}: a second comment for {m.group(2)}")
            else:
                sigs[m.group(2)]["comment"] = m.group(3)
    return frames, errors


def read_canmatrix(path):
    import canmatrix.formats
    db = canmatrix.formats.loadp_flat(path)
    frames = {}
    for fr in db.frames:
        sigs = {}
        for s in fr.signals:
            sigs[s.name] = signal(s.start_bit, s.size, s.is_signed, s.is_little_endian, s.factor, s.offset, s.min,
                                  s.max, s.unit, s.comment, "canmatrix")
        frames[fr.arbitration_id.id] = (fr.name, fr.size, sigs)
    return frames


def expected(messages):
    """(id, DBC message name, table message) for every message the DBC must hold."""
    out = [(m.can_id(1), m.name, m) for m in messages]
    out += [(m.can_id(0), table_rows.BROADCAST[m.name], m) for m in messages if m.name in table_rows.BROADCAST]
    return out


def check(reader, frames, messages):
    """Problems, one line each, and the number of signals found right."""
    problems, good = [], 0
    want = expected(messages)
    for extra in sorted(set(frames) - {i for i, _, _ in want}):
        problems.append(f"{reader}: message {frames[extra][0]} (id {extra}) is not in the table")
    for can_id, name, msg in want:
        if can_id not in frames:
            problems.append(f"{reader}: {name} (id {can_id}) is missing")
            continue
        fname, dlc, sigs = frames[can_id]
        if fname != name or dlc != msg.dlc:
            problems.append(f"{reader}: id {can_id} is {fname} of {dlc} bytes, the table says {name} of {msg.dlc}")
        for extra in sorted(set(sigs) - {f.name for f in msg.fields}):
            problems.append(f"{sigs[extra]['where']}: {name}.{extra} is not a field of the table")
        for f in msg.fields:
            s = sigs.get(f.name)
            if s is None:
                problems.append(f"{reader}: {name}.{f.name} is missing")
                continue
            lo, hi = f.type_range()
            want_sig = dict(start=f.offset * 8, size=f.bits, signed=f.signed, little=True, factor=f.scale_dec,
                            offset=Decimal(0), min=Decimal(f.min) * f.scale_dec, max=Decimal(f.max) * f.scale_dec,
                            unit=f.unit, comment=f.meaning())
            bad = [f"{k} {s[k]!r}, the table says {v!r}" for k, v in want_sig.items() if s[k] != v]
            if not lo <= f.min <= f.max <= hi:
                bad.append(f"the table's range {f.min}..{f.max} is outside {f.type} ({lo}..{hi})")
            if f.scale != 1.0 and not s["unit"]:
                bad.append(f"scaled by {f.scale_dec} but no unit")
            if not s["comment"]:
                bad.append("no comment")
            if f.scale == 1.0 and s["min_text"] is not None and not (
                    INTEGER.match(s["min_text"]) and INTEGER.match(s["max_text"])):
                bad.append(f"range [{s['min_text']}|{s['max_text']}] of an unscaled signal is not printed as integers")
            problems += [f"{s['where']}: {name}.{f.name}: {b}" for b in bad]
            good += not bad
    return problems, good


def main():
    dumper, dbc = sys.argv[1], sys.argv[2]
    messages = table_rows.load(dumper)
    by_lines, problems = read_lines(dbc)
    p1, good1 = check("line reader", by_lines, messages)
    p2, good2 = check("canmatrix", read_canmatrix(dbc), messages)
    problems += p1 + p2
    for p in problems:
        print("FAIL", p)
    print(f"{good1 + good2} signals right, {len(problems)} problems")
    return 1 if problems or not good1 or not good2 else 0


if __name__ == "__main__":
    sys.exit(main())
