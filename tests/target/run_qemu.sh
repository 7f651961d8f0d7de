#!/usr/bin/env bash
# Runs a test image on QEMU's netduinoplus2 (an STM32F405) with semihosting output and an
# instruction-counting clock, within a time limit; passes only when QEMU exits 0 and the image
# printed its closing line with no failure.
#   run_qemu.sh IMAGE.elf [SECONDS]
# TSE_QEMU_ARM, TSE_QEMU_MACHINE and TSE_QEMU_ICOUNT choose another QEMU, machine and -icount
# (tests/board_emu runs its model test on the project's emulator, tse-f407).
set -uo pipefail
elf=$1
limit=${2:-120}
qemu=${TSE_QEMU_ARM:-qemu-system-arm}
command -v "$qemu" >/dev/null || { echo "run_qemu: $qemu not found (bash scripts/setup.sh installs qemu-system-arm)" >&2; exit 2; }
out=$(mktemp)
trap 'rm -f "$out"' EXIT
timeout --kill-after=5 "$limit" "$qemu" -M "${TSE_QEMU_MACHINE:-netduinoplus2}" -display none -monitor none \
  -serial null -icount "${TSE_QEMU_ICOUNT:-shift=0}" -semihosting-config enable=on,target=native -kernel "$elf" \
  >"$out" 2>&1
rc=$?
cat "$out"
if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
  echo "run_qemu: $(basename "$elf") did not finish within ${limit} s" >&2
  exit 1
fi
if [ "$rc" -ne 0 ]; then
  echo "run_qemu: $(basename "$elf") exited $rc" >&2
  exit 1
fi
grep -Eq '(^|: )[0-9]+ passed, 0 failed$' "$out" || { echo "run_qemu: no passing closing line" >&2; exit 1; }
