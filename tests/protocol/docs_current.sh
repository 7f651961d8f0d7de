#!/usr/bin/env bash
# The committed protocol documents are what the message table says today.
# Usage: docs_current.sh PROTOGEN SOURCE_DIR
set -u
gen=$1
src=$2
fail=0
if ! "$gen" markdown | diff -u "$src/docs/protocol.md" - >/dev/null; then
  echo "FAIL: docs/protocol.md differs from the table; regenerate both: cmake --build <build dir> --target protocol_docs"
  fail=1
fi
if ! "$gen" dbc 1 | diff -u "$src/docs/tse_node1.dbc" - >/dev/null; then
  echo "FAIL: docs/tse_node1.dbc differs from the table; regenerate both: cmake --build <build dir> --target protocol_docs"
  fail=1
fi
echo "$((2 - fail * 1)) passed, $fail failed"
exit $fail
