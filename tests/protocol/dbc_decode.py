"""Frames packed by the firmware's codec, decoded with the committed DBC by a third-party reader
(Debian's python3-canmatrix): every field must come out with the value that was packed, scaled
as the DBC says.  Usage: dbc_decode.py PROTOGEN DBC"""
import subprocess
import sys

import canmatrix.formats


def main():
    gen, dbc = sys.argv[1], sys.argv[2]
    db = canmatrix.formats.loadp_flat(dbc)
    lines = subprocess.run([gen, "frames", "1"], capture_output=True, text=True, check=True).stdout.splitlines()
    passed = failed = 0
    for line in lines:
        fid, data, name, *fields = line.split(",")
        frame = db.frame_by_id(canmatrix.ArbitrationId(int(fid)))
        ok = frame is not None and frame.name == name
        if ok:
            decoded = frame.decode(bytearray.fromhex(data))
            for f in fields:
                key, raw = f.split("=")
                sig = decoded.get(key)
                if sig is None or int(sig.raw_value) != int(raw):
                    ok = False
                    print(f"FAIL {name}.{key}: packed {raw}, decoded {None if sig is None else sig.raw_value}")
                    continue
                factor = float(frame.signal_by_name(key).factor)
                if abs(float(sig.phys_value) - int(raw) * factor) > 1e-9 * max(1.0, abs(int(raw) * factor)):
                    ok = False
                    print(f"FAIL {name}.{key}: physical {sig.phys_value} != {int(raw) * factor}")
        else:
            print(f"FAIL frame {fid} ({name}) not in the DBC")
        passed += ok
        failed += not ok
    print(f"{passed} passed, {failed} failed")
    return 1 if failed or not passed else 0


if __name__ == "__main__":
    sys.exit(main())
