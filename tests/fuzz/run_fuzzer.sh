#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time from the committed seed corpus, and prints its
# figures (executions, coverage, corpus size).  First the target's regressions
# (SEED_DIR/../regressions) run once each, unmutated: the host build replays them too, but this
# build (Clang) computes as a CPU without FMA does, and the host build's CPU may have it
# (kinematics/src/kin_internal.h).  They are not seeds: mutating them steers the kin target into
# the near-singular float territory whose open questions docs/reliability.md lists.  New inputs go to a working corpus in the build
# tree, never into the repository; a crash leaves its input in WORK/artifacts and fails.
#   run_fuzzer.sh FUZZER NAME SECONDS SEED_DIR WORK_DIR [extra libFuzzer flags]
set -euo pipefail
fuzzer=$1 name=$2 seconds=$3 seeds=$4 work=$5
shift 5
mkdir -p "$work/corpus" "$work/artifacts"
log="$work/fuzz.log"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
if [ -d "$seeds/../regressions" ]; then
  mapfile -t inputs < <(find "$seeds/../regressions" -type f | sort)
  if [ ${#inputs[@]} -gt 0 ] &&
     ! "$fuzzer" -runs=1 -artifact_prefix="$work/artifacts/" "$@" "${inputs[@]}" >"$work/regressions.log" 2>&1; then
    tail -n 40 "$work/regressions.log"
    echo "fuzz $name: a regression input fails in the fuzz build (log: $work/regressions.log)" >&2
    exit 1
  fi
  echo "fuzz $name: ${#inputs[@]} regression inputs replayed in the fuzz build"
fi
start=$(date +%s)
set +e
"$fuzzer" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$work/artifacts/" "$@" "$work/corpus" "$seeds" >"$log" 2>&1
rc=$?
set -e
end=$(date +%s)
stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -1; }
done_line=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$log" | tail -1 || true)
cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<<"$done_line")
ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$done_line")
corp=$(sed -nE 's/.* corp: ([0-9]+).*/\1/p' <<<"$done_line")
echo "fuzz $name: $(stat number_of_executed_units) executions in $((end - start)) s" \
     "($(stat average_exec_per_sec)/s), coverage ${cov:-?} edges, ${ft:-?} features," \
     "corpus ${corp:-?} inputs, peak RSS $(stat peak_rss_mb) MB"
if [ "$rc" -ne 0 ]; then
  tail -n 60 "$log"
  echo "fuzz $name: FAILED (exit $rc); input kept in $work/artifacts/:" >&2
  ls -1 "$work/artifacts" >&2 || true
  echo "fuzz $name: reproduce with: $fuzzer $work/artifacts/<file>; once fixed, add the file" \
       "to $(realpath -m --relative-to=. "$seeds/../regressions")/ so that the host build replays it" >&2
  exit "$rc"
fi
