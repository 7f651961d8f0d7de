#!/usr/bin/env bash
# Every citation in the project points inside it: no file outside build/ and .git may cite the
# specification kept beside the checkout (the system spec by its file name, or the folder one level
# up that holds it), which a clone does not have.  Cite docs/ instead (docs/controller.md,
# docs/harness.md, ...).
# Usage: check_citations.sh [SOURCE_DIR]   (default: the checkout this script is in)
# Exit 0 when no file cites them, 1 listing every FILE:LINE that does, 2 for a usage error.
set -u
if [ $# -gt 1 ]; then
  echo "usage: check_citations.sh [SOURCE_DIR]" >&2
  exit 2
fi
src=${1:-$(cd "$(dirname "$0")/.." && pwd)}
if [ ! -d "$src" ]; then
  echo "check_citations.sh: $src is not a directory" >&2
  exit 2
fi
src=$(cd "$src" && pwd)
# Bracketed dots, so that this file does not cite them itself.
pattern='(^|[^[:alnum:]_-])system[.]md|[.][.]/shared([^[:alnum:]_-]|$)'
hits=$(find "$src" \( -path "$src/build" -o -path "$src/.git" \) -prune -o -type f -print0 |
  xargs -0 -r grep -InE -- "$pattern" | sed "s|^$src/||")
if [ -n "$hits" ]; then
  echo "$hits"
  echo "FAIL: $(printf '%s\n' "$hits" | wc -l) line(s) cite the specification outside the project; cite docs/ instead"
  exit 1
fi
echo "no file cites the specification outside the project"
