#!/usr/bin/env bash
# scripts/flash.sh's probe-free ways with no device (docs/board.md, "Flashing without a probe"):
# dfu-util with no DFU device listed, stm32flash with no serial port and with a port that is no
# bootloader (a pseudo-terminal), each failing within 5 s with its message; a tool that hangs
# bounded by its 10 s limit (stand-ins on PATH); and the address each writes at, read from the
# image: two tiny images linked here at 0x08000000 and 0x0800C000 (a bootloader's offset), their
# writes caught by stand-in tools, and one linked in RAM refused.
#   no_device.sh FLASH_SH
set -u
FLASH=$1
. "$(dirname "$0")/../support/check.sh"
command -v arm-none-eabi-gcc >/dev/null || { echo "no arm-none-eabi-gcc: skipped"; exit 77; }

# Two images: the vector table's first words and a loop, linked at the given address.
printf '__attribute__((section(".isr_vector"), used)) const unsigned vectors[2] = {0x20001000u, 0};\nvoid _start(void) { for (;;) {} }\n' >"$tmp/t.c"
image() { # NAME ADDRESS
  arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -nostdlib -nostartfiles -Wl,--section-start=.isr_vector="$2" \
    -Wl,-Ttext="$(printf '0x%x' $(($2 + 0x100)))" -o "$tmp/$1.elf" "$tmp/t.c" 2>"$tmp/e"
}
image at0 0x08000000 && image atC 0x0800C000 && image ram 0x20000000 || { cat "$tmp/e"; exit 1; }

# Runs flash.sh with a time limit; rc, seconds in $took, output in $tmp/e.
run() {
  local t0 t1
  t0=$(date +%s%N)
  timeout 60 bash "$FLASH" "$@" >"$tmp/e" 2>&1
  rc=$?
  t1=$(date +%s%N)
  took=$(( (t1 - t0) / 1000000 ))
}
within() { [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] && [ "$took" -lt "$1" ]; }

# The real tools, no device.  A DFU device plugged in would be written: not from a test.
if command -v dfu-util >/dev/null; then
  if timeout 10 dfu-util -l -d 0483:df11 2>/dev/null | grep -q "Found DFU: \[0483:df11\]"; then
    echo "a DFU device 0483:df11 is attached: the real dfu-util is not run against it"
  else
    run dfu-util "$tmp/atC.elf"
    check "dfu-util, no device: fails within 5 s" within 5000
    check "... naming the device and the BOOT0 procedure" \
      grep -q 'no STM32 DFU device (0483:df11) answered: set BOOT0 high' "$tmp/e"
    check "... having read the image's address" grep -q 'at 0x0800c000 through dfu-util' "$tmp/e"
  fi
fi
if command -v stm32flash >/dev/null; then
  run stm32flash "$tmp/at0.elf" "$tmp/no-such-port"
  check "stm32flash, no port: fails within 5 s" within 5000
  check "... naming the port and TSE_FLASH_PORT" grep -q "no serial port $tmp/no-such-port: .*TSE_FLASH_PORT" "$tmp/e"
  TSE_FLASH_PORT="$tmp/env-port" run stm32flash "$tmp/at0.elf"
  check "the port comes from TSE_FLASH_PORT" grep -q "no serial port $tmp/env-port" "$tmp/e"
  # A port that exists and is no bootloader: a pseudo-terminal nobody answers on.
  python3 -c 'import os, pty, sys, time
m, s = pty.openpty()
print(os.ttyname(s), flush=True)
time.sleep(30)' >"$tmp/pty" &
  holder=$!
  for _ in 1 2 3 4 5 6 7 8 9 10; do [ -s "$tmp/pty" ] && break; sleep 0.1; done
  run stm32flash "$tmp/at0.elf" "$(cat "$tmp/pty")"
  kill "$holder" 2>/dev/null
  check "stm32flash, a port with no bootloader: fails within 12 s" within 12000
  check "... saying no bootloader answered, and the BOOT0 procedure" \
    grep -q "no STM32 bootloader answered on .*: set BOOT0 high" "$tmp/e"
fi

# Stand-ins: tools that hang are cut at 10 s; tools that answer show where the image is written.
mkdir -p "$tmp/bin"
stand_in() { # NAME BODY
  printf '#!/bin/sh\n%s\n' "$2" >"$tmp/bin/$1"
  chmod +x "$tmp/bin/$1"
}
stand_in dfu-util 'sleep 60'
stand_in stm32flash 'sleep 60'
PATH="$tmp/bin:$PATH" run dfu-util "$tmp/at0.elf"
check "dfu-util hanging while listing: fails within 12 s, no device" within 12000
check "... saying no DFU device answered" grep -q "no STM32 DFU device (0483:df11) answered" "$tmp/e"
: >"$tmp/port"
PATH="$tmp/bin:$PATH" run stm32flash "$tmp/at0.elf" "$tmp/port"
check "stm32flash hanging: fails within 12 s" within 12000
check "... saying nothing answered within 10 s" grep -q "no STM32 bootloader answered on $tmp/port (nothing within 10 s)" "$tmp/e"

stand_in dfu-util "if [ \"\$1\" = -l ]; then echo 'Found DFU: [0483:df11] ver=2200, devnum=5, cfg=1, intf=0'; else echo \"\$*\" >>\"$tmp/args\"; fi"
stand_in stm32flash "echo \"\$*\" >>\"$tmp/args\""
stand_in st-flash "echo \"\$*\" >>\"$tmp/args\""
for elf in at0:0x08000000 atC:0x0800c000; do
  name=${elf%%:*}
  at=${elf#*:}
  : >"$tmp/args"
  PATH="$tmp/bin:$PATH" run dfu-util "$tmp/$name.elf"
  check "dfu-util writes $name.elf at $at and leaves" grep -q -- "-a 0 -s $at:leave -D .*/$name.bin" "$tmp/args"
  PATH="$tmp/bin:$PATH" run stm32flash "$tmp/$name.elf" "$tmp/port"
  check "stm32flash writes $name.elf at $at, verifies and starts it there" \
    grep -q -- "-w .*/$name.bin -v -S $at -g $at $tmp/port" "$tmp/args"
  PATH="$tmp/bin:$PATH" run st-flash "$tmp/$name.elf"
  check "st-flash writes $name.elf at $at" grep -q -- "write .*/$name.bin $at" "$tmp/args"
done
# The binary written begins with the vector table: 0x20001000 in its first word (little-endian).
keep=$tmp/keep.bin
stand_in dfu-util "if [ \"\$1\" = -l ]; then echo 'Found DFU: [0483:df11]'; else cp \"\$8\" \"$keep\"; fi"
PATH="$tmp/bin:$PATH" run dfu-util "$tmp/atC.elf"
check "the binary starts with the image's first word" test "$(od -An -tx1 -N4 "$keep" 2>/dev/null | tr -d ' ')" = 00100020
run dfu-util "$tmp/ram.elf"
check "an image linked in RAM is refused, naming its address" grep -q "is linked at 0x20000000, not in the STM32F4's flash" "$tmp/e"
check_done
