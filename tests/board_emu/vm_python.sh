#!/usr/bin/env bash
# The client's suite (python/tests_sim) against the production image on the emulated board,
# through the vcan harness (tests/vcan/python_can_test.sh --board).
#
#   vm_python.sh PYTHON ELF HOST_BUILD WORKDIR
#
# HOST_BUILD is the host build's directory (its host_tools and python/libtse_kin.so).  Skips (77)
# when the emulator is not built.
set -u
py=$1 elf=$2 host=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
if ! "$here/../../emu/build.sh" --path >/dev/null 2>&1 && [ -z "${TSE_EMU_QEMU:-}" ]; then
  echo "SKIP: the TSE emulator is not built for emu/ as it is: run emu/build.sh"
  exit 77
fi
t=$host/host_tools
for f in "$t/tsectl/tsectl" "$t/tse-kin" "$t/tse-rig" "$t/tse-canbridge" "$host/python/libtse_kin.so"; do
  [ -e "$f" ] || { echo "vm_python: $f not found: build the host preset first"; exit 2; }
done
HARNESS_FILES=$host/python/libtse_kin.so HARNESS_TIMEOUT=${HARNESS_TIMEOUT:-2400} \
  exec bash "$here/../vcan/python_can_test.sh" "$py" "$here/../../python" "$work" --board "$elf" \
  "$t/tsectl/tsectl" "$t/tse-kin" "$t/tse-rig" "$t/tse-canbridge"
