"""Decodes a candump -L log with the DBC (python3-canmatrix): every frame of the session must be
a message of the DBC and decode; prints what it saw.  Usage: decode_log.py DBC LOG"""
import collections
import sys

import canmatrix.formats


def main():
    db = canmatrix.formats.loadp_flat(sys.argv[1])
    seen = collections.Counter()
    bad = 0
    with open(sys.argv[2]) as f:
        for line in f:
            parts = line.split()
            if len(parts) < 3 or "#" not in parts[2]:
                continue
            ident, data = parts[2].split("#", 1)
            frame = db.frame_by_id(canmatrix.ArbitrationId(int(ident, 16)))
            if frame is None:
                print(f"FAIL: {ident} is not in the DBC")
                bad += 1
                continue
            try:
                frame.decode(bytearray.fromhex(data))
            except Exception as e:  # a frame the DBC cannot take apart
                print(f"FAIL: {frame.name} {data}: {e}")
                bad += 1
                continue
            seen[frame.name] += 1
    print("decoded with the DBC: " + ", ".join(f"{k} {v}" for k, v in sorted(seen.items())))
    total = sum(seen.values())
    print(f"{total} passed, {bad} failed")
    return 1 if bad or not total else 0


if __name__ == "__main__":
    sys.exit(main())
