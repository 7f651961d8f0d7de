"""tse.flash's reading of an image (docs/protocol.md, "Updating the firmware"), with the image built
here by hand: the header at 0x200, the CRC-32 of zlib over the bytes without the crc word.  The
exchange with a bootloader runs in the vcan harness (tests/vcan/flash.sh)."""
import struct
import zlib

import pytest

from tse import flash


def image(tmp_path, board="tse-sim", version=(0, 2, 0), size=4096, spoil=None):
    b = bytearray((i * 37 + 11) & 0xFF for i in range(size))
    b[0x200:0x230] = b"\0" * 48
    struct.pack_into("<5I", b, 0x200, 0x49455354, 1, zlib.crc32(board.encode()),
                     version[0] << 16 | version[1] << 8 | version[2], size)
    b[0x218:0x218 + len(board)] = board.encode()
    struct.pack_into("<I", b, 0x214, zlib.crc32(bytes(b[:0x214] + b[0x218:])))
    if spoil is not None:
        b[spoil] ^= 1
    p = tmp_path / "app.img"
    p.write_bytes(bytes(b))
    return p


def test_board_identity_is_the_crc32_of_its_name():
    assert flash.board_id("abc") == 0x352441C2


def test_a_whole_image_is_read(tmp_path):
    img = flash.read_image(image(tmp_path))
    assert img.version == (0, 2, 0) and img.length == 4096 and img.board_name == "tse-sim"
    assert img.board == zlib.crc32(b"tse-sim")


@pytest.mark.parametrize("spoil,words", [(0x200, "no image header"), (0x210, "header says"),
                                         (0x1000 - 1, "damaged image"), (0x214, "damaged image")])
def test_a_bad_image_is_named(tmp_path, spoil, words):
    with pytest.raises(ValueError, match=words):
        flash.read_image(image(tmp_path, spoil=spoil))


def test_too_short_to_be_an_image(tmp_path):
    p = tmp_path / "x.img"
    p.write_bytes(b"\xff" * 100)
    with pytest.raises(ValueError, match="not an image"):
        flash.read_image(p)
