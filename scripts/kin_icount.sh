#!/usr/bin/env bash
# Instruction counts of the kinematics and the move planning on the host, under callgrind.
#
# Method: bench/kin_icount.c (built with the release preset: -O3, x86-64) runs each measured
# operation many times inside a noinline function of its own (measure_ik_double_warm, ...) on the
# 2000-pose path of `tse-kin bench`, prototype design.  For each figure this script runs the
# program once under `valgrind --tool=callgrind --toggle-collect=measure_X`, so that only the
# instructions executed inside measure_X and everything it calls are counted (the `totals:` line
# of callgrind's output), then once more for measure_loop_X, the same loop with the library call
# replaced by a stub that does nothing (its loop overhead, about 20 instructions a call).
# Figure = (count(measure_X) - count(measure_loop_X)) / calls, rounded to the nearest integer, the
# calls being what `kin-icount list` says one measure performs.  validate_segment is one planning
# (fw_move_plan, validation included) of a 5 s move from the home pose to one 0.3 m higher with a
# 0.1 rad roll, under the limits the default parameter set gives a 1 kHz / 200 kHz controller,
# divided by the move's segments (no loop to take off).  Every operation is called once before
# any measure, so lazy symbol binding is not counted.  The counts are deterministic on a given
# machine and libc (libm's sin/cos pick their code by CPU features, so another CPU may differ by
# a little); nothing is timed.
#
# Output: one `name,instructions` line per figure, in this order: ik_double_warm, ik_double_cold,
# ik_float_warm, fk_double_warm, validate_segment, ik_float_cold, fk_float_warm; then one `#` line
# per figure with its goal.  The board's own figures come from scripts/target_bench.sh.
#
# On an x86-64 CPU with fused multiply-add, tse_ik and FK's Newton step run their second build
# (kinematics/src/kin_internal.h, TSE_FMA_CLONES) and that is what is counted; --baseline builds
# without it (-DTSE_NO_FMA_CLONES, into build/release-baseline) and counts the baseline x86-64
# code.  A `# build:` line says which was counted.
#
# Usage: scripts/kin_icount.sh [--baseline]   (builds into build/release, or build/release-baseline)
#        TSE_ICOUNT_BUILD=DIR scripts/kin_icount.sh   (another build directory, release preset)
# Needs valgrind (scripts/setup.sh installs it).
set -euo pipefail
cd "$(dirname "$0")/.."
flags=
build=${TSE_ICOUNT_BUILD:-build/release}
case ${1:-} in
  '') ;;
  --baseline) flags=-DTSE_NO_FMA_CLONES; build=${TSE_ICOUNT_BUILD:-build/release-baseline} ;;
  *) echo "kin_icount: unknown argument '$1' (usage: scripts/kin_icount.sh [--baseline])" >&2; exit 2 ;;
esac

command -v valgrind >/dev/null 2>&1 || { echo "kin_icount: valgrind not found (bash scripts/setup.sh installs it)" >&2; exit 1; }
cmake --preset release -B "$build" -DCMAKE_C_FLAGS="$flags" >/dev/null
cmake --build "$build" --target kin-icount -j "$(nproc)" >/dev/null
bin=$build/bench/kin-icount

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Instructions executed inside function $1 (inclusive) when the program runs just that function.
count() {
  local out=$work/cg.out
  rm -f "$out"
  valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect="$1" -q "$bin" "$1" >/dev/null
  local n
  n=$(awk '$1 == "totals:" { print $2 }' "$out")
  [ -n "$n" ] || { echo "kin_icount: no totals for $1" >&2; exit 1; }
  echo "$n"
}

list=$("$bin" list)
declare -A fig ncalls ntotal
while IFS=, read -r tag name measure loop calls; do
  [ "$tag" = figure ] || continue
  total=$(count "$measure")
  overhead=0
  [ "$loop" = - ] || overhead=$(count "$loop")
  fig[$name]=$(( (total - overhead + calls / 2) / calls ))
  ncalls[$name]=$calls
  ntotal[$name]=$(( total - overhead ))
  echo "$name,${fig[$name]}"
done <<<"$list"

for required in ik_double_warm ik_double_cold ik_float_warm fk_double_warm validate_segment; do
  [ -n "${fig[$required]:-}" ] || { echo "kin_icount: kin-icount gave no figure $required" >&2; exit 1; }
done

verdict() { if [ "$1" -le "$2" ]; then echo "met"; else echo "not met"; fi; }
echo "# ik_double_warm: goal <= 1500 instructions ($(verdict "${fig[ik_double_warm]}" 1500))"
echo "# ik_double_cold: goal <= 2500 instructions ($(verdict "${fig[ik_double_cold]}" 2500))"
echo "# ik_float_warm: host float, for information; the board's goal is measured by scripts/target_bench.sh"
fk_goal=$(( 3 * fig[ik_double_warm] ))
echo "# fk_double_warm: goal <= 3 x ik_double_warm = $fk_goal instructions ($(verdict "${fig[fk_double_warm]}" "$fk_goal"))"
echo "# validate_segment: for information; the move has ${ncalls[validate_segment]} segments, and planning it takes ${ntotal[validate_segment]} instructions"
[ -z "${fig[ik_float_cold]:-}" ] || echo "# ik_float_cold, fk_float_warm: host float, for information"
grep '^# build:' <<<"$list"
