#!/usr/bin/env bash
# The production image itself under QEMU (netduinoplus2, -icount shift=0,sleep=off: the virtual
# clock never waits for the host), without semihosting:
# it boots to its main loop although QEMU models no RCC (the clock tree's waits time out), no
# bxCAN and no flash controller, and its control tick (TIM3) and step interrupt (TIM2) fire.
# Read through QEMU's gdbstub with gdb-multiarch twice, a second apart: the counters must grow.
#   boot_check.sh tse-fw.elf
set -uo pipefail
elf=$1
qemu=${TSE_QEMU_ARM:-qemu-system-arm}
gdb=$(command -v gdb-multiarch || command -v arm-none-eabi-gdb) || { echo "boot_check: gdb-multiarch not found (bash scripts/setup.sh)" >&2; exit 2; }
port=$((20000 + RANDOM % 20000))
"$qemu" -M netduinoplus2 -display none -monitor none -serial null -icount shift=0,sleep=off \
  -kernel "$elf" -gdb "tcp:127.0.0.1:$port" &
qpid=$!
trap 'kill "$qpid" 2>/dev/null; wait "$qpid" 2>/dev/null' EXIT

read_state() {
  timeout 30 "$gdb" -batch -nx -ex "set pagination off" -ex "file $elf" -ex "target remote 127.0.0.1:$port" \
    -ex 'printf "control_calls=%u\n", tse_board.control_calls' \
    -ex 'printf "step_irqs=%u\n", tse_board.ticker.steps' \
    -ex 'printf "control_irqs=%u\n", tse_board.ticker.controls' \
    -ex 'printf "boot_faults=%u\n", tse_board.boot_faults' \
    -ex 'printf "state=%d\n", (int)tse_board.state' \
    -ex 'printf "fault=%d\n", (int)tse_board.fault' \
    -ex 'printf "pc=%#x\n", $pc' \
    -ex 'printf "where=%s\n", tse_fault_record.where ? tse_fault_record.where : "none"' \
    -ex detach 2>/dev/null | grep -E '^[a-z_]+='
}

sleep 2
first=$(read_state) || { echo "boot_check: gdb could not read the board state" >&2; exit 1; }
sleep 1
second=$(read_state) || { echo "boot_check: gdb could not read the board state the second time" >&2; exit 1; }
echo "first read:";  echo "$first" | sed 's/^/  /'
echo "second read:"; echo "$second" | sed 's/^/  /'
val() { echo "$1" | awk -F= -v k="$2" '$1 == k { print $2 }'; }

passed=0; failed=0
check() {
  if eval "$2"; then passed=$((passed + 1)); echo "[ OK ] $1"; else failed=$((failed + 1)); echo "[FAIL] $1"; fi
}
c1=$(val "$first" control_calls); c2=$(val "$second" control_calls)
s1=$(val "$first" step_irqs); s2=$(val "$second" step_irqs)
check "the control interrupt made control calls ($c1, then $c2)" '[ "${c1:-0}" -gt 100 ] && [ "${c2:-0}" -gt "$c1" ]'
check "the step interrupt fires ($s1, then $s2)" '[ "${s1:-0}" -gt 100 ] && [ "${s2:-0}" -gt "$s1" ]'
faults=$(val "$second" boot_faults)
# QEMU models no RCC: the crystal never answers, which the board must report, not hang on.
check "the clock timeout is recorded (boot faults $faults, where $(val "$second" where))" '[ $(( ${faults:-0} & 1 )) -eq 1 ]'
check "the controller holds the hardware fault (state $(val "$second" state), fault $(val "$second" fault))" \
  '[ "$(val "$second" state)" = 6 ] && [ "$(val "$second" fault)" = 10 ]'
echo "boot: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
