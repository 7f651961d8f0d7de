#!/usr/bin/env bash
# tse-sim --fault SPEC, without a bus: --help documents it; a bad spec stops tse-sim before it
# starts (exit 2) naming the item and the rule; a good one gets it as far as opening the
# interface (no CAN here: exit 1).
set -u
T=$1
. "$(dirname "$0")/../support/check.sh"

"$T" --help 2>"$tmp/usage"; check "--help exits 0" test $? -eq 0
check "usage names --fault" grep -q -- "\[--fault SPEC\]" "$tmp/usage"
for item in "drop|dup|reorder|delay|corrupt=P" "delay_ms=N" "seed=N" "silence=T\[+D\]" "busoff=T\[+D\]" \
            "estop=T\[+D\]" "limit=K@T\[+D\]" "stall=K@T\[+D\]"; do
  check "usage explains $item" grep -q -- "$item" "$tmp/usage"
done

bad() { # spec, what stderr must say
  "$T" --iface nosuchcan0 --node 1 --fault "$1" >"$tmp/out" 2>"$tmp/err"; local rc=$?
  check "'$1' exits 2" test $rc -eq 2
  check "'$1' says: $2" grep -qF -- "tse-sim: --fault: $2" "$tmp/err"
  check "'$1' opens no interface" test ! -s "$tmp/out"
}
bad "drop=1.5" "'drop=1.5': drop is a probability, 0..1"
bad "drop=0.6,dup=0.6" "drop, dup, reorder, delay and corrupt add up to 1.2: at most 1"
bad "jitter=1" "unknown item 'jitter'"
bad "limit=9@1" "'limit=9@1': the slide is 1..6"
bad "busoff=2+0" "'busoff=2+0': expected T or T+D, seconds after the start (T >= 0, D > 0)"
bad "seed=7,seed=8" "'seed' given twice"
bad "" "empty: give items such as drop=0.01,seed=7"

"$T" --iface nosuchcan0 --node 1 --fault drop=0.01,dup=0.01,seed=7,estop=5+1,stall=2@3 >"$tmp/out" 2>"$tmp/err"; rc=$?
check "a good spec gets as far as the interface (exit 1)" test $rc -eq 1
check "it says so" grep -q "cannot open CAN interface nosuchcan0" "$tmp/err"
check "no complaint about the spec" bash -c "! grep -q -- '--fault' '$tmp/err'"

check_done
