#!/usr/bin/env bash
# Writes the board image through an ST-Link: `flash.sh openocd IMAGE.elf` or
# `flash.sh st-flash IMAGE.elf` (the .bin beside it is written at 0x08000000).  Fails with a
# message, within a minute, when the tool or the probe is missing.
set -uo pipefail
tool=$1
elf=$2
fail() { echo "flash: $*" >&2; exit 1; }
[ -f "$elf" ] || fail "no image at $elf (build it: cmake --build --preset stm32f4)"
case "$tool" in
  openocd)
    command -v openocd >/dev/null || fail "openocd is not installed (apt-get install openocd)"
    log=$(timeout 60 openocd -f interface/stlink.cfg -f target/stm32f4x.cfg \
          -c "program $elf verify reset exit" 2>&1)
    rc=$?
    ;;
  st-flash)
    command -v st-flash >/dev/null || fail "st-flash is not installed (apt-get install stlink-tools)"
    bin=${elf%.elf}.bin
    [ -f "$bin" ] || fail "no binary at $bin"
    log=$(timeout 60 st-flash --reset write "$bin" 0x08000000 2>&1)
    rc=$?
    ;;
  *) fail "unknown tool '$tool' (openocd or st-flash)" ;;
esac
if [ "$rc" -ne 0 ]; then
  echo "$log" | tail -n 5 >&2
  if [ "$rc" -eq 124 ]; then
    fail "$tool did not finish within 60 s"
  elif echo "$log" | grep -Eqi "open failed|no stlink|couldn.t find|not found|unable to|no device"; then
    fail "no ST-Link probe answered: is it plugged in, powered, wired to SWDIO/SWCLK/GND/NRST, and is this user allowed to use it (udev rules, or root)?"
  else
    fail "$tool failed (exit $rc): see its last lines above"
  fi
fi
echo "$log" | tail -n 3
echo "flash: $(basename "$elf") written and verified with $tool"
