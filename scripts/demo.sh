#!/usr/bin/env bash
# The main job: set up, build the simulator and tsectl, and drive the simulated controller over
# CAN through homing, moves and a streamed trajectory with progress shown: on vcan0 where this
# kernel has it, otherwise inside a Debian kernel booted under QEMU (about a minute).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cmake --preset host >/dev/null
cmake --build --preset host --target tse-sim tsectl -j "$(nproc 2>/dev/null || echo 2)" >/dev/null
HARNESS_LIVE=1 bash tests/vcan/harness.sh scripts/demo_scenario.sh build/host/vm-demo \
  build/host/host_tools/tse-sim build/host/host_tools/tsectl/tsectl
