#!/usr/bin/env bash
# The model test image (models_test.c) on the project's emulator, through tests/target's runner;
# skips (77) when the emulator is not built.
#   run_models.sh IMAGE.elf [SECONDS]
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
qemu=${TSE_EMU_QEMU:-$("$here/../../emu/build.sh" --path 2>/dev/null)} || true
if [ -z "$qemu" ]; then
  echo "SKIP: the TSE emulator is not built for emu/ as it is: run emu/build.sh (or cmake --build --preset stm32f4 --target emu)"
  exit 77
fi
TSE_QEMU_ARM=$qemu TSE_QEMU_MACHINE=tse-f407 TSE_QEMU_ICOUNT=shift=3 exec "$here/../target/run_qemu.sh" "$@"
