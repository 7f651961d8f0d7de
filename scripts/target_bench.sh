#!/usr/bin/env bash
# Instruction counts of the board's hot paths on the emulated Cortex-M4F: builds the benchmark
# image (release flags, float kinematics) and runs it on QEMU's netduinoplus2 with
# -icount shift=0, where TIM2 at prescaler 0 gains exactly one count per guest instruction.
# Prints `name,instructions` lines (medians over many calls; `_max` is the worst), then '#'
# lines deriving CPU shares at 168 MHz, taking one instruction per cycle (the M4 with the ART
# accelerator runs close to that; flash wait states on a cache miss and FPU divides take more).
# The fixed-point kinematics on the emulated Cortex-M3 (cmake --preset cortex-m3) gives
# `ik_fixed_warm` and `ik_fixed_cold` the same way (bench/target_m3).
# Where the TSE emulator is built (emu/build.sh), the production image on it gives
# `control_tick_delay_max_us,N`: the longest a control interrupt began behind its timer while a
# 5 s move was blended into a running 5 s one (validate_blend above) with frames at the bus's full
# rate, and `control_tick_delay_boot_homing_max_us,N` over boot and homing
# (tests/board_emu, board_emu_control_tick_delay).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset stm32f4 >/dev/null
cmake --build --preset stm32f4 --target target-bench tse-fw >/dev/null
out=$(timeout 300 qemu-system-arm -M netduinoplus2 -display none -monitor none -serial null \
  -icount shift=0 -semihosting-config enable=on,target=native -kernel build/stm32f4/bench/target/target-bench.elf 2>&1)
echo "$out"
get() { echo "$out" | awk -F, -v k="$1" '$1 == k { print $2 }'; }
awk -v tick="$(get step_tick_6axes)" -v fast="$(get step_tick_6axes_fast)" -v slide="$(get step_tick_6axes_per_slide)" -v tmax="$(get step_tick_6axes_max)" -v seg="$(get control_segment)" \
    -v c1="$(get commit_1s)" -v c5="$(get commit_5s)" -v cb="$(get validate_blend)" -v fw="$(get frame_worst)" -v cw="$(get commit_worst)" 'BEGIN {
  f = 168e6
  printf "# stepping 6 axes at 192 kHz: step interrupt at 200 kHz x %d instructions = %.1f %% of the CPU (worst tick %d = %.2f us of jitter)\n", tick, 100 * 200e3 * tick / f, tmax, tmax / f * 1e6
  printf "# the step interrupt with its outputs: %d instructions where the six STEP (and DIR) pins share a port (one BSRR write, gen_f405), %d where they do not (a write per slide, monster8): %.2f times (goal: at most 1.5)\n", fast, slide, slide / fast
  printf "# 1 kHz control loop: %d instructions a segment = %.1f %% of the CPU\n", seg, 100 * 1e3 * seg / f
  printf "# commit to first step: a 1 s move validates in %.1f ms, a 5 s move in %.1f ms (then the next 1 ms control tick)\n", c1 / f * 1e3, c5 / f * 1e3
  printf "# a 5 s move blended into a running 5 s one validates in %.0f ms, in the main loop (the control tick runs on in its interrupt)\n", cb / f * 1e3
  printf "# the longest one frame holds the board from the bus: %d instructions = %.2f ms (goal 2 ms, 336,000); the costliest commit to its answer: %.0f ms (STATUS, telemetry, heartbeats and STOP served meanwhile; the watchdog trips at 2 s)\n", fw, fw / f * 1e3, cw / f * 1e3
}'
# The Cortex-M3 build (issue 29): the fixed-point kinematics on QEMU's mps2-an385, with -icount
# shift=6 and SysTick (bench/target_m3/bench_fixed.c calibrates the counts against 1,000 nops).
cmake --preset cortex-m3 >/dev/null
cmake --build --preset cortex-m3 --target target-bench-m3 >/dev/null
m3=$(timeout 300 qemu-system-arm -M mps2-an385 -display none -monitor none -serial null \
  -icount shift=6 -semihosting-config enable=on,target=native -kernel build/cortex-m3/bench/target_m3/target-bench-m3.elf 2>&1)
echo "$m3"
m3get() { echo "$m3" | awk -F, -v k="$1" '$1 == k { print $2 }'; }
awk -v w="$(m3get ik_fixed_warm)" -v fw="$(get ik_float_warm)" 'BEGIN {
  printf "# fixed-point warm IK on the Cortex-M3: %d instructions (goal 2,500; the M4F float build: %d); at 72 MHz and one instruction a cycle, %.1f us\n", w, fw, w / 72
}'
echo "# fk_fixed, control_segment_fixed: not measured (no fixed-point FK or controller yet: docs/kinematics.md, \"The fixed-point build\")"
# Debian's python3, which has python3-can (scripts/setup.sh), as the board-emu tests run.
py=/usr/bin/python3
[ -x "$py" ] || py=python3
if emu/build.sh --path >/dev/null 2>&1; then
  emu=$(timeout 1800 "$py" tests/board_emu/test_board_emu.py build/stm32f4/board/tse-fw.elf \
    BoardEmu.test_control_tick_delay 2>&1) || { echo "$emu" >&2; echo "target_bench: board_emu_control_tick_delay failed" >&2; exit 1; }
  line=$(echo "$emu" | grep 'figure: control_tick_delay_max_us')
  echo "control_tick_delay_max_us,$(echo "$line" | sed -n 's/.*control_tick_delay_max_us \([0-9]*\) .*/\1/p')"
  echo "control_tick_delay_boot_homing_max_us,$(echo "$line" | sed -n 's/.*over boot and homing \([0-9]*\) us.*/\1/p')"
  echo "# $(echo "$line" | sed "s/.*figure: //")"
else
  echo "# control_tick_delay_max_us: the TSE emulator is not built (emu/build.sh): not measured"
fi
