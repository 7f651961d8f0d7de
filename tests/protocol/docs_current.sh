#!/usr/bin/env bash
# The committed protocol documents and the Python client's tables are what the message table says
# today.
# Usage: docs_current.sh PROTOGEN SOURCE_DIR
set -u
gen=$1
src=$2
fail=0
if ! "$gen" markdown | diff -u "$src/docs/protocol.md" - >/dev/null; then
  echo "FAIL: docs/protocol.md differs from the table; regenerate them: cmake --build <build dir> --target protocol_docs"
  fail=$((fail + 1))
fi
if ! "$gen" dbc 1 | diff -u "$src/docs/tse_node1.dbc" - >/dev/null; then
  echo "FAIL: docs/tse_node1.dbc differs from the table; regenerate them: cmake --build <build dir> --target protocol_docs"
  fail=$((fail + 1))
fi
if ! "$gen" python | diff -u "$src/python/tse/_protocol.py" - >/dev/null; then
  echo "FAIL: python/tse/_protocol.py differs from the table; regenerate: cmake --build <build dir> --target protocol_docs"
  fail=$((fail + 1))
fi
echo "$((3 - fail)) passed, $fail failed"
[ $fail -eq 0 ]
