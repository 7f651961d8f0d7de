#!/usr/bin/env bash
# The search for the costliest MOVE_COMMIT frames on the emulated Cortex-M4F (bench/target/frame_search.c;
# docs/validation.md, "What one frame costs"): builds its image (release flags, float) and runs it on
# QEMU's netduinoplus2 with -icount shift=0, where TIM2 at prescaler 0 gains one count per guest
# instruction.  Prints the costliest frames found as initializers for bench/target/frame_cases.c, whose
# worst `scripts/target_bench.sh` reports as frame_worst.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset stm32f4 >/dev/null
cmake --build --preset stm32f4 --target frame-search >/dev/null
timeout 3600 qemu-system-arm -M netduinoplus2 -display none -monitor none -serial null \
  -icount shift=0 -semihosting-config enable=on,target=native -kernel build/stm32f4/bench/target/frame-search.elf
