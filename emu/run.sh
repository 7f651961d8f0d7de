#!/usr/bin/env bash
# Runs a board image on the TSE emulator (machine tse-f407, built by emu/build.sh) in the
# foreground, with its CAN bus and its rig on two UNIX sockets it serves (docs/emulator.md).
#
# Usage: emu/run.sh --elf ELF --can SOCKET --rig SOCKET --flash FILE [--console FILE]
#                   [--bitrate BPS] [--hse-hz HZ] [--icount SPEC|off] [-- extra qemu args]
#   --elf      the image (e.g. build/stm32f4/board/tse-fw.elf), loaded into the flash
#   --can      the CAN bus: 16-byte records both ways (docs/emulator.md)
#   --rig      the rig: text requests and answers (docs/emulator.md)
#   --flash    the flash's backing file (1 MiB; created erased when missing): what the image
#              saves (the parameter log, sectors 10 and 11) is there the next time
#   --console  where the image's boot line (its board's USART) goes (default: stdout)
#   --bitrate  the bus's bit rate (default 500000): the controller hears and is heard only
#              when its own timing gives this rate
#   --hse-hz   the board's crystal (default: the image's board's, else 8000000; 0: no crystal)
#   --icount   QEMU's -icount (default shift=3,align=off,sleep=on: 8 ns an instruction, about a
#              168 MHz Cortex-M4's speed; "off": the host's clock)
# The rig is wired to the pins of the board the image is built for, read from its .tse_board
# section (emu/board_props.py; an image without one gets the generic board's), and an image linked
# behind a bootloader (monster8 at 0x0800C000) starts from its own vector table, as that
# bootloader's jump would start it.
# The emulator is the binary emu/build.sh built (TSE_EMU_QEMU overrides); it exits with the
# image's QEMU (kill it to stop: SIGTERM ends it cleanly).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
usage() { sed -n '2,19p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
die() { echo "emu/run.sh: $*" >&2; exit 2; }

elf= can= rig= flash= console= bitrate=500000 hse= icount=shift=3,align=off,sleep=on
extra=()
while [ $# -gt 0 ]; do
  case $1 in
    --elf) elf=${2:?--elf needs a file}; shift ;;
    --can) can=${2:?--can needs a socket path}; shift ;;
    --rig) rig=${2:?--rig needs a socket path}; shift ;;
    --flash) flash=${2:?--flash needs a file}; shift ;;
    --console) console=${2:?--console needs a file}; shift ;;
    --bitrate) bitrate=${2:?--bitrate needs a number}; shift ;;
    --hse-hz) hse=${2:?--hse-hz needs a number}; shift ;;
    --icount) icount=${2:?--icount needs a value}; shift ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) usage; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
  shift
done
[ -n "$elf" ] && [ -n "$can" ] && [ -n "$rig" ] && [ -n "$flash" ] || { usage >&2; die "--elf, --can, --rig and --flash are required"; }
[ -f "$elf" ] || die "no image '$elf'"
[[ $bitrate =~ ^[1-9][0-9]*$ ]] || die "--bitrate '$bitrate' is not a positive number of bit/s"
[ -z "$hse" ] || [[ $hse =~ ^[0-9]+$ ]] || die "--hse-hz '$hse' is not a number of Hz"

# The image's board: its pins for the machine, its crystal, its ENABLE level for the rig.
board_machine= board_hse=8000000 enable_low=off
props=$(python3 "$here/board_props.py" "$elf") || die "cannot read the board of '$elf'"
while IFS='=' read -r key value; do
  case $key in
    hse) board_hse=$value ;;
    machine) board_machine=$value ;;
    enable_active_low) enable_low=$value ;;
  esac
done <<<"$props"
[ -n "$hse" ] || hse=$board_hse

qemu=${TSE_EMU_QEMU:-}
if [ -z "$qemu" ]; then
  qemu=$("$here/build.sh" --path) || die "the emulator is not built: run emu/build.sh"
fi
[ -x "$qemu" ] || die "'$qemu' is not executable"

for sock in "$can" "$rig"; do
  [ -S "$sock" ] && rm -f "$sock"
  [ -e "$sock" ] && die "'$sock' exists and is not a socket"
done

args=(-M "tse-f407,can-chardev=can0,bitrate=$bitrate$board_machine" -kernel "$elf" -display none -monitor none -nodefaults
      -chardev "socket,id=can0,path=$can,server=on,wait=off"
      -chardev "socket,id=rig0,path=$rig,server=on,wait=off"
      -global tse-rig.chardev=rig0
      -global "tse-rig.enable-active-low=$enable_low"
      -global "stm32f4-rcc.hse-hz=$hse"
      -global "stm32f4-flash.file=$flash")
if [ -n "$console" ]; then
  args+=(-serial "file:$console")
else
  args+=(-serial stdio)
fi
[ "$icount" = off ] || args+=(-icount "$icount")
exec "$qemu" "${args[@]}" "${extra[@]}"
