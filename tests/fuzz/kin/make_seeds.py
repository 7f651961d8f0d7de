#!/usr/bin/env python3
"""Writes the kin target's seeds (the byte layout is kin_input.c's): the worked poses of
kinematics.md as exact doubles, plausible poses near the prototype's workspace with each
combination of seeds and forward-kinematics slides, designs near the prototype, and awkward values
(NaN, infinities, huge, subnormal, just beyond float's range).  Run it again when the layout
changes, then minimise into the corpus:
    make_seeds.py /tmp/seeds
    build/fuzz/tests/fuzz/kin/fuzz_kin -merge=1 tests/fuzz/kin/corpus /tmp/seeds"""
import hashlib
import os
import random
import struct
import sys

BOTH, DOUBLE, FLOAT = 0, 1, 2
IK_SEED, FK, FK_SEED, PARAMS = 4, 8, 16, 32
SAME, NUDGED, ANY, MOVED = 0, 64, 128, 192


def raw(x):
    return bytes([6]) + struct.pack("<d", x)


def band(u):
    """A value at fraction u of its plausible band."""
    return bytes([0]) + struct.pack("<H", int(round(u * 65535)))


def awkward(i):
    return bytes([7 | (i << 3)])


def seeds():
    rnd = random.Random(9)
    out = []
    worked = [(0, 0, 1.0, 0, 0, 0), (0.1, -0.05, 1.1, 0.1, -0.05, 0.2)]
    for flags in (BOTH | FK, DOUBLE | FK | NUDGED, FLOAT | FK | MOVED, BOTH | IK_SEED | FK | FK_SEED, BOTH | FK | FK_SEED):
        for pose in worked:
            data = bytes([flags]) + b"".join(raw(x) for x in pose)
            if flags & IK_SEED:
                data += bytes([1]) + bytes(6)  # a warm seed: the pose's own slides
            if flags & FK and flags & 192 in (NUDGED, MOVED):
                data += bytes(rnd.randrange(256) for _ in range(6))
            if flags & FK_SEED:
                data += bytes([1])  # the seed is the pose itself
            out.append(data)
    for n in range(40):
        flags = rnd.choice([BOTH, BOTH | FK, BOTH | IK_SEED, FLOAT | FK | NUDGED, DOUBLE | FK | ANY, BOTH | FK | FK_SEED])
        data = bytes([flags]) + b"".join(band(rnd.uniform(0.3, 0.7) if k < 2 else rnd.random()) for k in range(6))
        data += bytes(rnd.randrange(256) for _ in range(24))
        out.append(data)
    # designs near the prototype
    for n in range(8):
        params = b"".join(bytes([4, rnd.randrange(256)]) if rnd.random() < 0.3 else bytes([0]) for _ in range(11))
        out.append(bytes([BOTH | PARAMS | FK]) + params + b"".join(band(0.5) for _ in range(6)))
    # awkward values in the pose and in the slides
    for i in range(32):
        pose = [band(0.5)] * 6
        pose[i % 6] = awkward(i)
        out.append(bytes([BOTH | FK | ANY]) + b"".join(pose) + b"".join(band(0.45) for _ in range(5)) + awkward(i))
    for x in (1e300, -1e300, 3.5e38, 1e20, 5e-324, 1e5):
        out.append(bytes([BOTH]) + raw(x) + b"".join(band(0.5) for _ in range(5)))
    return out


def main(out_dir):
    os.makedirs(out_dir, exist_ok=True)
    for data in seeds():
        with open(os.path.join(out_dir, hashlib.sha1(data).hexdigest()), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
