#!/usr/bin/env bash
# Runs every libFuzzer target for SECONDS each under ASan + UBSan, two at a time (the CI machine has
# 2 cores), each from its committed seed corpus (tests/fuzz/corpus/NAME/) into a scratch corpus, so
# the source tree is never written. A crash, a leak, a sanitizer report, a 10 s input or 2 GB of
# memory fails the run; the reproducer is kept under OUT (default build-fuzz/findings/).
# Usage: tests/fuzz/run.sh [BUILD_DIR] [SECONDS] [OUT]
set -u
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build-fuzz}
seconds=${2:-60}
findings=${3:-$build/findings}
mkdir -p "$findings"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run_one() {  # run_one TARGET CORPUS-NAME
  local t=$1 c=$2
  mkdir -p "$work/$t"
  "$build/bin/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$findings/$t-" "$work/$t" "$here/corpus/$c" > "$findings/$t.log" 2>&1
  local rc=$?
  local runs
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$findings/$t.log" | grep -o '[0-9]*$')
  echo "fuzz $t: exit $rc, ${runs:-?} inputs in ${seconds} s"
  [ "$rc" -eq 0 ] || { tail -30 "$findings/$t.log"; return 1; }
}
status=0
pairs=("fuzz_scene scene" "fuzz_study study" "fuzz_case case" "fuzz_mesh_stl stl"
       "fuzz_mesh_obj obj" "fuzz_mesh_ply ply" "fuzz_mesh_off off")
for ((i = 0; i < ${#pairs[@]}; i += 2)); do
  run_one ${pairs[i]} & a=$!
  if ((i + 1 < ${#pairs[@]})); then
    run_one ${pairs[i + 1]} & b=$!
    wait $b || status=1
  fi
  wait $a || status=1
done
exit $status
