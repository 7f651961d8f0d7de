"""Firmware updates over the bus, as `tsectl flash` does them (docs/protocol.md, "Updating the
firmware"): Controller.flash(path) calls flash(controller, path).

The image is checked before anything is sent (its header at 0x200, its length, its CRC-32, as zlib
computes it, over its bytes without the crc word); the node is asked what it is (BOOT_QUERY; an
application refuses it `state` and is sent BOOT_ENTER, refused while its drives may be on); an image
for another board or longer than the application area is refused before anything is erased; then
erase, the blocks two in flight (a block refused for its frames, CRC or order is sent again, five
times at most), verify, the bootloader's report checked against the image, and start."""
import struct
import time
import zlib
from collections import namedtuple

HEADER_OFFSET = 0x200
HEADER_BYTES = 48
CRC_OFFSET = HEADER_OFFSET + 20
MAGIC = 0x49455354          # b"TSEI" in memory order
HEADER_VERSION = 1
WINDOW = 2                  # blocks in flight (boot/update.h: BOOT_WINDOW_BLOCKS)
BOOT_MAGIC = 0x544F4F42     # BOOT_ENTER's b"BOOT"
RETRIES = 5

Image = namedtuple("Image", "data board board_name version length crc")
Flashed = namedtuple("Flashed", "version crc erase_s transfer_s rate")
Flashed.__doc__ = """What Controller.flash did: the version and CRC the bootloader reports, the erase's and the
transfer's seconds, and the transfer's rate in bytes per second (wall clock)."""


def board_id(name):
    """A board's identity: the CRC-32 of its name (boot/image.h)."""
    return zlib.crc32(name.encode())


def read_image(path):
    """The image at path, checked as tsectl checks it; ValueError naming what is wrong."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < HEADER_OFFSET + HEADER_BYTES:
        raise ValueError(f"{path}: {len(data)} bytes: not an image")
    magic, hv, board, version, length, crc = struct.unpack_from("<6I", data, HEADER_OFFSET)
    name = data[HEADER_OFFSET + 24:HEADER_OFFSET + 40].rstrip(b"\0").decode(errors="replace")
    if magic != MAGIC or hv != HEADER_VERSION:
        raise ValueError(f"{path}: no image header at 0x{HEADER_OFFSET:X} (tse-image stamp writes it)")
    if length != len(data):
        raise ValueError(f"{path}: its header says {length} bytes, the file has {len(data)}")
    own = zlib.crc32(data[:CRC_OFFSET] + data[CRC_OFFSET + 4:])
    if own != crc:
        raise ValueError(f"{path}: its CRC-32 is 0x{own:08x}, its header says 0x{crc:08x}: a damaged image")
    return Image(data, board, name, ((version >> 16) & 0xFF, (version >> 8) & 0xFF, version & 0xFF), length, crc)


def _version_text(v):
    return ".".join(str(x) for x in v)


def flash(ctl, path, progress=None):
    """Writes the image at path into ctl's node and starts it; returns a Flashed.  progress(done, total)
    is called after each block.  Raises ValueError for a bad file (nothing sent), Rejected for a
    refusal (nothing erased when it is the board or the size), Timeout."""
    from .can import Rejected, Timeout
    img = read_image(path)
    boot = _reach_bootloader(ctl, Rejected, Timeout)
    if boot["board"] != img.board:
        raise Rejected({"function": 0x1D, "seq": 0, "reason": _code("board"), "scissor": 0, "kin_status": 0,
                        "field": 0, "where": 0},
                       prefix=f"the image is for board {img.board_name} (0x{img.board:08x}), node {ctl.node} is board "
                              f"0x{boot['board']:08x}: nothing erased: ")
    if img.length > boot["app_size"]:
        raise Rejected({"function": 0x1D, "seq": 0, "reason": _code("length"), "scissor": 0, "kin_status": 0,
                        "field": 1, "where": 0},
                       prefix=f"the image's {img.length} bytes do not fit the area of {boot['app_size']}: ")
    t0 = time.monotonic()
    _command(ctl, Rejected, "BOOT_ERASE", timeout=max(ctl.timeout, 60.0), seq=1, length=img.length)
    erase_s = time.monotonic() - t0
    t0 = time.monotonic()
    _transfer(ctl, img, boot["block_bytes"], progress, Rejected)
    transfer_s = time.monotonic() - t0
    _command(ctl, Rejected, "BOOT_VERIFY", seq=2)
    after = _query(ctl, 3)
    if after is None or not after["valid"] or after["crc"] != img.crc or after["version"] != img.version:
        raise Rejected({"function": 0x1B, "seq": 2, "reason": _code("crc"), "scissor": 0, "kin_status": 0, "field": 0,
                        "where": 0}, prefix="the bootloader does not report the image written: ")
    _command(ctl, Rejected, "BOOT_START", seq=4)
    return Flashed(after["version"], after["crc"], erase_s, transfer_s, img.length / transfer_s)


def _command(ctl, Rejected, message, timeout=None, **values):
    saved = ctl.timeout
    if timeout is not None:
        ctl.timeout = timeout
    try:
        _mark, name, v = ctl._exchange(message, **values)
    finally:
        ctl.timeout = saved
    if name == "REJECT":
        raise Rejected(v)
    return v


def _query(ctl, seq):
    """BOOT_QUERY's three answers as a dict, None when an application refused it."""
    mark, name, v = ctl._exchange("BOOT_QUERY", seq=seq)
    if name == "REJECT":
        return None if _reason(v) == "state" else v

    def pick():
        got = {n: f for s, n, f in ctl._answers if s > mark and n in ("BOOT_ID", "BOOT_LAYOUT", "BOOT_APP")}
        return got if len(got) == 3 else None
    got = ctl._wait_for(pick, ctl.timeout, "BOOT_ID, BOOT_LAYOUT and BOOT_APP")
    i, lay, app = got["BOOT_ID"], got["BOOT_LAYOUT"], got["BOOT_APP"]
    return {"board": i["board_lo"] | i["board_hi"] << 16, "block_bytes": i["block_bytes"],
            "app_start": lay["app_start"], "app_size": lay["app_size"], "valid": app["valid"],
            "version": (app["major"], app["minor"], app["patch"]), "crc": app["crc_lo"] | app["crc_hi"] << 16}


def _reach_bootloader(ctl, Rejected, Timeout):
    got = _query(ctl, 0)
    if isinstance(got, dict) and "board" in got:
        return got
    if got is not None:  # refused for another reason than an application's state
        raise Rejected(got)
    _command(ctl, Rejected, "BOOT_ENTER", seq=0, magic=BOOT_MAGIC)
    saved = ctl.timeout
    ctl.timeout = 0.25
    try:
        for k in range(40):
            try:
                got = _query(ctl, (k + 1) & 0xFF)
                if got is not None and "board" in got:
                    return got
            except Timeout:
                pass
    finally:
        ctl.timeout = saved
    raise Timeout(f"node {ctl.node}'s bootloader did not answer within 10 s of BOOT_ENTER")


def _transfer(ctl, img, block_bytes, progress, Rejected):
    blocks = (img.length + block_bytes - 1) // block_bytes
    data = img.data + b"\xff" * 8
    seq0 = 0x40
    next_send = next_ack = retries = 0
    marks = {}
    while next_ack < blocks:
        while next_send < blocks and next_send - next_ack < WINDOW:
            off = next_send * block_bytes
            n = min(block_bytes, img.length - off)
            frames = (n + 7) // 8
            crc = zlib.crc32(img.data[off:off + n])
            marks[next_send] = ctl._mark()
            out = [_encode(ctl, "BOOT_WRITE", seq=(seq0 + next_send) & 0xFF, block=next_send, frames=frames,
                           crc_lo=crc & 0xFFFF, crc_hi=crc >> 16)]
            for k in range(frames):
                w = struct.unpack_from("<4H", data, off + 8 * k)
                out.append(_encode(ctl, "BOOT_DATA", w0=w[0], w1=w[1], w2=w[2], w3=w[3]))
            ctl._send_frames(out)
            next_send += 1
        name, v = ctl._answer(marks[next_ack], "BOOT_WRITE", (seq0 + next_ack) & 0xFF)
        if name == "ACK":
            next_ack += 1
            if progress:
                progress(next_ack, blocks)
            continue
        if _reason(v) not in ("crc", "length", "order") or retries >= RETRIES:
            raise Rejected(v, prefix=f"block {next_ack} of the image: ")
        retries += 1
        for b in range(next_ack + 1, next_send):  # the block behind it: refused order
            ctl._answer(marks[b], "BOOT_WRITE", (seq0 + b) & 0xFF)
        next_send = next_ack


def _reason(v):
    from .can import _enum
    return _enum("reason", v["reason"])


def _code(reason):
    from .can import _enum_value
    return _enum_value("reason", reason)


def _encode(ctl, message, **values):
    from .can import encode
    return encode(message, ctl.node, **values)
