#!/usr/bin/env bash
# Installs every Debian package the build, the tools and the tests need.  A second run is a
# no-op: packages already present (dpkg -s) are not asked for again, and apt-get update runs only
# when something is missing.
set -euo pipefail

packages=(
  cmake make gcc libc6-dev          # host build
  ccache                            # compiled objects kept across clones (CMakeLists.txt: TSE_CCACHE)
  libcmocka-dev                     # unit tests
  gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi   # the board build
  qemu-system-arm gdb-multiarch     # on-target tests and instruction counts (netduinoplus2)
  openocd stlink-tools              # flashing the board through an ST-Link
  dfu-util stm32flash               # flashing without a probe: USB DFU and the UART bootloader
  python3 python3-mpmath            # the independent high-precision oracle
  python3-numpy python3-scipy       # the fsolve baseline of the benchmark; tse.kin's arrays
  python3-pytest python3-setuptools # the Python tests (python/tests) and pip install ./python
  python3-pip                       # pip install --no-build-isolation ./python (README, python/tests)
  python3-matplotlib                # scripts/study.sh's plots of the design study
  python3-canmatrix python3-can     # third-party decoders that check the DBC; tse.can's bus
  qemu-system-x86 busybox-static cpio can-utils   # the vcan harness (a VM where the kernel has no CAN)
  clang libclang-rt-14-dev          # the fuzz preset (libFuzzer, AddressSanitizer, UBSan)
  cppcheck clang-tidy               # scripts/static.sh
  valgrind                          # scripts/kin_icount.sh (instruction counts on the host)
  libgsl-dev                        # bench/gsl_peer.c, the GSL Newton peer of the benchmark
  dpkg-dev patch xz-utils meson ninja-build pkg-config libglib2.0-dev libpixman-1-dev libfdt-dev
                                    # emu/build.sh: the TSE emulator (QEMU from Debian's source)
)

missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
as_root=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  as_root=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
