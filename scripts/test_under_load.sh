#!/usr/bin/env bash
# scripts/test.sh with busy loops running beside it, as on a machine shared with other work (the
# suites must pass so: their time limits come from what the controller needs and the measured
# speed of the machine, not from an idle one).  Prints the wall time, and the highest 1-minute load
# average seen (sampled every 10 s).  The loops are plain shell loops at normal priority, one per
# --loops (default 2: on a 2-core machine, a load near 4 before the suites add theirs); they end
# with the script.
#   scripts/test_under_load.sh [--loops N]
set -euo pipefail
cd "$(dirname "$0")/.."
loops=2
while [ $# -gt 0 ]; do
  case $1 in
    --loops) loops=${2:?--loops needs a value}; shift 2 ;;
    -h|--help) sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "test_under_load.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
case $loops in ''|*[!0-9]*) echo "test_under_load.sh: --loops takes a whole number, not '$loops'" >&2; exit 2 ;; esac
pids=()
stop() { [ ${#pids[@]} -eq 0 ] || kill "${pids[@]}" 2>/dev/null || true; }
trap stop EXIT
for _ in $(seq "$loops"); do
  (while :; do :; done) &
  pids+=($!)
done
peak=$(mktemp)
echo 0 >"$peak"
(while sleep 10; do
   awk -v f="$peak" '{ getline p < f; close(f); if ($1 > p) { print $1 > f; close(f) } }' /proc/loadavg
 done) &
pids+=($!)
start=$SECONDS
set +e
bash scripts/test.sh
rc=$?
set -e
echo "test_under_load: scripts/test.sh beside $loops busy loops on $(nproc) cores: exit $rc after" \
     "$((SECONDS - start)) s; highest 1-minute load average $(cat "$peak")"
rm -f "$peak"
exit "$rc"
