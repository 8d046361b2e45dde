#!/usr/bin/env bash
# Checks the contract's exit codes and outputs by running the program as a user would.
set -u
source "$(dirname "$0")/checks.sh"
case_scene() {  # the scene of a validation case, as a scene file
  /usr/bin/python3 -c "import json,sys; print(json.dumps(json.load(open(sys.argv[1]))['scene']))" "$1"
}

# A good run: exit 0, the three files, a parseable summary with status ok.
case_scene "$src/validation/cases/hertz/hertz-glass-sphere-plane-1ms.json" > "$work/good.json"
"$bin" run "$work/good.json" --out "$work/good" -q
check "good run exits 0" test $? -eq 0
check "good run writes summary.json" test -s "$work/good/summary.json"
check "force.csv header" test "$(head -1 "$work/good/force.csv")" = "t,fx,fy,fz,f"
check "energy.csv header" test "$(head -1 "$work/good/energy.csv")" = "t,kinetic,elastic,contact,gravity,dissipated,total"
check "status ok" grep -q '"status": "ok"' "$work/good/summary.json"

# Bad input: exit 2, one line on stderr naming the file and key, no output folder.
sed 's/"radius": 0.01/"radius": -0.01/' "$work/good.json" > "$work/bad.json"
"$bin" run "$work/bad.json" --out "$work/bad" 2> "$work/bad.err"
check "negative radius exits 2" test $? -eq 2
check "one line on stderr" test "$(wc -l < "$work/bad.err")" -eq 1
check "names file and key" grep -q "bad.json: bodies\[0\].shape.radius: must be > 0" "$work/bad.err"
check "no output written" test ! -e "$work/bad"

printf '{"name": "x", "duration": 0.1,\n "bodies": [}\n' > "$work/syntax.json"
"$bin" run "$work/syntax.json" --out "$work/syntax" 2> "$work/syntax.err"
check "syntax error exits 2" test $? -eq 2
check "syntax error has line:col" grep -q "syntax.json:2:" "$work/syntax.err"

"$bin" run "$work/missing.json" --out "$work/m" 2> /dev/null
check "missing file exits 2" test $? -eq 2
"$bin" run 2> /dev/null
check "missing argument exits 2" test $? -eq 2
"$bin" frobnicate 2> /dev/null
check "unknown command exits 2" test $? -eq 2
"$bin" --help > /dev/null
check "--help exits 0" test $? -eq 0

# Unstable: a linear contact stepped at 3x its critical step with the check waived: exit 3,
# summary.json says unstable, no curves.
/usr/bin/python3 - "$work/good.json" "$work/unstable.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["contact"] = {"law": "linear", "kn": 1.0e7}
m = 2500 * 4 / 3 * 3.141592653589793 * 0.01 ** 3
s["dt"] = 3 * 2 * (m / 1.0e7) ** 0.5
s["allow_unsafe_dt"] = True
s["duration"] = 0.05
json.dump(s, open(sys.argv[2], "w"))
PY
mkdir -p "$work/unstable" && echo "stale" > "$work/unstable/force.csv"
"$bin" run "$work/unstable.json" --out "$work/unstable" -q
check "unstable exits 3" test $? -eq 3
check "unstable summary" grep -q '"status": "unstable"' "$work/unstable/summary.json"
check "no curves from an unstable run" test ! -e "$work/unstable/force.csv"

# Stability sweep: the contract's files; bad factors are bad input.
"$bin" stability "$work/good.json" --out "$work/stab" --factors 0.5,1,20 -q
check "stability exits 0" test $? -eq 0
check "stability.csv header" test "$(head -1 "$work/stab/stability.csv" | cut -d, -f1-6)" = "factor,dt,status,energy_drift,peak_force,cpu_seconds"
check "stability.csv has a row per factor" test "$(wc -l < "$work/stab/stability.csv")" -eq 4
check "stability summary keys" grep -q '"dt_stable_max_measured"' "$work/stab/summary.json"
"$bin" stability "$work/good.json" --out "$work/stab-bad" --factors 0.5,-1 2> "$work/stab.err"
check "negative factor exits 2" test $? -eq 2
check "negative factor is named" grep -q -- '--factors: "-1" is not a positive number' "$work/stab.err"
check "nothing written for bad factors" test ! -e "$work/stab-bad"
"$bin" stability "$work/good.json" --out "$work/stab-bad" --factors "" 2> /dev/null
check "empty factor list exits 2" test $? -eq 2

# A mesh scene goes through the FEM/DEM runner: the same contract, and the geometry pipeline's
# errors for a bad mesh file.
/usr/bin/python3 - "$src" "$work/mesh.json" <<'PY'
import json, sys
src, out = sys.argv[1], sys.argv[2]
case = json.load(open(f"{src}/validation/cases/stability/stability-fem-particle-block.json"))
s = case["scene"]
for b in s["bodies"]:
    if b["shape"]["type"] == "mesh":
        b["shape"]["file"] = f"{src}/data/meshes/particle-seed3-320.off"
json.dump(s, open(out, "w"))
PY
"$bin" run "$work/mesh.json" --out "$work/mesh" -q
check "mesh scene exits 0" test $? -eq 0
check "mesh scene summary" grep -q '"status": "ok"' "$work/mesh/summary.json"
check "mesh scene force rows" test "$(wc -l < "$work/mesh/force.csv")" -gt 10
printf 'solid broken\n  facet normal 0 0 1\n' > "$work/broken.stl"
sed "s#$src/data/meshes/particle-seed3-320.off#$work/broken.stl#" "$work/mesh.json" > "$work/badmesh.json"
"$bin" run "$work/badmesh.json" --out "$work/badmesh" 2> "$work/badmesh.err"
check "bad mesh file exits 2" test $? -eq 2
check "bad mesh names the file" grep -q "broken.stl" "$work/badmesh.err"
check "nothing written for a bad mesh" test ! -e "$work/badmesh"

# advise: a bad mesh, a tolerance of 0 or below, a budget too small for one reference: one line,
# exit 2, nothing written.
"$bin" advise "$work/broken.stl" --tolerance 5% --out "$work/advise-bad" 2> "$work/advise.err"
check "advise: bad mesh exits 2" test $? -eq 2
check "advise: bad mesh is one line naming the file" \
  test "$(wc -l < "$work/advise.err")" -eq 1 -a -n "$(grep broken.stl "$work/advise.err")"
check "advise: nothing written for a bad mesh" test ! -e "$work/advise-bad"
for tol in 0 -5% 0%; do  # --tolerance=: a value starting with - is not an option
  "$bin" advise "$src/data/meshes/particle-seed3-320.off" --tolerance="$tol" \
    --out "$work/advise-tol" 2> "$work/advise.err"
  check "advise: tolerance $tol exits 2" test $? -eq 2
  check "advise: tolerance $tol is named" grep -q -- "--tolerance" "$work/advise.err"
done
check "advise: nothing written for a bad tolerance" test ! -e "$work/advise-tol"
"$bin" advise "$src/data/meshes/particle-seed3-320.off" --budget 0.001 \
  --out "$work/advise-budget" 2> "$work/advise.err"
check "advise: a budget below one reference exits 2" test $? -eq 2
check "advise: the budget is named on one line" \
  test "$(wc -l < "$work/advise.err")" -eq 1 -a -n "$(grep -- --budget "$work/advise.err")"
check "advise: nothing written for a small budget" test ! -e "$work/advise-budget"

report_checks
