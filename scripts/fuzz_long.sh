#!/usr/bin/env bash
# The long fuzz runs of docs/reliability.md: builds the fuzz preset and runs each target (or the
# ones named) for SECONDS (default 3600) from its committed seed corpus, JOBS at a time (default
# the number of cores), at low priority.  Each run's figures (executions, rate, coverage, corpus)
# are printed and kept in build/fuzz/long/<target>/fuzz.log; the corpus it grew stays in
# build/fuzz/long/<target>/corpus, to be merged into its folder's seeds with
#   build/fuzz/tests/fuzz/<folder>/fuzz_<t> -merge=1 tests/fuzz/<folder>/corpus build/fuzz/long/<t>/corpus
#   scripts/fuzz_long.sh [--seconds S] [--jobs J] [target...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=3600
jobs=$(nproc 2>/dev/null || echo 2)
targets=()
while [ $# -gt 0 ]; do
  case $1 in
    --seconds) seconds=${2:?--seconds needs a value}; shift 2 ;;
    --jobs) jobs=${2:?--jobs needs a value}; shift 2 ;;
    -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "fuzz_long.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
case $seconds in ''|*[!0-9]*) echo "fuzz_long.sh: --seconds takes a whole number, not '$seconds'" >&2; exit 2 ;; esac
case $jobs in ''|*[!0-9]*|0) echo "fuzz_long.sh: --jobs takes a whole number >= 1, not '$jobs'" >&2; exit 2 ;; esac
# A target is declared in its folder's CMakeLists.txt (tse_fuzz_target NAME); a folder may declare
# more than one (controller and controller_float share theirs, with its seeds and regressions).
declared() {
  local d
  for d in tests/fuzz/*/CMakeLists.txt; do
    sed -nE 's/^tse_fuzz_target\(NAME ([a-z_0-9]+).*/\1 '"$(basename "$(dirname "$d")")"'/p' "$d"
  done
}
if [ ${#targets[@]} -eq 0 ]; then
  while read -r t _; do targets+=("$t"); done < <(declared)
fi
declare -A folder
while read -r t d; do folder[$t]=$d; done < <(declared)
for t in "${targets[@]}"; do
  [ -n "${folder[$t]:-}" ] || { echo "fuzz_long.sh: no fuzz target '$t' in tests/fuzz" >&2; exit 2; }
done

cmake --preset fuzz >/dev/null
cmake --build build/fuzz -j "$jobs" --target "${targets[@]/#/fuzz_}"
echo "fuzz_long.sh: ${#targets[@]} targets for $seconds s each, $jobs at a time"
failed=0
run_one() {
  local t=$1 exe
  exe=$(find build/fuzz/tests/fuzz/"${folder[$t]}" -maxdepth 1 -name "fuzz_$t" -type f | head -1)
  nice -n 19 bash tests/fuzz/run_fuzzer.sh "$exe" "$t" "$seconds" "tests/fuzz/${folder[$t]}/corpus" \
    "build/fuzz/long/$t" $(cat "build/fuzz/fuzz-work/$t.flags")
}
running=0
for t in "${targets[@]}"; do
  run_one "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n || failed=1
    running=$((running - 1))
  fi
done
while [ "$running" -gt 0 ]; do
  wait -n || failed=1
  running=$((running - 1))
done
exit "$failed"
