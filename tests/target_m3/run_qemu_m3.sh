#!/usr/bin/env bash
# Runs a Cortex-M3 test image on QEMU's mps2-an385 (tests/target/run_qemu.sh on another machine).
#   run_qemu_m3.sh IMAGE.elf [SECONDS]
exec env TSE_QEMU_MACHINE=mps2-an385 "$(dirname "$0")/../target/run_qemu.sh" "$@"
