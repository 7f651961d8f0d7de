#!/usr/bin/env bash
# Issue 28 on the emulated board: the bootloader's own image (boot/stm32f4, tse-boot.elf) in sector 0
# of the emulated STM32F407 with an empty application area, driven by tsectl on the harness's
# vcan0: it answers BOOT_QUERY as its board, refuses an image for another board before erasing,
# and takes an 85 KiB image through the board's flash controller (flash_f4_device_ops): erase,
# blocks, VERIFY (its CRC read back from the emulated flash).  The image is random bytes with a
# valid header, not an application: tsectl flash --no-start leaves the board in its bootloader.
# Then the update is cut by power cycles (tse-rig cutflash at an erase and at a word program,
# tse-rig reset at a random moment) and sent again.  The figures printed are the
# emulator's wall clock, not a board's.
#
#   vm_boot.sh TSE_BOOT_ELF HOST_TOOLS WORKDIR PYTHON
#
# Skips (77) when the emulator is not built.
set -u
elf=$1 tools=$2 work=$3 py=$4
here=$(cd "$(dirname "$0")" && pwd)
if ! "$here/../../emu/build.sh" --path >/dev/null 2>&1 && [ -z "${TSE_EMU_QEMU:-}" ]; then
  echo "SKIP: the TSE emulator is not built for emu/ as it is: run emu/build.sh"
  exit 77
fi
for b in tsectl/tsectl tse-rig tse-canbridge tse-image; do
  [ -x "$tools/$b" ] || { echo "vm_boot: $tools/$b not found: build the host preset first"; exit 2; }
done
mkdir -p "$work/images"
cd "$work/images" || exit 2
"$py" - <<'PY' || exit 2
import random, struct
r = random.Random(7)
b = bytearray(r.getrandbits(8) for _ in range(87040))
b[0:8] = struct.pack("<II", 0x20020000, (0x08004000 + 0x400) | 1)
b[0x200:0x230] = b"\xff" * 48
open("app.bin", "wb").write(b)
PY
# The board's name the bootloader image is built for (TSE_BOARD, default gen_f405: boot/stm32f4).
"$tools/tse-image" stamp app.bin app.img --board gen_f405 --version 0.3.0 >/dev/null || exit 2
"$tools/tse-image" stamp app.bin foreign.img --board another-board --version 0.3.0 >/dev/null || exit 2
cat >scenario.sh <<'SH'
pass=0
fail=0
check() { if eval "$2"; then pass=$((pass + 1)); echo "ok: $1"; else fail=$((fail + 1)); echo "FAIL: $1"; fi; }
T="tsectl --iface vcan0 --node 1 --timeout 20000"
sleep 2
$T flash foreign.img >foreign.log 2>&1
check "an image for another board refused before erasing" "grep -q 'nothing erased' foreign.log"
check "the bootloader reports an empty application area at 0x08004000" "grep -q 'application area 0x08004000, 770048 bytes; no application' foreign.log"
$T flash app.img --no-start >flash.log 2>&1
rc=$?
check "tsectl flash exits 0" "[ $rc -eq 0 ]"
check "verified: 0.3.0 read back from the emulated flash" "grep -q 'verified: application 0.3.0' flash.log"

# Cut by power cycles (issue 28 pt 5): at the 2nd flash operation (the second sector's erase), at
# the 5000th (a word of the blocks), and at a moment drawn at random; each time the bootloader
# comes back with no application (the header was never written) and the update, sent again,
# completes.  The emulator's cutflash cuts as the Nth operation starts (docs/emulator.md).
cut_then_complete() {
  what=$1
  tse-rig flashops >ops.log 2>&1
  $T flash app.img --no-start >cut.log 2>&1
  rcc=$?
  sleep 3
  $T flash app.img --no-start >again.log 2>&1
  rca=$?
  check "$what: the cut update fails (exit $rcc)" "[ $rcc -ne 0 ]"
  check "$what: the bootloader answers after the power cycle, no application in its area" "grep -q '770048 bytes; no application' again.log"
  check "$what: the update sent again completes and verifies" "[ $rca -eq 0 ] && grep -q 'verified: application 0.3.0' again.log"
  tail -3 cut.log | sed "s/^/  $what, cut: /"
}
tse-rig cutflash 2 >/dev/null
cut_then_complete "power cut at the 2nd flash operation (an erase)"
tse-rig cutflash 5000 >/dev/null
cut_then_complete "power cut at the 5000th flash operation (a word)"
delay=$(( $(od -An -N1 -tu1 /dev/urandom) % 20 + 2 ))
( sleep $delay; tse-rig reset >/dev/null ) &
cut_then_complete "power cycle (tse-rig reset) ${delay} s into the update"
cat foreign.log flash.log
grep -h "^transfer\|^rate\|^erased" flash.log | sed 's/^/figure: emulated board: /'
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
SH
HARNESS_TIMEOUT=${HARNESS_TIMEOUT:-1500} bash "$here/../vcan/harness.sh" --board "$elf" --file app.img --file foreign.img \
  scenario.sh "$work/run" "$tools/tsectl/tsectl" "$tools/tse-rig" "$tools/tse-canbridge"
