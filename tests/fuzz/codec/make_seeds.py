#!/usr/bin/env python3
"""Writes the codec's seed corpus from the compiled table (tests/protocol's table_dump): for every
message, a frame at its length with every field at its minimum, at its maximum, and at zero where
zero is in range, to decode in the message's direction; and an encode request with the same values.
Run it again when the table changes:
    make_seeds.py build/host/tests/protocol/proto_table_dump tests/fuzz/codec/corpus"""
import hashlib
import os
import struct
import subprocess
import sys

WIDTH = {"u8": 1, "i8": 1, "u16": 2, "i16": 2, "u24": 3, "i24": 3, "u32": 4, "i32": 4}

def main(dump, out):
    msgs, order = {}, []
    for line in subprocess.run([dump], check=True, capture_output=True, text=True).stdout.splitlines():
        f = line.split("\t")
        if f[0] == "M":
            msgs[f[1]] = {"function": int(f[2], 0), "dlc": int(f[3]), "fields": []}
            order.append(f[1])
        elif f[0] == "F":
            msgs[f[1]]["fields"].append((f[3], int(f[4]), int(f[5]), int(f[6])))
    os.makedirs(out, exist_ok=True)
    seeds = []
    for index, name in enumerate(order):
        m = msgs[name]
        to_host = name in ("REJECT", "ACK", "STATUS", "SLIDES_A", "SLIDES_B", "SLIDES_C", "FK_A",
                           "FK_B", "FK_C", "PARAM_VALUE")
        for pick in (lambda lo, hi: lo, lambda lo, hi: hi, lambda lo, hi: min(max(0, lo), hi)):
            data = bytearray(8)
            values = []
            for typ, off, lo, hi in m["fields"]:
                v = pick(lo, hi)
                values.append(v)
                data[off:off + WIDTH[typ]] = (v & ((1 << 8 * WIDTH[typ]) - 1)).to_bytes(WIDTH[typ], "little")
            ident = m["function"] << 4 | 1
            seeds.append(bytes([2 if to_host else 0]) + struct.pack("<HB", ident, m["dlc"]) + bytes(data))
            words = [v & 0xFFFFFFFF for v in values] + [0] * (7 - len(values))
            seeds.append(bytes([1, index, 1]) + struct.pack("<7I", *words))
    for s in seeds:
        with open(os.path.join(out, hashlib.sha1(s).hexdigest()), "wb") as fh:
            fh.write(s)
    print(f"{len(set(seeds))} seeds in {out}")

if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
