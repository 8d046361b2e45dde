#!/usr/bin/env bash
# ParaView series of whole runs (`asperity run --vtk-every N`), checked with VTK's own readers:
# a sphere scene and a deformable and a rigid rock from examples/. Also: frames change no result,
# bad --vtk-every and an unwritable folder are exit 2, and a killed run's run.pvd lists only
# frames that exist.
set -u
bin=$1
src=$(cd "$2" && pwd)
py=/usr/bin/python3  # Debian's python3-vtk9 lives there
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
fail() { echo "FAIL: $*"; failed=1; }

# Summaries without their timing keys (cpu, wall, profile): what must not change.
strip() {
  "$py" -c 'import json,sys
s = json.load(open(sys.argv[1]))
for k in ("cpu_seconds", "wall_seconds", "profile"): s.pop(k, None)
print(json.dumps(s, sort_keys=True))' "$1"
}

for ex in glass-sphere-on-plate rock-drop-fem rock-drop-rigid; do
  scene="$src/examples/$ex.json"
  "$bin" run "$scene" --out "$work/$ex-plain" -q || fail "$ex: run without frames"
  "$bin" run "$scene" --out "$work/$ex" -q --vtk-every 100 || fail "$ex: run with frames"
  [ "$(strip "$work/$ex-plain/summary.json")" = "$(strip "$work/$ex/summary.json")" ] ||
    fail "$ex: summary.json differs with frames"
  cmp -s "$work/$ex-plain/force.csv" "$work/$ex/force.csv" || fail "$ex: force.csv differs"
  "$py" "$src/tests/io/check_vtk_series.py" "$work/$ex" "$scene" || fail "$ex: series check"
done

# ASCII frames: the same check, and the same numbers as base64 (both round-trip the doubles).
ex=rock-drop-fem
"$bin" run "$src/examples/$ex.json" --out "$work/ascii" -q --vtk-every 100 --vtk-ascii ||
  fail "ascii run"
"$py" "$src/tests/io/check_vtk_series.py" "$work/ascii" "$src/examples/$ex.json" || fail "ascii"
grep -q 'format="ascii"' "$work/ascii/vtk/bodies_000001.vtu" || fail "ascii: not ascii"
"$py" - "$work/ascii/vtk/bodies_000001.vtu" "$work/$ex/vtk/bodies_000001.vtu" <<'PY' || fail "ascii and base64 frames differ"
import sys, vtk
from vtk.util.numpy_support import vtk_to_numpy
def read(f):
    r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(f); r.Update(); return r.GetOutput()
a, b = read(sys.argv[1]), read(sys.argv[2])
for name in ("displacement", "velocity", "contact_force"):
    if not (vtk_to_numpy(a.GetPointData().GetArray(name)) == vtk_to_numpy(b.GetPointData().GetArray(name))).all():
        sys.exit(1)
PY

# Bad input: exit 2, one line, no output folder.
for bad in 0 -5; do
  "$bin" run "$src/examples/glass-sphere-on-plate.json" --out "$work/bad$bad" --vtk-every "$bad" \
    2> "$work/bad.err"
  [ $? -eq 2 ] || fail "--vtk-every $bad: not exit 2"
  [ "$(wc -l < "$work/bad.err")" -eq 1 ] || fail "--vtk-every $bad: not one line"
  [ ! -e "$work/bad$bad" ] || fail "--vtk-every $bad: wrote $work/bad$bad"
done
sed 's/"record"/"output": {"vtk_every": 0}, "record"/' "$src/examples/glass-sphere-on-plate.json" \
  > "$work/zero.json"
"$bin" run "$work/zero.json" --out "$work/zero" 2> "$work/zero.err"
[ $? -eq 2 ] || fail "output.vtk_every 0: not exit 2"
grep -q "zero.json: output.vtk_every" "$work/zero.err" || fail "output.vtk_every 0: message"
touch "$work/afile" # a file where a folder of the output path should be
"$bin" run "$src/examples/glass-sphere-on-plate.json" --out "$work/afile/run" --vtk-every 10 \
  2> "$work/ro.err"
[ $? -eq 2 ] || fail "unwritable frame folder: not exit 2"
[ "$(wc -l < "$work/ro.err")" -eq 1 ] || fail "unwritable frame folder: not one line"

# The scene key alone writes frames.
sed 's/"record"/"output": {"vtk_every": 500}, "record"/' "$src/examples/glass-sphere-on-plate.json" \
  > "$work/key.json"
"$bin" run "$work/key.json" --out "$work/key" -q && [ -s "$work/key/vtk/run.pvd" ] ||
  fail "output.vtk_every: no run.pvd"

# Killed mid-run: run.pvd lists only whole frames (a frame is renamed into place before the
# collection that lists it). Killed at several moments; every listed file must load.
for delay in 0.3 0.6 1.0; do
  "$bin" run "$src/examples/sphere-packing-box.json" --out "$work/killed" -q --vtk-every 200 &
  pid=$!
  sleep "$delay"
  kill -9 "$pid" 2> /dev/null
  wait "$pid" 2> /dev/null
  if [ -e "$work/killed/vtk/run.pvd" ]; then
    "$py" - "$work/killed/vtk" <<'PY' || fail "killed after $delay s: run.pvd lists a frame that is not whole"
import os, re, sys, vtk
d = sys.argv[1]
files = re.findall(r'file="([^"]+)"', open(os.path.join(d, "run.pvd")).read())
for f in files:
    r = vtk.vtkXMLGenericDataObjectReader()
    r.SetFileName(os.path.join(d, f)); r.Update()
    if r.GetOutput() is None or r.GetOutput().GetNumberOfPoints() == 0:
        sys.exit(1)
PY
  fi
done

exit $failed
