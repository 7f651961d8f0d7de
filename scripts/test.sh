#!/usr/bin/env bash
# Sets up the machine, then builds and runs every test: the host build (with the Python suites,
# whose pytest closing lines are printed after it), the sanitizer build, the
# fuzz targets for a bounded time each (TSE_FUZZ_SECONDS, default 60; scripts/fuzz_long.sh runs
# them for hours), the static analysis (scripts/static.sh), and the board build (whose float
# kinematics must not pull in software double arithmetic, whose image must fit its flash and RAM
# budgets) with its on-target tests on QEMU's netduinoplus2, the Cortex-M3 build of the fixed-point
# kinematics with its on-target test on QEMU's mps2-an385, and the board's tests on the project's
# emulator (emu/).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)

# pytest's closing lines, from the log of a build's last ctest run (ctest shows a passing test's
# output nowhere else): the Python suites on the host, and tse.can against tse-sim in the VM.
pytest_lines() {
  awk '/^[0-9]+\/[0-9]+ Testing: / { t = $3 }
       /^(pytest .*: )?[0-9]+ (passed|failed).* in [0-9.]+s$/ { print "pytest, " t ": " $0 }' \
    "$1/Testing/Temporary/LastTest.log"
}

# The sanitizer build runs every test but the VM scenarios (label vcan): they drive, in a VM under
# TCG, the same tse-sim and tsectl code the host build's VM tests run and the sanitizer build's
# CLI contracts, simulation and fuzz tests exercise; with ASan inside TCG they took 5 minutes more.
for preset in host asan; do
  echo "=== ${preset}: configure, build, test"
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j "$jobs"
  if [ "$preset" = host ]; then
    ctest --preset "$preset" -j "$jobs"
    pytest_lines build/host
  else
    ctest --preset "$preset" -j "$jobs" -LE vcan
  fi
done

fuzz_seconds=${TSE_FUZZ_SECONDS:-60}
echo "=== fuzz: each target for ${fuzz_seconds} s from its seed corpus"
cmake --preset fuzz -DTSE_FUZZ_SECONDS="$fuzz_seconds" >/dev/null
cmake --build --preset fuzz -j "$jobs"
ctest --preset fuzz -L fuzz -j "$jobs"

echo "=== static analysis"
bash scripts/static.sh

echo "=== stm32f4: cross build, on-target tests"
cmake --preset stm32f4 >/dev/null
cmake --build --preset stm32f4 -j "$jobs"
ctest --preset stm32f4 -L target -j "$jobs"

# The fixed-point kinematics on a core without an FPU (Cortex-M3, QEMU mps2-an385): built with no
# floating-point routine in any image (checked by the build), its on-target test.
echo "=== cortex-m3: cross build, on-target tests"
cmake --preset cortex-m3 >/dev/null
cmake --build --preset cortex-m3 -j "$jobs"
ctest --preset cortex-m3 -L target -j "$jobs"

# The production image on the TSE emulator (docs/emulator.md), on the host and on the harness's
# vcan0 (tests/board_emu).  The emulator is built once and cached outside the clone (the first
# build takes a quarter of an hour); a build that fails fails the run.  Only where Debian's QEMU
# source cannot be fetched at all (emu/build.sh exits 3, saying why) do the board-emu tests skip.
echo "=== stm32f4: the image on the emulator"
emu_rc=0
emu/build.sh || emu_rc=$?
if [ "$emu_rc" -eq 3 ]; then
  echo "test.sh: QEMU's source cannot be fetched here: the board-emu tests skip (see above)"
elif [ "$emu_rc" -ne 0 ]; then
  echo "test.sh: emu/build.sh failed (exit $emu_rc)" >&2
  exit 1
fi
# Two at a time: a test on the host keeps one emulator (one core) busy; the VM tests run alone.
ctest --preset stm32f4 -L board-emu -j "$jobs"
