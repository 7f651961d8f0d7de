#!/usr/bin/env bash
# Runs a scenario on a CAN bus: on vcan0 directly where this kernel has vcan (as root), otherwise
# inside a stock Debian kernel booted under QEMU (this machine's kernel has no CAN; see
# docs/harness.md).
#
#   harness.sh [--file PATH]... [--python DIR]... SCENARIO WORKDIR [BINARY...]
#
# SCENARIO is a shell script (run by busybox sh on both paths) with vcan0 up, the BINARIES on its
# PATH and can-utils (cansend, candump) beside them; it prints what it checks and ends with
# 'N passed, M failed'.  Its output comes back on stdout; the exit status is the scenario's.
# WORKDIR holds what the harness builds or keeps (the kernel, the initramfs, the console log).
#
# The board: with --board ELF (and HARNESS_BOARD_ARGS, words passed to emu/run.sh after its own,
# such as "--bitrate 250000" or "-- -global tse-rig.initial-m=0.3"), the scenario's controller is
# that image on the emulated STM32F407 (emu/, docs/emulator.md) instead of a tse-sim it starts:
# the emulator runs on this host (emu/run.sh, the binary emu/build.sh built; a fresh flash file
# each run; its USART console in WORKDIR/board/console.log), and its CAN channel reaches vcan0
# through tse-canbridge (here, or in the VM over a virtio-serial port).  The scenario's
# environment has TSE_TARGET=board and TSE_RIG, the rig channel tse-rig uses (in the VM, the
# virtio port that leads to it); without --board TSE_TARGET=sim.  tse-canbridge and tse-rig must
# be among the BINARYs.  No emulator built, or no tse-canbridge or tse-rig, is an error naming it
# (exit 2) before anything is set up.
#
# Data files: each --file PATH, and each path in HARNESS_FILES (separated by spaces), is copied
# into the scenario's working directory under its own name, so the scenario opens it as
# ./NAME.  That directory is /tmp in the VM and a fresh WORKDIR/run on vcan0, so a scenario is
# written once for both.  A missing file, two files with the same name, a missing scenario or
# binary, or a bad HARNESS_TIMEOUT is an error naming it (exit 2) before anything is set up.
#
# Python: with --python DIR (repeatable), and each directory in HARNESS_PYTHON, the scenario can
# run 'python3': Debian's /usr/bin/python3 (3.11), with python3-can and python3-pytest and the
# python3-* packages they depend on importable ('python3 -m pytest -q -p no:cacheprovider ...').
# Its environment has PYTHONPATH holding each DIR (HARNESS_PYTHON's first, then --python's, in
# order), PYTHONDONTWRITEBYTECODE=1 (nothing is written into the trees, pytest's assertion
# rewriting included), PYTHONNOUSERSITE=1 and PY_COLORS=0 (the VM's console is a terminal, where
# pytest would colour).
# In the VM each DIR is copied to /py/NAME (NAME its last component), its PYTHONPATH entry; on
# vcan0 the entry is the DIR itself (absolute), and WORKDIR/python-bin, holding only the link
# python3 -> /usr/bin/python3, comes first on PATH.  The VM gets, in an uncompressed archive of its
# own: the interpreter and the shared libraries it and its extension modules need (ldd), its
# standard library less what a test never needs (test, idlelib, tkinter, turtle, turtledemo,
# lib2to3, ensurepip, pydoc_data, distutils, config-*, CPython's own test extensions, nis) with
# Debian's compiled .pyc and their sources' mtimes (nothing is compiled under TCG), and the files
# dpkg lists in /usr/lib/python3/dist-packages for those packages.  There HOME is /, no locale is
# set (python3 takes its UTF-8 mode: text is UTF-8), the clock is the host's, in UTC, and /tmp (in
# RAM) is the working directory.  Both paths print "figure: [VM ]python3 -c 'import can, pytest':
# S s" before the scenario.  A missing DIR, one that is not a directory, one with a ':' in its
# path, or two with one NAME is an error naming it (exit 2) before anything is set up; without
# python3-can or python3-pytest installed the harness exits 1.  Without --python the initramfs is
# what it was.
#
# Environment:
#   HARNESS_FILES="a.csv p.txt"  data files, as --file (use --file for a path with a space)
#   HARNESS_PYTHON="dir1 dir2"   Python trees, as --python (use --python for a path with a space)
#   HARNESS_PY_PACKAGES="python3-numpy"  Debian python3-* packages the Python of --python gets
#                                besides python3-can and python3-pytest (each with its own
#                                python3-* dependencies and shared libraries), installed here
#   HARNESS_LIVE=1               show the scenario's output as it happens (VM path: progress bars
#                                included) instead of all at once when the VM has powered off
#   HARNESS_TIMEOUT=SECONDS      the scenario's time limit (default 480).  A scenario still
#                                running then is killed, with everything it started, and the
#                                harness prints "harness: the scenario timed out after S s; it was
#                                running: COMMAND (scenario line N)" and exits 124.  The VM's own
#                                limit is 120 s above it.
#
# Where a hang was: the scenario runs under 'sh -x' with its trace on file descriptor 9 (busybox
# sh's BASH_XTRACEFD), so its stdout and stderr are untouched; the trace is read only after a
# time-out.  A scenario must leave fd 9 alone.  The command shown is the latest the scenario's own
# flow reached; a background loop of the scenario still running at the time-out can show instead.
# On vcan0 the whole trace is kept in WORKDIR/scenario.trace, and the run directory in WORKDIR/run.
set -u

usage() {
  cat <<'EOF'
usage: harness.sh [--file PATH]... [--python DIR]... [--board ELF] SCENARIO WORKDIR [BINARY...]
Runs SCENARIO on vcan0 (here, or in a QEMU VM when this kernel has no CAN) with the BINARIES on its
PATH; each --file PATH (and each path in HARNESS_FILES) is copied into its working directory.
With --python DIR (and HARNESS_PYTHON) the scenario can run python3 (Debian's, with python-can and
pytest) with each DIR on PYTHONPATH (in the VM: /py/NAME of DIR).
With --board ELF the controller is that image on the emulated board (TSE_TARGET=board, TSE_RIG).
Environment: HARNESS_FILES, HARNESS_PYTHON, HARNESS_PY_PACKAGES, HARNESS_LIVE=1,
HARNESS_TIMEOUT=SECONDS (default 480);
see the header of this script.
EOF
}
die() { echo "harness: $*" >&2; exit 2; }

# --- Arguments, all checked before anything is set up.
files=()
read -r -d '' -a env_files <<<"${HARNESS_FILES:-}" # spaces, tabs or newlines between paths
files+=(${env_files[@]+"${env_files[@]}"})
board=
pydirs=()
read -r -d '' -a env_pydirs <<<"${HARNESS_PYTHON:-}"
pydirs+=(${env_pydirs[@]+"${env_pydirs[@]}"})
while [ $# -gt 0 ]; do
  case $1 in
    --file) [ $# -ge 2 ] || die "--file needs a PATH"; files+=("$2"); shift 2 ;;
    --file=*) files+=("${1#--file=}"); shift ;;
    --python) [ $# -ge 2 ] || die "--python needs a DIR"; pydirs+=("$2"); shift 2 ;;
    --python=*) pydirs+=("${1#--python=}"); shift ;;
    --board) [ $# -ge 2 ] || die "--board needs an ELF image"; board=$2; shift 2 ;;
    --board=*) board=${1#--board=}; shift ;;
    -h | --help) usage; exit 0 ;;
    --) shift; break ;;
    -*) die "unknown option '$1' (options: --file PATH, --python DIR, --board ELF, --help)" ;;
    *) break ;;
  esac
done
[ $# -ge 2 ] || { usage >&2; exit 2; }
scenario=$1
work=$2
shift 2
[ -e "$scenario" ] || die "scenario not found: $scenario"
[ -f "$scenario" ] && [ -r "$scenario" ] || die "scenario is not a readable file: $scenario"
scenario=$(readlink -f "$scenario")
for b in "$@"; do
  [ -e "$b" ] || die "binary not found: $b"
  [ -f "$b" ] && [ -x "$b" ] || die "binary is not an executable file: $b"
done
declare -A seen=()
for f in ${files[@]+"${files[@]}"}; do
  [ -n "$f" ] || die "empty data file name"
  [ -e "$f" ] || die "data file not found: $f"
  [ -f "$f" ] || die "data file is not a regular file: $f"
  [ -r "$f" ] || die "data file is not readable: $f"
  name=$(basename "$f")
  [ -z "${seen[$name]+x}" ] || die "two data files named $name: ${seen[$name]} and $f"
  seen[$name]=$f
done
declare -A pyseen=()
pypath=() # the DIRs, absolute
for d in ${pydirs[@]+"${pydirs[@]}"}; do
  [ -n "$d" ] || die "empty python directory name"
  [ -e "$d" ] || die "python directory not found: $d"
  [ -d "$d" ] || die "python directory is not a directory: $d"
  [ -r "$d" ] && [ -x "$d" ] || die "python directory is not readable: $d"
  abs=$(readlink -f "$d")
  case $abs in *:*) die "python directory has a ':' in its path (PYTHONPATH cannot hold it): $d" ;; esac
  [ "$abs" != / ] || die "python directory cannot be /: $d"
  name=$(basename "$abs")
  [ -z "${pyseen[$name]+x}" ] || die "two python directories named $name: ${pyseen[$name]} and $d"
  pyseen[$name]=$d
  pypath+=("$abs")
done
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
if [ -n "$board" ]; then
  [ -f "$board" ] && [ -r "$board" ] || die "board image not found: $board"
  board=$(readlink -f "$board")
  bridge_bin= rig_bin=
  for b in "$@"; do
    case $(basename "$b") in tse-canbridge) bridge_bin=$(readlink -f "$b") ;; tse-rig) rig_bin=$(readlink -f "$b") ;; esac
  done
  [ -n "$bridge_bin" ] || die "--board needs tse-canbridge among the BINARYs"
  [ -n "$rig_bin" ] || die "--board needs tse-rig among the BINARYs"
  emu_dir=${TSE_EMU_DIR:-$here/../../emu} # another tree's emu/ (its run.sh and build.sh), for trying one
  emu_qemu=${TSE_EMU_QEMU:-$("$emu_dir/build.sh" --path 2>/dev/null)} ||
    die "the board emulator is not built for emu/ as it is: run emu/build.sh (about 20 minutes, once)"
  [ -x "$emu_qemu" ] || die "the board emulator $emu_qemu is not executable"
  read -r -a board_args <<<"${HARNESS_BOARD_ARGS:-}"
fi
limit=${HARNESS_TIMEOUT:-480}
# The VM's speed measure (the init script's): iterations of an awk loop, and the seconds they take
# in the VM on the reference machine (2 cores, nothing else running), measured there.
speed_work=80000
speed_ref_s=0.95
case $limit in
  '' | *[!0-9]*) die "HARNESS_TIMEOUT must be a whole number of seconds, not '$limit'" ;;
esac
[ ${#limit} -le 6 ] && [ $((10#$limit)) -ge 1 ] ||
  die "HARNESS_TIMEOUT must be between 1 and 999999 seconds, not '$limit'"
limit=$((10#$limit))
if [ ${#pypath[@]} -gt 0 ]; then
  [ -x /usr/bin/python3 ] || { echo "harness: /usr/bin/python3 not found (run scripts/setup.sh as root)"; exit 1; }
  for p in python3-can python3-pytest ${HARNESS_PY_PACKAGES-}; do
    case $p in python3-*) ;; *) die "HARNESS_PY_PACKAGES names Debian python3-* packages, not '$p'" ;; esac
    [ "$(dpkg-query -W -f='${db:Status-Abbrev}' "$p" 2>/dev/null)" = "ii " ] ||
      { echo "harness: $p is not installed (run scripts/setup.sh as root)"; exit 1; }
  done
fi

mkdir -p "$work" || die "cannot create the work directory $work"
work=$(readlink -f "$work")

# The trace: one line per command, '+SEQ LINE: COMMAND'.  SEQ counts the commands each shell
# process traces; a subshell (background job, command substitution, pipeline) continues from its
# parent's count at the fork, so the highest SEQ is where the scenario's flow got to, whatever
# order concurrent processes wrote their lines in.  Equal SEQ: the higher scenario line (a
# background job traces its command with the count its parent gives the next one).
PS4_TRACE='+$((_harness_seq+=1)) $LINENO: '
last_command() {
  awk 'match($0, /^\+[0-9]+ [0-9]+: /) {
         split(substr($0, 2, RLENGTH - 3), f, " "); seq = f[1] + 0; line = f[2] + 0
         if (seq > bs || (seq == bs && line >= bl)) { bs = seq; bl = line; bc = substr($0, RLENGTH + 1) }
       }
       END { if (bs) printf "%s (scenario line %d)\n", bc, bl }' "$1"
}
report_timeout() {
  local where
  where=$(last_command "$1")
  if [ -n "$where" ]; then
    echo "harness: the scenario timed out after $limit s; it was running: $where"
  else
    echo "harness: the scenario timed out after $limit s (it traced no command)"
  fi
}

# --- The emulated board, on this host either way: its two channels are UNIX sockets in
# WORKDIR/board, which tse-canbridge and tse-rig reach here or through the VM's virtio ports.
board_pid=
board_stop() {
  [ -z "$board_pid" ] || { kill -TERM -- "-$board_pid" 2>/dev/null; sleep 0.2; kill -KILL -- "-$board_pid" 2>/dev/null; }
  board_pid=
}
board_start() {
  local d="$work/board"
  rm -rf "$d"
  mkdir -p "$d"
  TSE_EMU_QEMU=$emu_qemu setsid "$emu_dir/run.sh" --elf "$board" --can "$d/can.sock" --rig "$d/rig.sock" \
    --flash "$d/flash.bin" --console "$d/console.log" ${board_args[@]+"${board_args[@]}"} \
    </dev/null >"$d/emulator.log" 2>&1 &
  board_pid=$!
  for _ in $(seq 1 300); do # up to 30 s for both sockets
    [ -S "$d/can.sock" ] && [ -S "$d/rig.sock" ] && break
    kill -0 "$board_pid" 2>/dev/null || break
    sleep 0.1
  done
  if ! [ -S "$d/can.sock" ] || ! [ -S "$d/rig.sock" ]; then
    echo "harness: the board emulator did not start:"
    tail -20 "$d/emulator.log"
    board_stop
    exit 1
  fi
  echo "harness: board $(basename "$board") on the emulator ($emu_qemu)"
}

# --- vcan0 on this kernel.
if [ "$(id -u)" -eq 0 ] && ip link add dev vcan0 type vcan 2>/dev/null; then
  ip link set vcan0 up
  echo "harness: vcan0 on this kernel"
  export TSE_TARGET=sim
  bridge_pid=
  if [ -n "$board" ]; then
    board_start
    "$bridge_bin" --channel "$work/board/can.sock" --iface vcan0 2>"$work/board/bridge.log" &
    bridge_pid=$!
    export TSE_TARGET=board TSE_RIG="$work/board/rig.sock"
  fi
  for b in "$@"; do PATH="$(dirname "$(readlink -f "$b")"):$PATH"; done
  if [ ${#pypath[@]} -gt 0 ]; then # Debian's python3 first on PATH, the DIRs themselves on PYTHONPATH
    mkdir -p "$work/python-bin"
    ln -sfn /usr/bin/python3 "$work/python-bin/python3"
    PATH="$work/python-bin:$PATH"
    PYTHONPATH=$(IFS=:; echo "${pypath[*]}")
    export PYTHONPATH PYTHONDONTWRITEBYTECODE=1 PYTHONNOUSERSITE=1 PY_COLORS=0
    unset PYTHONHOME
    t0=$(date +%s.%N)
    if "$work/python-bin/python3" -c 'import can, pytest'; then
      t1=$(date +%s.%N)
      echo "figure: python3 -c 'import can, pytest': $(awk "BEGIN{printf \"%.2f\", $t1 - $t0}") s"
    else
      echo "harness: python3 cannot import can and pytest"
    fi
  fi
  export PATH
  run="$work/run"
  trace="$work/scenario.trace"
  flag="$work/timed-out"
  rm -rf "$run" "$flag"
  mkdir -p "$run"
  for f in ${files[@]+"${files[@]}"}; do cp "$f" "$run/"; done
  # busybox sh, as in the VM; without it the scenario runs untraced under sh.
  if command -v busybox >/dev/null 2>&1; then shell=(busybox sh -x); else shell=(sh); fi
  spid=
  wpid=
  stop() {
    [ -z "$wpid" ] || kill -KILL -- "-$wpid" 2>/dev/null
    [ -z "$spid" ] || kill -KILL -- "-$spid" 2>/dev/null
    [ -z "$bridge_pid" ] || kill -TERM "$bridge_pid" 2>/dev/null
    board_stop
    ip link del vcan0 2>/dev/null
  }
  trap 'stop; exit 130' INT
  trap 'stop; exit 143' TERM HUP
  # The scenario and the watchdog each lead a process group of their own, so that either can be
  # ended with everything it started.  stdin stays the harness's (fd 3 around the '&').
  exec 3<&0
  (cd "$run" && exec env BASH_XTRACEFD=9 PS4="$PS4_TRACE" setsid "${shell[@]}" "$scenario" 9>"$trace" <&3 3<&-) &
  spid=$!
  setsid bash -c 'sleep "$1" && : >"$2" && kill -TERM -- "-$3"; sleep 2; kill -KILL -- "-$3"' \
    watchdog "$limit" "$flag" "$spid" </dev/null >/dev/null 2>&1 &
  wpid=$!
  disown "$wpid" # ended below without a job notice
  exec 3<&-
  wait "$spid"
  rc=$?
  kill -KILL -- "-$wpid" 2>/dev/null
  wpid=
  timed_out=
  if [ -e "$flag" ]; then
    kill -KILL -- "-$spid" 2>/dev/null
    timed_out=1
    rc=124
  else
    kill -TERM -- "-$spid" 2>/dev/null # whatever the scenario left running
  fi
  for _ in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do # up to 2 s for it to end
    kill -0 -- "-$spid" 2>/dev/null || break
    sleep 0.1
  done
  kill -KILL -- "-$spid" 2>/dev/null
  spid=
  [ -z "$bridge_pid" ] || { kill -TERM "$bridge_pid" 2>/dev/null; wait "$bridge_pid" 2>/dev/null; }
  board_stop
  ip link del vcan0
  trap - INT TERM HUP
  [ -z "$timed_out" ] || report_timeout "$trace"
  exit $rc
fi

echo "harness: no vcan on this kernel; booting a Debian kernel under QEMU (TCG)"
for tool in busybox cpio qemu-system-x86_64; do
  command -v "$tool" >/dev/null 2>&1 || { echo "harness: $tool not found (run scripts/setup.sh as root)"; exit 1; }
done
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

# The initramfs: busybox, the four CAN modules, the binaries with their shared libraries, the data
# files in /tmp (the scenario's working directory).
root="$work/root"
rm -rf "$root" "$work/pyroot" "$work/initrd-python.img" # the last two: a run with --python
mkdir -p "$root"/{bin,proc,sys,dev,tmp,mods}
cp "$(command -v busybox)" "$root/bin/busybox"
for a in sh mount insmod ip sleep cat echo poweroff ls grep kill pidof head tail wc sed awk date seq cut basename dirname \
         setsid; do
  ln -sf busybox "$root/bin/$a"
done
cp "$mods/net/can/can.ko" "$mods/net/can/can-raw.ko" "$mods/drivers/net/can/dev/can-dev.ko" \
   "$mods/drivers/net/can/vcan.ko" "$root/mods/"
if [ -n "$board" ]; then # the virtio-serial ports that lead to the board's channels
  for m in virtio/virtio virtio/virtio_ring virtio/virtio_pci_legacy_dev virtio/virtio_pci_modern_dev \
           virtio/virtio_pci char/virtio_console; do
    cp "$mods/drivers/$m.ko" "$root/mods/"
  done
fi
for b in "$@" /usr/bin/cansend /usr/bin/candump; do
  cp "$b" "$root/bin/"
  for lib in $(ldd "$b" | awk '/=>/{print $3} /^\t\/lib/{print $1}'); do
    mkdir -p "$root$(dirname "$lib")"
    cp -L "$lib" "$root$lib"
  done
done
for f in ${files[@]+"${files[@]}"}; do cp "$f" "$root/tmp/"; done
if [ ${#pypath[@]} -gt 0 ]; then
  # Python (only with --python), in an archive of its own ahead of the gzipped one: Debian's
  # interpreter; its standard library less what a test never needs; the files dpkg lists in
  # /usr/lib/python3/dist-packages for python3-can, python3-pytest and, recursively, each installed
  # python3-* package their Depends name (an alternative not installed is one the interpreter
  # satisfies); Debian's compiled .pyc beside each source.  cpio keeps the mtimes (in the archive
  # too, and the kernel sets them), so the .pyc stay valid and nothing is compiled under TCG.
  t_py=$(date +%s.%N)
  pyroot="$work/pyroot"
  rm -rf "$pyroot"
  mkdir -p "$pyroot"
  py_real=$(readlink -f /usr/bin/python3) # /usr/bin/python3.11
  py_name=$(basename "$py_real")
  py_tag=cpython-$(echo "${py_name#python}" | tr -d .) # the .pyc tag, cpython-311
  py_lib=usr/lib/$py_name
  declare -A py_got=()
  # shellcheck disable=SC2206 # a list of package names
  py_todo=(python3-can python3-pytest ${HARNESS_PY_PACKAGES-})
  while [ ${#py_todo[@]} -gt 0 ]; do
    p=${py_todo[0]}
    py_todo=("${py_todo[@]:1}")
    [ -z "${py_got[$p]+x}" ] || continue
    py_got[$p]=1
    for d in $(dpkg-query -W -f='${Depends}' "$p" | tr ',|' '\n\n' |
               awk '$1 ~ /^python3-/ {sub(/:.*/, "", $1); print $1}'); do
      [ "$(dpkg-query -W -f='${db:Status-Abbrev}' "$d" 2>/dev/null)" != "ii " ] || py_todo+=("$d")
    done
  done
  {
    (cd / && find "$py_lib" \( -path "$py_lib/test" -o -path "$py_lib/idlelib" \
        -o -path "$py_lib/tkinter" -o -path "$py_lib/turtledemo" -o -path "$py_lib/lib2to3" \
        -o -path "$py_lib/ensurepip" -o -path "$py_lib/pydoc_data" -o -path "$py_lib/distutils" \
        -o -path "$py_lib/config-*" -o -path "$py_lib/dist-packages" -o -path "$py_lib/site-packages" \) \
        -prune \
      -o \( -name 'turtle.*' -o -path "$py_lib/sitecustomize.py" -o -path "$py_lib/lib-dynload/_tkinter.*" \
        -o -path "$py_lib/lib-dynload/_test*" -o -path "$py_lib/lib-dynload/_ctypes_test.*" \
        -o -path "$py_lib/lib-dynload/_xxtestfuzz.*" -o -path "$py_lib/lib-dynload/xxlimited*" \
        -o -path "$py_lib/lib-dynload/nis.*" \) \
      -o \( -type f -o -type l \) -print)
    dpkg -L "${!py_got[@]}" | while read -r f; do
      case $f in /usr/lib/python3/dist-packages/*) ;; *) continue ;; esac
      [ -f "$f" ] || [ -L "$f" ] || continue
      echo "${f#/}"
      case $f in
        *.py) pyc="${f%/*}/__pycache__/${f##*/}" && pyc="${pyc%.py}.$py_tag.pyc"
              [ ! -f "$pyc" ] || echo "${pyc#/}" ;;
      esac
    done
  } | (cd / && cpio -pdm --quiet "$pyroot")
  mkdir -p "$pyroot/usr/bin"
  cp -p "$py_real" "$pyroot/usr/bin/$py_name"
  ln -s "$py_name" "$pyroot/usr/bin/python3"
  mkdir -p "$pyroot/py"
  vm_pypath=
  for d in "${pypath[@]}"; do
    cp -a "$d" "$pyroot/py/"
    vm_pypath=$vm_pypath${vm_pypath:+:}/py/$(basename "$d")
  done
  # The shared libraries of the interpreter and of every extension module (the trees' too), but
  # those of the binaries, which are in the other archive.
  for lib in $(ldd "$py_real" $(find "$pyroot" -name '*.so' -type f) 2>/dev/null |
                 awk '/=>/{print $3} /^\t\/lib/{print $1}' | sort -u); do
    [ -e "$root$lib" ] || [ -e "$pyroot$lib" ] && continue
    mkdir -p "$pyroot$(dirname "$lib")"
    cp -L "$lib" "$pyroot$lib"
  done
  quote() { printf "'%s'" "$(printf %s "$1" | sed "s/'/'\\\\''/g")"; }
  printf 'export PYTHONPATH=%s PYTHONDONTWRITEBYTECODE=1 PYTHONNOUSERSITE=1 PY_COLORS=0\n' \
    "$(quote "$vm_pypath")" >"$pyroot/python.conf"
  py_pkgs=$(printf '%s\n' "${!py_got[@]}" | sort | tr '\n' ' ')
  echo "figure: Python for the VM: ${#py_got[@]} packages (${py_pkgs% }), $(du -sm "$pyroot" | cut -f1) MB," \
    "staged in $(awk "BEGIN{printf \"%.1f\", $(date +%s.%N) - $t_py}") s"
fi
cp "$scenario" "$root/scenario.sh"
printf 'limit=%d\n' "$limit" >"$root/harness.conf"
printf 'board=%s\n' "${board:+1}" >>"$root/harness.conf"
printf "trace_ps4='%s'\n" "$PS4_TRACE" >>"$root/harness.conf"
cat >"$root/init" <<'INIT'
#!/bin/sh
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
for m in can can-dev can-raw vcan; do insmod /mods/$m.ko; done
ip link add dev vcan0 type vcan && ip link set vcan0 up
. /harness.conf
export TSE_TARGET=sim
if [ -n "$board" ]; then
  # The board's channels: virtio-serial ports named tse.can and tse.rig.
  for m in virtio_ring virtio virtio_pci_legacy_dev virtio_pci_modern_dev virtio_pci virtio_console; do
    insmod /mods/$m.ko
  done
  can_port= rig_port=
  for _ in $(seq 1 50); do
    for n in /sys/class/virtio-ports/*/name; do
      [ -e "$n" ] || continue
      case $(cat "$n") in
        tse.can) can_port=/dev/$(basename "$(dirname "$n")") ;;
        tse.rig) rig_port=/dev/$(basename "$(dirname "$n")") ;;
      esac
    done
    [ -n "$can_port" ] && [ -n "$rig_port" ] && [ -e "$can_port" ] && [ -e "$rig_port" ] && break
    sleep 0.1
  done
  if [ -z "$can_port" ] || [ -z "$rig_port" ]; then
    echo "harness: the board's virtio ports did not appear in the VM"
  else
    tse-canbridge --channel "$can_port" --iface vcan0 2>/tmp/bridge.log &
    export TSE_TARGET=board TSE_RIG=$rig_port
  fi
fi
# The VM's speed now: a fixed piece of work (speed_work above), timed on the VM's clock (which
# follows the host's), against what it takes on this project's reference machine unloaded
# (speed_ref_s).  TSE_VM_SLOW, at least 1, is how many times slower the VM runs; the
# scenarios multiply their waits for an answer by it (answer_ms in target.sh).
t0=$(cut -d' ' -f1 /proc/uptime)
awk 'BEGIN { for (i = 0; i < @SPEED_WORK@; i++) s += i * 0.5; if (s < 0) print s }'
t1=$(cut -d' ' -f1 /proc/uptime)
TSE_VM_SLOW=$(awk -v t="$t1" -v t0="$t0" -v ref=@SPEED_REF_S@ 'BEGIN { s = (t - t0) / ref; printf "%.2f", s < 1 ? 1 : s }')
export TSE_VM_SLOW
echo "=== scenario begin"
echo "figure: VM boot, kernel start to scenario: $(cut -d' ' -f1 /proc/uptime) s"
echo "figure: VM speed: the speed work took $(awk -v t="$t1" -v t0="$t0" 'BEGIN { printf "%.2f", t - t0 }') s (@SPEED_REF_S@ s on the reference machine unloaded): answer waits x $TSE_VM_SLOW"
INIT
sed -i "s/@SPEED_WORK@/$speed_work/; s/@SPEED_REF_S@/$speed_ref_s/g" "$root/init"
if [ ${#pypath[@]} -gt 0 ]; then
  cat >>"$root/init" <<'INIT'
. /python.conf
t0=$(cut -d' ' -f1 /proc/uptime)
if python3 -c 'import can, pytest'; then
  t1=$(cut -d' ' -f1 /proc/uptime)
  echo "figure: VM python3 -c 'import can, pytest': $(awk "BEGIN{printf \"%.2f\", $t1 - $t0}") s"
else
  echo "harness: python3 cannot import can and pytest in the VM"
fi
INIT
fi
cat >>"$root/init" <<'INIT'
cd /tmp
# The scenario and its watchdog lead process groups of their own; the trace goes to fd 9.
exec 3<&0
BASH_XTRACEFD=9 PS4=$trace_ps4 setsid sh -x /scenario.sh 9>/harness.trace <&3 3<&- &
spid=$!
setsid sh -c "sleep $limit && : >/harness.timed-out && kill -TERM -$spid; sleep 2; kill -KILL -$spid" \
  </dev/null >/dev/null 2>&1 &
wpid=$!
exec 3<&-
wait $spid 2>/dev/null
rc=$?
kill -KILL -$wpid 2>/dev/null
if [ -e /harness.timed-out ]; then
  kill -KILL -$spid 2>/dev/null
  echo "=== scenario end 124"
  echo "=== trace begin"
  tail -n 200 /harness.trace
  echo "=== trace end"
else
  echo "=== scenario end $rc"
fi
poweroff -f
INIT
chmod +x "$root/init"
(cd "$root" && find . | cpio -o -H newc 2>/dev/null | gzip >"$work/initrd.gz")
initrd="$work/initrd.gz"
if [ ${#pypath[@]} -gt 0 ]; then
  # Uncompressed (the kernel copies it faster under TCG than it would gunzip it), first (cpio pads
  # it to 512 bytes, so the gzipped archive after it starts aligned), then the gzipped one.
  t_rd=$(date +%s.%N)
  initrd="$work/initrd-python.img"
  { (cd "$pyroot" && find . | cpio -o -H newc 2>/dev/null); cat "$work/initrd.gz"; } >"$initrd"
  echo "figure: initramfs with Python $(du -k "$initrd" | cut -f1) KiB (the gzipped part" \
    "$(du -k "$work/initrd.gz" | cut -f1) KiB), packed in $(awk "BEGIN{printf \"%.1f\", $(date +%s.%N) - $t_rd}") s"
fi

# QEMU's own limit stays above the scenario's, so that a time-out inside the VM gets reported.
vm_devices=()
if [ -n "$board" ]; then
  board_start
  trap 'board_stop' EXIT
  vm_devices=(-device virtio-serial-pci
              -chardev "socket,id=boardcan,path=$work/board/can.sock" -device virtserialport,chardev=boardcan,name=tse.can
              -chardev "socket,id=boardrig,path=$work/board/rig.sock" -device virtserialport,chardev=boardrig,name=tse.rig)
fi
t0=$(date +%s.%N)
if [ -n "${HARNESS_LIVE:-}" ]; then
  # Live: the scenario's output as it happens (progress bars included).
  timeout $((limit + 120)) qemu-system-x86_64 -accel tcg -m 512 -nographic -no-reboot -kernel "$vmlinuz" \
    -initrd "$initrd" -append "console=ttyS0 quiet panic=-1" ${vm_devices[@]+"${vm_devices[@]}"} 2>&1 |
    tee "$work/console.log" |
    sed -u -n '/=== scenario begin/,/=== scenario end/{/=== scenario/d;p}'
else
  timeout $((limit + 120)) qemu-system-x86_64 -accel tcg -m 512 -nographic -no-reboot -kernel "$vmlinuz" \
    -initrd "$initrd" -append "console=ttyS0 quiet panic=-1" ${vm_devices[@]+"${vm_devices[@]}"} \
    >"$work/console.log" 2>&1
fi
t1=$(date +%s.%N)
[ -n "${HARNESS_LIVE:-}" ] || sed -n '/=== scenario begin/,/=== scenario end/p' "$work/console.log" | sed '1d;$d' | tr -d '\r'
rc=$(sed -n 's/.*=== scenario end \([0-9]*\).*/\1/p' "$work/console.log" | tr -d '\r')
echo "harness: VM boot to power-off $(echo "$t1 - $t0" | bc 2>/dev/null || awk "BEGIN{print $t1 - $t0}") s"
[ -n "$rc" ] || { echo "harness: the VM did not finish the scenario"; tail -20 "$work/console.log"; exit 1; }
if grep -q '=== trace begin' "$work/console.log"; then
  sed -n '/=== trace begin/,/=== trace end/p' "$work/console.log" | sed '1d;$d' | tr -d '\r' >"$work/scenario.trace"
  report_timeout "$work/scenario.trace"
fi
exit "$rc"
