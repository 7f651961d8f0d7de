#!/usr/bin/env bash
# Runs a scenario on a CAN bus: on vcan0 directly where this kernel has vcan, otherwise inside a
# stock Debian kernel booted under QEMU (this machine's kernel has no CAN; see system.md).
#
#   harness.sh SCENARIO WORKDIR BINARY...
#
# SCENARIO is a shell script run with vcan0 up, the BINARIES on its PATH and can-utils beside
# them; it prints what it checks and ends with 'N passed, M failed'.  Its output comes back on
# stdout; the exit status is the scenario's.
set -u
scenario=$1
work=$2
shift 2
mkdir -p "$work"
work=$(readlink -f "$work")

if [ "$(id -u)" -eq 0 ] && ip link add dev vcan0 type vcan 2>/dev/null; then
  ip link set vcan0 up
  echo "harness: vcan0 on this kernel"
  export PATH="$(dirname "$(readlink -f "$1")"):$PATH"
  for b in "$@"; do export PATH="$(dirname "$(readlink -f "$b")"):$PATH"; done
  sh "$scenario"
  rc=$?
  ip link del vcan0
  exit $rc
fi

echo "harness: no vcan on this kernel; booting a Debian kernel under QEMU (TCG)"
# The kernel: the version Debian's linux-image-amd64 depends on, unpacked once into $work.
resolve() { apt-cache depends linux-image-amd64 2>/dev/null | awk '/Depends: linux-image-[0-9]/{print $2; exit}'; }
kpkg=$(resolve)
if [ -z "$kpkg" ] && [ "$(id -u)" -eq 0 ]; then
  apt-get update -qq >/dev/null 2>&1 # package lists never fetched on this machine
  kpkg=$(resolve)
fi
if [ -z "$kpkg" ]; then echo "harness: cannot resolve linux-image-amd64 (run scripts/setup.sh as root)"; exit 1; fi
kdir="$work/$kpkg"
if [ ! -d "$kdir" ]; then
  (cd "$work" && apt-get download "$kpkg" >/dev/null 2>&1) ||
    { [ "$(id -u)" -eq 0 ] && apt-get update -qq && (cd "$work" && apt-get download "$kpkg" >/dev/null); } ||
    { echo "harness: cannot download $kpkg"; exit 1; }
  dpkg-deb -x "$work/${kpkg}"_*.deb "$kdir.tmp" && mv "$kdir.tmp" "$kdir" && rm -f "$work/${kpkg}"_*.deb
fi
vmlinuz=$(ls "$kdir"/boot/vmlinuz-* | head -1)
mods=$(ls -d "$kdir"/lib/modules/*/kernel)

# The initramfs: busybox, the four CAN modules, the binaries with their shared libraries.
root="$work/root"
rm -rf "$root"
mkdir -p "$root"/{bin,proc,sys,dev,tmp,mods}
cp /bin/busybox "$root/bin/"
for a in sh mount insmod ip sleep cat echo poweroff ls grep kill pidof head tail wc sed awk date seq cut; do
  ln -sf busybox "$root/bin/$a"
done
cp "$mods/net/can/can.ko" "$mods/net/can/can-raw.ko" "$mods/drivers/net/can/dev/can-dev.ko" \
   "$mods/drivers/net/can/vcan.ko" "$root/mods/"
for b in "$@" /usr/bin/cansend /usr/bin/candump; do
  cp "$b" "$root/bin/"
  for lib in $(ldd "$b" | awk '/=>/{print $3} /^\t\/lib/{print $1}'); do
    mkdir -p "$root$(dirname "$lib")"
    cp -L "$lib" "$root$lib"
  done
done
cp "$scenario" "$root/scenario.sh"
cat >"$root/init" <<'INIT'
#!/bin/sh
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
for m in can can-dev can-raw vcan; do insmod /mods/$m.ko; done
ip link add dev vcan0 type vcan && ip link set vcan0 up
echo "=== scenario begin"
echo "figure: VM boot, kernel start to scenario: $(cut -d' ' -f1 /proc/uptime) s"
cd /tmp && sh /scenario.sh
echo "=== scenario end $?"
poweroff -f
INIT
chmod +x "$root/init"
(cd "$root" && find . | cpio -o -H newc 2>/dev/null | gzip >"$work/initrd.gz")

t0=$(date +%s.%N)
if [ -n "${HARNESS_LIVE:-}" ]; then
  # Live: the scenario's output as it happens (progress bars included).
  timeout 600 qemu-system-x86_64 -accel tcg -m 512 -nographic -no-reboot -kernel "$vmlinuz" \
    -initrd "$work/initrd.gz" -append "console=ttyS0 quiet panic=-1" 2>&1 | tee "$work/console.log" |
    sed -u -n '/=== scenario begin/,/=== scenario end/{/=== scenario/d;p}'
else
  timeout 600 qemu-system-x86_64 -accel tcg -m 512 -nographic -no-reboot -kernel "$vmlinuz" \
    -initrd "$work/initrd.gz" -append "console=ttyS0 quiet panic=-1" >"$work/console.log" 2>&1
fi
t1=$(date +%s.%N)
[ -n "${HARNESS_LIVE:-}" ] || sed -n '/=== scenario begin/,/=== scenario end/p' "$work/console.log" | sed '1d;$d' | tr -d '\r'
rc=$(sed -n 's/.*=== scenario end \([0-9]*\).*/\1/p' "$work/console.log" | tr -d '\r')
echo "harness: VM boot to power-off $(echo "$t1 - $t0" | bc 2>/dev/null || awk "BEGIN{print $t1 - $t0}") s"
[ -n "$rc" ] || { echo "harness: the VM did not finish the scenario"; tail -20 "$work/console.log"; exit 1; }
exit "$rc"
