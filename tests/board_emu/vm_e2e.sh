#!/usr/bin/env bash
# The end-to-end scenario (tests/vcan/e2e_target.sh) on the production image on the emulated
# board, driven by tsectl on the harness's vcan0 (tests/vcan/harness.sh --board), and the
# differential test: the same scenario on tse-sim must give the same transcript, the sequence of every command's ACK or REJECT (with its reason) and
# the final commanded slides in steps.
#
#   vm_e2e.sh ELF HOST_TOOLS WORKDIR
#
# HOST_TOOLS is the host build's host_tools directory (tsectl, tse-sim, tse-kin, tse-rig,
# tse-canbridge).  Skips (77) when the emulator is not built.
set -u
elf=$1 tools=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
vcan=$here/../vcan
if ! "$here/../../emu/build.sh" --path >/dev/null 2>&1 && [ -z "${TSE_EMU_QEMU:-}" ]; then
  echo "SKIP: the TSE emulator is not built for emu/ as it is: run emu/build.sh"
  exit 77
fi
bins=()
for b in tsectl/tsectl tse-sim tse-kin tse-rig tse-canbridge; do
  [ -x "$tools/$b" ] || { echo "vm_e2e: $tools/$b not found: build the host preset first"; exit 2; }
  bins+=("$tools/$b")
done
mkdir -p "$work"
transcript() { sed -n '/=== transcript begin/,/=== transcript end/p' "$1" | sed '1d;$d'; }

rc=0
for target in sim board; do
  out=$work/$target.out
  args=()
  [ "$target" = board ] && args=(--board "$elf")
  echo "=== the scenario on $target"
  t0=$(date +%s)
  HARNESS_TIMEOUT=${HARNESS_TIMEOUT:-1500} bash "$vcan/harness.sh" ${args[@]+"${args[@]}"} --file "$vcan/target.sh" \
    "$vcan/e2e_target.sh" "$work/$target" "${bins[@]}" >"$out" 2>&1
  r=$?
  sed '/=== transcript begin/,/=== transcript end/d' "$out"
  echo "figure: the scenario on $target took $(($(date +%s) - t0)) s"
  transcript "$out" >"$work/$target.transcript"
  [ $r -eq 0 ] || rc=1
done

echo "=== the differential test: tse-sim against the board"
# Every command's answer the same, line for line.  The final commanded slides in whole steps the
# same too, but for a slide whose exact position (tse-kin's double inverse kinematics of the final
# pose, an oracle independent of both) lies within the float build's accuracy of a rounding
# boundary: the board solves in float (slides within 0.3 um of the exact ones, docs/kinematics.md),
# tse-sim in double, so there the two may round apart by one step, and only there.
grep -v '^final steps:' "$work/sim.transcript" >"$work/sim.answers"
grep -v '^final steps:' "$work/board.transcript" >"$work/board.answers"
if [ -s "$work/sim.answers" ] && diff -u "$work/sim.answers" "$work/board.answers"; then
  echo "ok: the same $(wc -l <"$work/board.answers") lines of ACKs and REJECTs (with their reasons) from both"
else
  echo "FAIL: the answers differ (above: - tse-sim, + the board)"
  rc=1
fi
pose=$(sed -n 's/^final pose: //p' "$work/board.transcript" | tr ' ' ,)
exact=$(echo "$pose" | "$tools/tse-kin" ik | awk -F, '$1 == "ok" { for (k = 3; k <= 8; ++k) printf "%.4f ", $k * 1280000 }')
s1=$(sed -n 's/^final steps: //p' "$work/sim.transcript")
s2=$(sed -n 's/^final steps: //p' "$work/board.transcript")
echo "final steps: tse-sim $s1; board $s2; exact $exact"
if echo "$s1 | $s2 | $exact" | awk -F'|' '{ n1 = split($1, a, " "); n2 = split($2, b, " "); n3 = split($3, x, " ");
     if (n1 != 6 || n2 != 6 || n3 != 6) exit 1
     for (k = 1; k <= 6; ++k) { d = a[k] - b[k]; if (d == 0) continue
       f = x[k] - int(x[k]); if (f < 0) f += 1; near = f - 0.5; if (near < 0) near = -near
       if ((d != 1 && d != -1) || near > 0.3 * 1.28) exit 1
       printf "  slide %d: %d against %d, its exact %.4f steps %.2f of a step from the rounding boundary\n", k, a[k], b[k], x[k], near }
   }'; then
  echo "ok: the final steps agree (to the rounding of positions within the float build's accuracy of a boundary)"
else
  echo "FAIL: the final steps differ beyond the float build's rounding"
  rc=1
fi
exit $rc
