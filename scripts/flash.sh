#!/usr/bin/env bash
# Writes the board image (docs/board.md, "Building and flashing"):
#   flash.sh openocd IMAGE.elf           through an ST-Link, with OpenOCD
#   flash.sh st-flash IMAGE.elf          through an ST-Link, with st-flash
#   flash.sh dfu-util IMAGE.elf          no probe: the STM32's USB DFU bootloader (BOOT0 high,
#                                        device 0483:df11)
#   flash.sh stm32flash IMAGE.elf [PORT] no probe: the UART bootloader on USART1 (BOOT0 high), on
#                                        PORT, else $TSE_FLASH_PORT, else /dev/ttyUSB0
# The image is written where it is linked: the address of its first loaded byte, read from the
# ELF (a board whose bootloader keeps the start of flash links the image at an offset, such as
# 0x0800C000), and its binary is made from the same ELF.  Fails with a message naming what is
# missing when the tool, the device or its answer is: within seconds for the probe-free ways (no
# DFU device listed; no serial port, or no bootloader answering on it within 10 s), a minute for
# a probe.
set -uo pipefail
tool=${1:-}
elf=${2:-}
fail() { echo "flash: $*" >&2; exit 1; }
[ -n "$tool" ] && [ -n "$elf" ] || fail "usage: flash.sh openocd|st-flash|dfu-util|stm32flash IMAGE.elf [PORT]"
[ -f "$elf" ] || fail "no image at $elf (build it: cmake --build --preset stm32f4)"

# The address of the image's first loaded byte: the lowest load address (PhysAddr) of a LOAD
# segment that carries bytes, where objcopy -O binary starts the binary (the vector table).
image_address() {
  command -v arm-none-eabi-readelf >/dev/null || fail "arm-none-eabi-readelf is not installed (apt-get install binutils-arm-none-eabi)"
  local type off virt phys filesz rest low=
  while read -r type off virt phys filesz rest; do
    [ "$type" = LOAD ] && [[ $phys == 0x* && $filesz == 0x* ]] || continue
    (( filesz > 0 )) && { [ -z "$low" ] || (( phys < low )); } && low=$phys
  done < <(arm-none-eabi-readelf -lW "$elf" 2>/dev/null)
  [ -n "$low" ] || fail "$elf: no loadable bytes (is it an ARM ELF image?)"
  # Flash of the STM32F405/407: 1 MiB from 0x08000000.
  (( low >= 0x08000000 && low < 0x08100000 )) || fail "$elf is linked at $low, not in the STM32F4's flash (0x08000000..0x080FFFFF)"
  printf '0x%08x\n' "$((low))"
}

# The binary of exactly what the ELF loads, from its first loaded byte.
image_binary() {
  command -v arm-none-eabi-objcopy >/dev/null || fail "arm-none-eabi-objcopy is not installed (apt-get install binutils-arm-none-eabi)"
  tmp=$(mktemp -d) || fail "no temporary directory"
  trap 'rm -rf "$tmp"' EXIT
  bin=$tmp/$(basename "${elf%.elf}").bin
  arm-none-eabi-objcopy -O binary "$elf" "$bin" || fail "arm-none-eabi-objcopy could not make a binary of $elf"
}

bootloader_steps="set BOOT0 high (BOOT1/PB2 low), reset the board"
case "$tool" in
  openocd)
    command -v openocd >/dev/null || fail "openocd is not installed (apt-get install openocd)"
    log=$(timeout 60 openocd -f interface/stlink.cfg -f target/stm32f4x.cfg \
          -c "program $elf verify reset exit" 2>&1)
    rc=$?
    ;;
  st-flash)
    command -v st-flash >/dev/null || fail "st-flash is not installed (apt-get install stlink-tools)"
    addr=$(image_address) || exit 1
    image_binary
    echo "flash: $(basename "$bin") ($(stat -c %s "$bin") bytes) at $addr through st-flash"
    log=$(timeout 60 st-flash --reset write "$bin" "$addr" 2>&1)
    rc=$?
    ;;
  dfu-util)
    command -v dfu-util >/dev/null || fail "dfu-util is not installed (apt-get install dfu-util)"
    addr=$(image_address) || exit 1
    image_binary
    echo "flash: $(basename "$bin") ($(stat -c %s "$bin") bytes) at $addr through dfu-util (USB DFU, 0483:df11)"
    # dfu-util -l exits 0 whether or not a device is there: what it lists says.
    list=$(timeout 10 dfu-util -l -d 0483:df11 2>&1)
    if ! echo "$list" | grep -q "Found DFU: \[0483:df11\]"; then
      echo "$list" | tail -n 3 >&2
      fail "no STM32 DFU device (0483:df11) answered: $bootloader_steps and connect its USB (OTG FS, PA11/PA12) to this computer; as a normal user dfu-util needs a udev rule for 0483:df11 (or root) (docs/board.md, \"Flashing without a probe\")"
    fi
    log=$(timeout 120 dfu-util -d 0483:df11 -a 0 -s "$addr:leave" -D "$bin" 2>&1)
    rc=$?
    ;;
  stm32flash)
    command -v stm32flash >/dev/null || fail "stm32flash is not installed (apt-get install stm32flash)"
    port=${3:-${TSE_FLASH_PORT:-/dev/ttyUSB0}}
    addr=$(image_address) || exit 1
    image_binary
    echo "flash: $(basename "$bin") ($(stat -c %s "$bin") bytes) at $addr through stm32flash on $port (115200 8E1)"
    [ -e "$port" ] || fail "no serial port $port: connect a 3.3 V USB-serial adapter to USART1 (its RX to PA9, its TX to PA10, GND) and name its port with TSE_FLASH_PORT (docs/board.md, \"Flashing without a probe\")"
    # The bootloader answers 0x7F with ACK at once; 10 s is ample for it and bounds a silent port.
    probe=$(timeout 10 stm32flash -b 115200 "$port" 2>&1)
    prc=$?
    if [ "$prc" -ne 0 ]; then
      echo "$probe" | grep -v -e '^stm32flash ' -e 'sourceforge' -e '^$' | tail -n 3 >&2
      [ "$prc" -eq 124 ] && why="nothing within 10 s" || why="stm32flash exit $prc"
      fail "no STM32 bootloader answered on $port ($why): $bootloader_steps, and check the adapter's wiring to PA9/PA10 and that it is 3.3 V (docs/board.md, \"Flashing without a probe\")"
    fi
    log=$(timeout 120 stm32flash -b 115200 -w "$bin" -v -S "$addr" -g "$addr" "$port" 2>&1)
    rc=$?
    ;;
  *) fail "unknown tool '$tool' (openocd, st-flash, dfu-util or stm32flash)" ;;
esac
if [ "$rc" -ne 0 ]; then
  echo "$log" | tail -n 5 >&2
  if [ "$rc" -eq 124 ]; then
    fail "$tool did not finish in time"
  elif [ "$tool" = openocd ] || [ "$tool" = st-flash ]; then
    if echo "$log" | grep -Eqi "open failed|no stlink|couldn.t find|not found|unable to|no device"; then
      fail "no ST-Link probe answered: is it plugged in, powered, wired to SWDIO/SWCLK/GND/NRST, and is this user allowed to use it (udev rules, or root)?"
    fi
  fi
  fail "$tool failed (exit $rc): see its last lines above"
fi
echo "$log" | tail -n 3
echo "flash: $(basename "$elf") written and verified with $tool"
