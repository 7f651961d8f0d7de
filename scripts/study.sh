#!/usr/bin/env bash
# The paper's design study for one design (docs/analysis.md): tse-kin's sweeps of k1, k2 (eta),
# k3 and k4, the singular values along the vertical axis, the workspace at two orientations and
# the type-1 margin of two slide angles, as CSV files and matplotlib PNGs.
#
#   scripts/study.sh [--params FILE] [--out DIR] [--grid NR,NPHI,NZ] [--designs N] [--jobs J]
#                    [--quick] [--tse-kin PATH]
#
# Without --tse-kin it builds tse-kin in build/release (optimised: the study's time is quoted), and
# the kinematics library beside it (<build>/python/libtse_kin.so, or $TSE_KIN_LIB), whose reader
# gives the design's values.
# The design comes from --params (a parameter file read as a design, as tse-kin --design reads it;
# default the paper's prototype); the
# output goes to --out (default build/study/NAME, NAME the file's name or "prototype"): the PNGs
# there, the CSVs in its csv/ folder.  The sweeps' time is printed (the paper's full study: four
# sweeps of 50 designs on its 16 x 24 x 32 grid).  --quick: tiny grids and few designs, for tests.
# Exit status: 0 done; 1 a tool failed (its message is shown), 2 bad arguments.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

kin=
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --tse-kin)
      [ $# -ge 2 ] || { echo "study: --tse-kin needs a path" >&2; exit 2; }
      kin=$2; shift 2 ;;
    --tse-kin=*) kin=${1#--tse-kin=}; shift ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) args+=("$1"); shift ;;
  esac
done

# Debian's interpreter, the one python3-matplotlib installs into (a pyenv or venv python earlier
# in PATH would not have it).
py=/usr/bin/python3
[ -x "$py" ] || py=$(command -v python3)
if ! "$py" -c 'import matplotlib' 2>/dev/null; then
  echo "study: matplotlib is missing; installing the project's packages (scripts/setup.sh)" >&2
  bash "$root/scripts/setup.sh"
fi

if [ -z "$kin" ]; then
  echo "study: building tse-kin and the kinematics library (build/release)" >&2
  (cd "$root" && cmake --preset release >/dev/null &&
     cmake --build --preset release --target tse-kin tse_kin_py -j "$(nproc 2>/dev/null || echo 2)" >/dev/null)
  kin=$root/build/release/host_tools/tse-kin
fi
[ -x "$kin" ] || { echo "study: no tse-kin at '$kin'" >&2; exit 2; }

exec "$py" "$root/scripts/study.py" --tse-kin "$kin" ${args[@]+"${args[@]}"}
