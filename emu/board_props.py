#!/usr/bin/env python3
"""The board an image is built for, read from its .tse_board section (board_identity in
hal/stm32f4/include/hal_stm32f4/board_desc.h), as emu/run.sh passes it to the emulator.

    board_props.py IMAGE.elf

Prints `key=value` lines: board (its name), hse (the crystal, Hz), machine (the tse-f407 machine's
pin properties, a `,`-led suffix of -M), enable_active_low (on/off: the rig's enable-active-low).
An image without the section (a test image) is the generic board's: prints nothing, exit 0.
Exit 2 when the file is not a 32-bit little-endian ELF or its section is malformed.
"""
import struct
import sys

ID_BYTES = 48
SLIDES = 6
LAYOUT = struct.Struct(f"<{ID_BYTES}sII{SLIDES}s{SLIDES}s{SLIDES}s{SLIDES}sBBBBBBBB")


def section(data, name):
    if data[:4] != b"\x7fELF" or data[4] != 1 or data[5] != 1:
        raise ValueError("not a 32-bit little-endian ELF")
    shoff, = struct.unpack_from("<I", data, 0x20)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x2E)
    headers = [struct.unpack_from("<IIIIIIIIII", data, shoff + i * shentsize) for i in range(shnum)]
    names = headers[shstrndx]
    for h in headers:
        start = names[4] + h[0]
        got = data[start:data.index(b"\0", start)].decode()
        if got == name:
            return data[h[4]:h[4] + h[5]]
    return None


def pin(p):
    return "-" if p == 0xFF else f"{'ABCDEFGHI'[p >> 4]}{p & 15}"


def pins(ps):
    return ":".join(pin(p) for p in ps)


def main():
    if len(sys.argv) != 2:
        print("usage: board_props.py IMAGE.elf", file=sys.stderr)
        return 2
    with open(sys.argv[1], "rb") as f:
        data = f.read()
    try:
        raw = section(data, ".tse_board")
        if raw is None:
            return 0
        (ident, hse, app, step, dirs, lim, enable, enable_high, estop, _led, _led_high, can_rx, can_tx,
         boot_usart, _boot_tx) = LAYOUT.unpack_from(raw)
    except (ValueError, struct.error, IndexError) as e:
        print(f"board_props.py: {sys.argv[1]}: {e}", file=sys.stderr)
        return 2
    name = ident.rstrip(b"\0").decode()
    if not name.startswith("tse-board:"):
        print(f"board_props.py: {sys.argv[1]}: .tse_board does not start with tse-board:", file=sys.stderr)
        return 2
    print(f"board={name[len('tse-board:'):]}")
    print(f"hse={hse}")
    print(f"machine=,step-pins={pins(step)},dir-pins={pins(dirs)},enable-pin={pin(enable[0])},"
          f"lim-pins={pins(lim)},estop-pin={pin(estop)},can-pins={pins((can_rx, can_tx))},"
          f"boot-usart={boot_usart},app-addr={app:#010x}")
    print(f"enable_active_low={'off' if enable_high else 'on'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
