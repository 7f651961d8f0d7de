#!/usr/bin/env bash
# Offline kinematics: set up, build tse-kin, and run it on a demo trajectory
# (a helix rising through the workspace with the plate tilting), showing the slides it commands,
# then the design figures of the paper beside ours.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cmake --preset host >/dev/null
cmake --build --preset host --target tse-kin -j "$(nproc 2>/dev/null || echo 2)" >/dev/null
K=build/host/host_tools/tse-kin

echo "=== inverse kinematics along a helix (X, Y, Z in m; roll, pitch in rad) -> slides in mm"
awk 'BEGIN { n = 24; for (i = 0; i <= n; ++i) { t = i / n; a = 6.2831853 * t;
        printf "%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", 0.15 * cos(a), 0.15 * sin(a), 0.5 + 0.9 * t, 0.05 * sin(a), 0.05 * cos(a), 0.1 * t } }' >build/demo_poses.csv
"$K" ik <build/demo_poses.csv >build/demo_slides.csv
paste -d, build/demo_poses.csv build/demo_slides.csv | awk -F, '
  BEGIN { printf "%5s  %7s %7s %6s %6s %6s | %-6s %7s %7s %7s %7s %7s %7s\n", "step", "X", "Y", "Z", "roll", "pitch", "status", "sA1", "sB1", "sA2", "sB2", "sA3", "sB3" }
  { printf "%5d  %7.3f %7.3f %6.3f %6.3f %6.3f | %-6s", NR, $1, $2, $3, $4, $5, $7;
    for (i = 9; i <= 14; ++i) printf " %7.1f", $i * 1000; printf "\n" }'
echo
echo "=== forward kinematics of the last slides (seeded with the home pose): the pose comes back"
tail -1 build/demo_slides.csv | cut -d, -f3- | "$K" fk
echo
echo "=== design figures (kinematics.md): vertical gear ratio and HAF, workspace on the paper's grid"
"$K" haf | tail -2
"$K" workspace | tail -2
