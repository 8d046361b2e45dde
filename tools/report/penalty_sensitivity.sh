#!/usr/bin/env bash
# Runs the penalty-sensitivity studies (data/study/penalty-a*.json: the same impacts at Munjiza
# penalties α = 10, 100, 1000) into build/ and writes reports/study/penalty/ from them; its
# summary per α by build/bin/penalty_summary (cmake --build build --target penalty_summary).
# Usage: tools/report/penalty_sensitivity.sh [path/to/asperity]   (resumable: finished cases kept)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
bin="${1:-$root/build/bin/asperity}"
dirs=()
for a in 10 100 1000; do
  out="$root/build/study-penalty-a$a"
  "$bin" study "$root/data/study/penalty-a$a.json" --out "$out"
  dirs+=("$out")
done
/usr/bin/python3 "$root/tools/report/penalty_sensitivity.py" --out "$root/reports/study/penalty" "${dirs[@]}"
