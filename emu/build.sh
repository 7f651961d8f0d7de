#!/usr/bin/env bash
# Builds the TSE emulator: Debian's QEMU 7.2 source with the device models of emu/hw added, one
# binary (qemu-system-arm, arm-softmmu only, machine tse-f407), cached outside the clone:
#
#   ${TSE_EMU_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/tse-emu}/<key>/qemu-system-arm
#
# <key> hashes emu/'s build inputs (hw/, qemu/, this script) and the source package's version,
# so a second run with the binary present does nothing but print its path.  The last line of
# stdout is always that path.  Exit status: 0 built (or already), 3 QEMU's source package cannot
# be fetched (said on stderr with apt's last words), 1 any other failure, 2 a usage error.
#
# Usage: emu/build.sh [--update] [--clean] [-j N] | --path
#   --path    print the binary's path if it is built for emu/ as it is, else fail (exit 1)
#   --update  ask the archive again for the newest QEMU source package (apt-get update with the
#             private configuration below) instead of the version fetched last time
#   --clean   build in a fresh tree (otherwise the previous tree is reused: only the files that
#             changed are compiled again)
#   -j N      parallel compile jobs (default 2, or TSE_EMU_JOBS)
#
# The source comes from `apt-get source qemu` through a private apt configuration holding
# deb-src lines for the suites /etc/apt's sources use (TSE_EMU_SOURCES_LIST: a file of deb-src
# lines to use instead); nothing in /etc changes and no root is needed.  Build dependencies:
# scripts/setup.sh (libglib2.0-dev libpixman-1-dev libfdt-dev meson ninja-build dpkg-dev ...).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cache=${TSE_EMU_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/tse-emu}
jobs=${TSE_EMU_JOBS:-2}
update=0
clean=0
path_only=0
while [ $# -gt 0 ]; do
  case $1 in
    --update) update=1 ;;
    --clean) clean=1 ;;
    --path) path_only=1 ;;
    -j) jobs=${2:?-j needs a number}; shift ;;
    -j*) jobs=${1#-j} ;;
    -h|--help) sed -n '2,25p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "emu/build.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done

say() { echo "emu/build.sh: $*" >&2; }
die() { say "$*"; exit 1; }

mkdir -p "$cache"
apt_dir=$cache/apt
version_file=$cache/source-version

# The key: the source package's version and every build input under emu/ (not run.sh, tests or
# docs, which do not change the binary).
emu_inputs_hash() {
  (cd "$here" && find hw qemu build.sh -type f | LC_ALL=C sort | xargs sha256sum) | sha256sum | cut -c1-16
}

# ---- the private apt configuration ----

# deb-src lines for every `deb` entry of /etc/apt (one-line and deb822 formats).
derive_sources() {
  local f
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    sed -n -E 's/^[[:space:]]*deb[[:space:]]+/deb-src /p' "$f"
  done
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    # deb822 stanzas: Types, URIs, Suites, Components, Signed-By; blank lines separate them.
    awk '
      function flush() {
        if (types ~ /(^| )deb( |$)/ && uris != "" && enabled != "no") {
          n = split(uris, u, " "); m = split(suites, s, " ")
          opt = signed != "" ? "[signed-by=" signed "] " : ""
          for (i = 1; i <= n; i++) for (j = 1; j <= m; j++)
            print "deb-src " opt u[i] " " s[j] " " comps
        }
        types = uris = suites = comps = signed = enabled = ""
      }
      /^[[:space:]]*#/ { next }
      /^[[:space:]]*$/ { flush(); next }
      { key = tolower($1); sub(/:$/, "", key); $1 = ""; sub(/^ +/, "")
        if (key == "types") types = $0; else if (key == "uris") uris = $0
        else if (key == "suites") suites = $0; else if (key == "components") comps = $0
        else if (key == "signed-by") signed = $0; else if (key == "enabled") enabled = tolower($0) }
      END { flush() }' "$f"
  done
}

apt_opts=()
setup_apt() {
  mkdir -p "$apt_dir/lists/partial" "$apt_dir/cache/archives/partial"
  if [ -n "${TSE_EMU_SOURCES_LIST:-}" ]; then
    cp "$TSE_EMU_SOURCES_LIST" "$apt_dir/sources.list"
  else
    derive_sources | awk '!seen[$0]++' > "$apt_dir/sources.list"
  fi
  [ -s "$apt_dir/sources.list" ] || die "no deb entries found in /etc/apt to derive deb-src lines from (set TSE_EMU_SOURCES_LIST to a file of deb-src lines)"
  apt_opts=(-o "Dir::Etc::sourcelist=$apt_dir/sources.list" -o "Dir::Etc::sourceparts=-"
            -o "Dir::State::lists=$apt_dir/lists" -o "Dir::Cache=$apt_dir/cache"
            -o "APT::Sandbox::User=$(id -un)" -o "Debug::NoLocking=1")
}

fetch_failed() {
  say "cannot fetch QEMU's source package: $1"
  say "  (apt-get source qemu through deb-src lines for the suites of /etc/apt: $apt_dir/sources.list)"
  [ -f "$apt_dir/log" ] && sed 's/^/  | /' "$apt_dir/log" | tail -8 >&2
  exit 3
}

# Asks the archive for the newest qemu source version; writes it to $version_file.
resolve_version() {
  setup_apt
  say "asking the archive for QEMU's source package (apt-get update, private lists in $apt_dir)"
  apt-get "${apt_opts[@]}" -q update > "$apt_dir/log" 2>&1 || true
  local v
  v=$({ apt-cache "${apt_opts[@]}" showsrc qemu 2>>"$apt_dir/log" || true; } | sed -n 's/^Version: //p' | sort -V | tail -1)
  [ -n "$v" ] || fetch_failed "no source package 'qemu' in the archive (network, or no deb-src index)"
  echo "$v" > "$version_file"
}

if [ "$path_only" = 1 ]; then
  [ -s "$version_file" ] || die "not built (no QEMU source fetched yet): run emu/build.sh"
  p=$cache/$(printf '%s\n%s\n' "$(cat "$version_file")" "$(emu_inputs_hash)" | sha256sum | cut -c1-16)/qemu-system-arm
  [ -x "$p" ] || die "not built for emu/ as it is: run emu/build.sh"
  echo "$p"
  exit 0
fi
if [ "$update" = 1 ] || [ ! -s "$version_file" ]; then
  resolve_version
fi
version=$(cat "$version_file")
key=$(printf '%s\n%s\n' "$version" "$(emu_inputs_hash)" | sha256sum | cut -c1-16)
out=$cache/$key/qemu-system-arm

if [ -x "$out" ] && [ "$clean" = 0 ]; then
  echo "$out"
  exit 0
fi

# ---- source ----
upstream=${version#*:}          # 1:7.2+dfsg-7+deb12u18 -> 7.2+dfsg-7+deb12u18
work=$cache/work/$upstream
src=$work/qemu
bld=$work/build
if [ "$clean" = 1 ]; then
  rm -rf "$work"
fi
if [ ! -f "$src/.tse-unpacked" ]; then
  [ ${#apt_opts[@]} -gt 0 ] || setup_apt
  if ! ls "$apt_dir/lists/"*Sources* >/dev/null 2>&1; then
    apt-get "${apt_opts[@]}" -q update > "$apt_dir/log" 2>&1 || true
  fi
  rm -rf "$work"
  mkdir -p "$work/dl"
  say "fetching qemu $version (apt-get source)"
  (cd "$work/dl" && apt-get "${apt_opts[@]}" -q --download-only source "qemu=$version") \
    > "$apt_dir/log" 2>&1 || fetch_failed "apt-get source qemu=$version failed"
  dsc=$(ls "$work"/dl/qemu_*.dsc 2>/dev/null | head -1)
  [ -n "$dsc" ] || fetch_failed "no .dsc downloaded"
  say "unpacking (dpkg-source -x, Debian's patches applied)"
  command -v dpkg-source >/dev/null || die "dpkg-source missing: run scripts/setup.sh (dpkg-dev)"
  (cd "$work" && dpkg-source --no-check -x "$dsc" qemu) > "$work/unpack.log" 2>&1 \
    || { tail -5 "$work/unpack.log" >&2; die "dpkg-source -x failed"; }
  touch "$src/.tse-unpacked"
fi
# emu/qemu/tse.patch, as it is: the one applied before is taken back first, so that only the
# files the two touch change (and are compiled again).
if ! cmp -s "$here/qemu/tse.patch" "$src/.tse-patch"; then
  if [ -f "$src/.tse-patch" ]; then
    (cd "$src" && patch -R -p1 --quiet < .tse-patch) || die "cannot take back the previous emu/qemu/tse.patch (--clean starts afresh)"
  fi
  (cd "$src" && patch -p1 --forward --quiet < "$here/qemu/tse.patch") || die "emu/qemu/tse.patch does not apply to qemu $version"
  cp "$here/qemu/tse.patch" "$src/.tse-patch"
fi

# ---- our models: copied only where their contents changed (ninja then rebuilds just those) ----
mkdir -p "$src/hw/tse"
for f in "$here"/hw/*; do
  dst=$src/hw/tse/$(basename "$f")
  cmp -s "$f" "$dst" || cp "$f" "$dst"
done
for f in "$src"/hw/tse/*; do
  [ -e "$here/hw/$(basename "$f")" ] || rm -f "$f"
done
cmp -s "$here/qemu/arm-softmmu.mak" "$src/configs/devices/arm-softmmu/default.mak" \
  || cp "$here/qemu/arm-softmmu.mak" "$src/configs/devices/arm-softmmu/default.mak"

# ---- configure (once a tree) and build ----
for tool in meson ninja pkg-config cc; do
  command -v $tool >/dev/null || die "$tool missing: run scripts/setup.sh"
done
# arm-softmmu only, nothing QEMU would build by default, no edk2 blobs (Debian's tarball has
# none).  (QEMU's QOM cast checks stay on: without them a cast to a class with interfaces loses
# its cache and the core's class lookups cost more, not less.)
configure_args=(--target-list=arm-softmmu --without-default-features --without-default-devices
                --disable-install-blobs --enable-fdt=system --disable-docs --audio-drv-list=)
if [ ! -f "$bld/build.ninja" ] || [ "$(cat "$bld/.tse-configure" 2>/dev/null)" != "${configure_args[*]}" ]; then
  rm -rf "$bld"
  mkdir -p "$bld"
  say "configuring (arm-softmmu, no default features or devices)"
  t0=$(date +%s)
  (cd "$bld" && "$src/configure" "${configure_args[@]}") > "$work/configure.log" 2>&1 \
    || { tail -20 "$work/configure.log" >&2; die "configure failed (log: $work/configure.log)"; }
  echo "${configure_args[*]}" > "$bld/.tse-configure"
  say "configured in $(( $(date +%s) - t0 )) s"
fi
say "building qemu-system-arm (-j$jobs; log: $work/build.log)"
t0=$(date +%s)
ninja -C "$bld" -j "$jobs" qemu-system-arm > "$work/build.log" 2>&1 \
  || { grep -E 'error|Error' "$work/build.log" | head -20 >&2; tail -5 "$work/build.log" >&2; die "build failed (log: $work/build.log)"; }
say "built in $(( $(date +%s) - t0 )) s"
# Our models compile warning-free (QEMU's release build does not use -Werror): a warning fails
# the build, and its file is removed from the tree so that the next run compiles it again.
if grep -E '^\.\./qemu/hw/tse/[^:]+:[0-9]+(:[0-9]+)?: warning' "$work/build.log" >&2; then
  for f in $(grep -oE '^\.\./qemu/hw/tse/[^:]+' "$work/build.log" | sort -u); do rm -f "$bld/$f"; done
  die "warnings in emu/hw (above)"
fi

mkdir -p "$cache/$key"
cp "$bld/qemu-system-arm" "$out.tmp"
strip "$out.tmp" 2>/dev/null || true
mv "$out.tmp" "$out"
printf 'qemu %s\nemu inputs %s\nbuilt %s\n' "$version" "$(emu_inputs_hash)" "$(date -u +%FT%TZ)" > "$cache/$key/BUILD-INFO"
# The four binaries built last stay (other branches' models), older ones go.
(cd "$cache" && ls -dt -- */ | sed 's#/$##' | grep -E '^[0-9a-f]{16}$' | tail -n +5 | xargs -r rm -rf --)
say "$(du -h "$out" | cut -f1) $out"
echo "$out"
