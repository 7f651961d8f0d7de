#!/usr/bin/env bash
# The tse-kin contract as a script sees it: exit codes, one line out per line in, malformed rows,
# order independence, the worked values, --help everywhere.  Usage: cli_contract.sh TSE_KIN
set -u
K=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
check() { # name, condition...
  local name=$1; shift
  if "$@"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $name"; fi
}

# Exit codes.
"$K" ik </dev/null >/dev/null 2>&1; check "ik on empty input exits 0" test $? -eq 0
"$K" ik --bogus </dev/null >/dev/null 2>"$tmp/err"; rc=$?
check "unknown option exits 2" test $rc -eq 2
check "unknown option is named" grep -q -- "--bogus" "$tmp/err"
"$K" frobnicate >/dev/null 2>&1; check "unknown command exits 2" test $? -eq 2
"$K" ik --precision quad </dev/null >/dev/null 2>&1; check "bad precision exits 2" test $? -eq 2
"$K" workspace --grid 1,2 >/dev/null 2>&1; check "bad grid exits 2" test $? -eq 2
"$K" ik --params "$tmp/missing" </dev/null >/dev/null 2>"$tmp/err"; rc=$?
check "missing params file exits 1" test $rc -eq 1
check "missing params file is named" grep -q "missing" "$tmp/err"
printf 'L = 1.7\nk2 = 3\n' >"$tmp/bad.params"
"$K" ik --params "$tmp/bad.params" </dev/null >/dev/null 2>"$tmp/err"; rc=$?
check "bad params file exits 1" test $rc -eq 1
check "bad params file names line 2" grep -q "bad.params:2: unknown key 'k2'" "$tmp/err"

# Malformed rows: an invalid line each, and the stream goes on.
printf '0,0,1,0,0,0\nabc\n\n1,2\n0,0,1,0,0,0,7\n0,0,1,0,0,0\n' >"$tmp/in"
"$K" ik <"$tmp/in" >"$tmp/out"; rc=$?
check "malformed rows exit 0" test $rc -eq 0
check "one line out per line in" test "$(wc -l <"$tmp/out")" -eq 6
check "malformed rows are invalid,0" test "$(grep -c '^invalid,0,nan' "$tmp/out")" -eq 4
check "good rows around them solved" test "$(grep -c '^ok,0,' "$tmp/out")" -eq 2

# The worked value of kinematics.md, both precisions.
for prec in double float; do
  tol=$([ "$prec" = double ] && echo 1e-9 || echo 2e-6)
  echo "0,0,1,0,0,0" | "$K" ik --precision "$prec" | awk -F, -v t="$tol" '
    { ok = ($1 == "ok" && $2 == 0); for (i = 3; i <= 8; ++i) { d = $i - 0.43015083911167; if (d < 0) d = -d; if (d > t) ok = 0 } }
    END { exit !ok }'
  check "worked value ($prec)" test $? -eq 0
done

# Order independence: reversed input gives reversed output.
awk 'BEGIN { srand(5); for (i = 0; i < 50; ++i) printf "%.6f,%.6f,%.6f,%.4f,%.4f,%.4f\n", rand()*0.6-0.3, rand()*0.6-0.3, 0.4+rand()*1.2, rand()*0.4-0.2, rand()*0.4-0.2, rand()-0.5 }' >"$tmp/poses"
"$K" ik <"$tmp/poses" >"$tmp/fwd"
tac "$tmp/poses" | "$K" ik | tac >"$tmp/rev"
check "output independent of line order" cmp -s "$tmp/fwd" "$tmp/rev"

# FK takes the slides back to the pose; a seed pose may follow.
echo "0.39127069075903,0.41631844093909,0.38241559603276,0.42099161248302,0.56558364785006,0.23697220292616,0.1,0,1.1,0,0,0.2" |
  "$K" fk | awk -F, '{ exit !($1 == "ok" && ($3 - 0.1)^2 < 1e-18 && ($5 - 1.1)^2 < 1e-18 && ($8 - 0.2)^2 < 1e-18) }'
check "fk of the worked value" test $? -eq 0
echo "0,0,1,0,0,0" | "$K" jacobian | awk -F, '{ exit !($1 == "ok" && NF == 44) }'
check "jacobian line has status, scissor, 36 + 6 numbers" test $? -eq 0
"$K" workspace --grid 5,4,5 | tail -1 | grep -Eq '^[0-9]+,100,0\.[0-9]+$'
check "workspace last line is reachable,total,fraction" test $? -eq 0
"$K" haf | tail -1 | grep -q '^haf,.*,paper,11.487$'
check "haf summary line" test $? -eq 0

for c in "" ik fk jacobian haf workspace bench; do
  "$K" $c --help >"$tmp/help" 2>&1; rc=$?
  check "--help ${c:-(top)} exits 0" test $rc -eq 0
  check "--help ${c:-(top)} prints usage" grep -q "usage: tse-kin" "$tmp/help"
done

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
