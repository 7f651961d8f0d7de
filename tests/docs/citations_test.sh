#!/usr/bin/env bash
# scripts/check_citations.sh on trees made here: it passes a clean tree, fails on each way of citing
# the specification outside the project (naming the file and line), and looks past build/ and .git.
# Usage: citations_test.sh CHECK_CITATIONS_SH
set -u
check=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The cited names are assembled, so that this file does not cite them itself.
up=".."
pass=0 fail=0
expect() { # expect WANT_RC WHAT TREE [TEXT_IN_OUTPUT]
  local want=$1 what=$2 tree=$3 text=${4:-} out rc
  out=$(bash "$check" "$tree" 2>&1)
  rc=$?
  if [ "$rc" -ne "$want" ]; then
    echo "FAIL: $what: exit $rc, expected $want"; echo "$out"; fail=$((fail + 1)); return
  fi
  if [ -n "$text" ] && ! grep -qF -- "$text" <<<"$out"; then
    echo "FAIL: $what: the output does not name '$text'"; echo "$out"; fail=$((fail + 1)); return
  fi
  echo "ok: $what"; pass=$((pass + 1))
}
tree() { rm -rf "$work/t"; mkdir -p "$work/t/src" "$work/t/docs" "$work/t/build/host" "$work/t/.git"; \
  printf '/* see docs/controller.md, "E-stop" */\n' >"$work/t/src/a.c"; }

tree
expect 0 "a clean tree" "$work/t"

tree
printf 'int x;\n/* the state machine of %s */\n' "system.$(echo md)" >"$work/t/src/b.c"
expect 1 "the spec's file name in a C comment" "$work/t" "src/b.c:2:"

tree
printf '# see %s/shared/spec/%s\n' "$up" "system.$(echo md)" >"$work/t/docs/c.md"
expect 1 "the spec's path in a document" "$work/t" "docs/c.md:1:"

tree
printf 'cat %s/shared/README\n' "$up" >"$work/t/src/d.sh"
expect 1 "the folder beside the checkout" "$work/t" "src/d.sh:1:"

tree
printf '(%s)\n' "$up/shared" >"$work/t/src/e.txt"
expect 1 "the folder beside the checkout, at the end of a word" "$work/t" "src/e.txt:1:"

tree
printf 'see %s\n' "system.$(echo md)" >"$work/t/build/host/f.c"
printf 'see %s\n' "system.$(echo md)" >"$work/t/.git/g"
expect 0 "build/ and .git are not the project's text" "$work/t"

tree
printf 'see filesystem.md and %s/sharedlib\n' "$up" >"$work/t/src/h.c"
expect 0 "names that only contain the cited ones" "$work/t"

expect 2 "a missing directory" "$work/none"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
