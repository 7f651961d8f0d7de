#!/usr/bin/env bash
# Issue 28 over vcan: images made here (random code, stamped by tse-image as the build stamps the
# board's), then flash.sh in the harness with tse-boot-sim as the board's bootloader.
# Usage: flash_test.sh PYTHON PYTHON_DIR WORKDIR TSE_IMAGE TSE_BOOT_SIM TSECTL TSE_SIM
set -u
py=$1; pydir=$2; work=$3; image=$4; shift 4
here=$(dirname "$(readlink -f "$0")")
mkdir -p "$work/images"
cd "$work/images" || exit 2
# An application of 85 KiB (the board's today): a vector table whose reset vector lies after the
# header (0x08004000 + 0x400, Thumb), the header's 48 bytes kept free (0xFF), the rest random.
"$py" - <<'PY' || exit 2
import random, struct
for name, seed, size in (("app1.bin", 1, 87040), ("app2.bin", 2, 87040)):
    r = random.Random(seed)
    b = bytearray(r.getrandbits(8) for _ in range(size))
    b[0:8] = struct.pack("<II", 0x20020000, (0x08004000 + 0x400) | 1)
    b[0x200:0x230] = b"\xff" * 48
    open(name, "wb").write(b)
PY
"$image" stamp app1.bin app1.img --board tse-sim --version 0.1.0 >/dev/null || exit 2
"$image" stamp app2.bin app2.img --board tse-sim --version 0.2.0 >/dev/null || exit 2
"$image" stamp app2.bin foreign.img --board olimex-e407 --version 0.2.0 >/dev/null || exit 2
cp app2.img damaged.img && printf '\x00' | dd of=damaged.img bs=1 seek=50000 conv=notrunc status=none
bash "$here/harness.sh" --python "$pydir" --file app1.img --file app2.img --file foreign.img --file damaged.img \
    "$here/flash.sh" "$work" "$@"
