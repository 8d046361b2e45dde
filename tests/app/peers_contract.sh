#!/usr/bin/env bash
# The peer adapters and the external-solver gate through the program's contract (issue 14):
# exit 2 for usage (unknown or uninstalled peer, a scene a peer cannot express, a --solver-cmd
# without {scene} and {out}) with nothing written, exit 1 for a peer or solver that fails, JUnit
# with readable messages, the example solver (exact passes the Hertz cases, x1.05 fails them), and
# the gates' policy through `crosscheck --list`.
# Needs the Debian packages yade, lammps, liggghts and calculix-ccx (deps/debian-packages.txt).
set -u
source "$(dirname "$0")/checks.sh"
lines() { wc -l < "$1"; }
plane=$src/validation/cases/record/record-on-plane-normal.json
box=$src/validation/cases/record/record-on-box-oblique.json
mesh=$src/validation/cases/stability/stability-rigid-particle-block.json
fem=$src/validation/cases/stability/stability-fem-particle-block.json
solver="python3 $src/peers/example_solver/hertz_solver.py"

# Usage errors: exit 2, one line naming the peer and the reason, nothing written.
"$bin" crosscheck "$plane" --out "$work/u1" --peer nosuch 2> "$work/u1.err"
check "unknown peer exits 2" test $? -eq 2
check "unknown peer: one line naming the known ones" grep -q "nosuch: unknown peer (known: yade, lammps, liggghts, calculix)" "$work/u1.err"
check "unknown peer: nothing written" test ! -e "$work/u1"
"$bin" crosscheck "$plane" --out "$work/u2" --peer lammps --lammps /nonexistent/lmp 2> "$work/u2.err"
check "uninstalled peer exits 2" test $? -eq 2
check "uninstalled peer names its package" grep -q "lammps: not installed .*Debian package lammps" "$work/u2.err"
check "uninstalled peer: nothing written" test ! -e "$work/u2"
"$bin" crosscheck "$mesh" --out "$work/u3" --peer lammps 2> "$work/u3.err"
check "mesh body for lammps exits 2" test $? -eq 2
check "mesh body: names file, body and reason" grep -q "stability-rigid-particle-block.json: bodies\[0\] .*shape: lammps: a mesh body has no counterpart" "$work/u3.err"
check "mesh body: one line" test "$(lines "$work/u3.err")" -eq 1
check "mesh body: nothing written" test ! -e "$work/u3"
"$bin" crosscheck "$box" --out "$work/u4" --peer yade,liggghts 2> "$work/u4.err"
check "box for liggghts exits 2 before yade runs" test $? -eq 2
check "box: nothing written" test ! -e "$work/u4"
"$bin" crosscheck "$mesh" --out "$work/u7" --peer calculix 2> "$work/u7.err"
check "rigid particle for calculix exits 2" test $? -eq 2
check "rigid particle: names the body and calculix's reason" grep -q "stability-rigid-particle-block.json: bodies\[0\] .*calculix: one moving fem body" "$work/u7.err"
check "rigid particle for calculix: nothing written" test ! -e "$work/u7"
"$bin" crosscheck "$fem" --out "$work/u8" --peer calculix 2> "$work/u8.err"
check "fem rock for calculix exits 2" test $? -eq 2
check "fem rock: one line naming calculix's reason" grep -q "bodies\[0\] .*calculix: " "$work/u8.err"
check "fem rock: one line" test "$(lines "$work/u8.err")" -eq 1
"$bin" validate "$src/validation/cases/hertz" --out "$work/u5" --solver-cmd "$solver" 2> "$work/u5.err"
check "--solver-cmd without {scene} {out} exits 2" test $? -eq 2
check "--solver-cmd: nothing written" test ! -e "$work/u5"
"$bin" validate "$mesh" --out "$work/u6" --solver lammps 2> "$work/u6.err"
check "a sweep for --solver exits 2" test $? -eq 2

# The gates' policy (validation/peer_policy.json) through `crosscheck --list`: every gate carries
# its why; a policy entry without one, a peer without a policy, is exit 2 with one line naming it.
"$bin" crosscheck --list --peer yade,lammps,liggghts > "$work/list.txt" 2> "$work/list.err"
check "--list exits 0" test $? -eq 0
check "--list: a header line per peer" test "$(grep -c '^# ' "$work/list.txt")" -eq 3
check "--list: every gate has six fields, the last its why" \
  awk -F '\t' '!/^#/ && (NF != 6 || $6 == "") { exit 1 }' "$work/list.txt"
check "--list: the box cases are lammps's refusals" \
  grep -qP "^refused\trecord\.record-on-box-oblique\t.*\tlammps\tshape: lammps: a box is not mapped\t" \
  "$work/list.txt"
python3 - "$src/validation/peer_policy.json" "$work/nowhy.json" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
p["peers"]["lammps"]["rules"][0]["why"] = ""
json.dump(p, open(sys.argv[2], "w"))
PY
"$bin" crosscheck --list --peer lammps --policy "$work/nowhy.json" > /dev/null 2> "$work/nowhy.err"
check "a rule without its why exits 2" test $? -eq 2
check "a rule without its why: one line naming the key" \
  grep -q "nowhy.json: peers.lammps.rules\[0\].why: must give the reason" "$work/nowhy.err"
"$bin" crosscheck --list --peer calculix > /dev/null 2> "$work/nopolicy.err"
check "a peer without a policy exits 2" test $? -eq 2
check "a peer without a policy: one line" test "$(lines "$work/nopolicy.err")" -eq 1

# A peer that runs and fails is a tool failure: exit 1, its reason on one line.
"$bin" crosscheck "$plane" --out "$work/f1" --yade /bin/false 2> "$work/f1.err"
check "--yade /bin/false exits 1" test $? -eq 1
check "--yade /bin/false: one line" test "$(lines "$work/f1.err")" -eq 1
check "--yade /bin/false: yade failed" grep -q "yade failed (exit 1)" "$work/f1.err"

# Force recorded on the plane: all three peers agree with asperity; JUnit per peer and quantity.
"$bin" crosscheck "$plane" --out "$work/c1" --peer yade,lammps,liggghts --max-rel-diff 1e-6 \
  --junit "$work/c1.xml" --quiet
check "plane-recorded cross-check with three peers exits 0" test $? -eq 0
check "three peer folders" test -s "$work/c1/yade/summary.json" -a -s "$work/c1/lammps/force.csv" -a -s "$work/c1/liggghts/summary.json"
check "JUnit: 12 testcases, no failure" grep -q 'tests="12" failures="0" errors="0"' "$work/c1.xml"

# One atom type for spheres of one material (the single-type path the 10,000-sphere cost scene
# needs): two glass spheres are one LAMMPS and one LIGGGHTS type, and the elastic impact still
# agrees with asperity to round-off (measured <= 3e-14; 1e-9 leaves room for the platform only).
pair=$src/validation/cases/hertz/hertz-glass-sphere-sphere-1ms.json
"$bin" crosscheck "$pair" --out "$work/t1" --peer lammps,liggghts --max-rel-diff 1e-9 --quiet
check "one-type sphere pair agrees with lammps and liggghts to 1e-9" test $? -eq 0
check "lammps: 2 atoms, 1 atom type" grep -qx "1 atom types" "$work/t1/lammps/atoms.data"
check "liggghts: 2 atoms, 1 atom type" grep -qx "1 atom types" "$work/t1/liggghts/atoms.data"

# --cost-only: each code's plain run, nothing recorded per step, DIR/cost.json.
"$bin" crosscheck "$plane" --out "$work/k0" --cost-only --max-rel-diff 0.1 2> "$work/k0.err"
check "--cost-only with --max-rel-diff exits 2" test $? -eq 2
check "--cost-only with --max-rel-diff: nothing written" test ! -e "$work/k0"
"$bin" crosscheck "$plane" --out "$work/k1" --peer yade,lammps,liggghts --cost-only --quiet
check "--cost-only with three peers exits 0" test $? -eq 0
check "--cost-only: no trace written" test ! -e "$work/k1/yade/raw.csv" -a ! -e "$work/k1/lammps/trace.dump" -a ! -e "$work/k1/liggghts/trace.dump"
check "--cost-only: four codes, each with its steps' CPU" python3 -c "
import json, sys
c = json.load(open(sys.argv[1]))
codes = c['codes']
assert sorted(codes) == ['asperity', 'lammps', 'liggghts', 'yade'], codes
for k, v in codes.items():
    assert v['run_cpu_seconds'] > 0, (k, v)
    assert abs(v['cpu_per_step_per_particle'] * c['steps'] * c['particles'] - v['step_cpu_seconds']) <= 1e-12, k
    if k == 'asperity' or v['step_cpu_from'] == \"the peer's loop CPU clock\":
        assert v['step_cpu_seconds'] == v['loop_cpu_seconds'] >= 0, (k, v)
    else:  # the difference of two processes: may be below zero for a run this short (531 steps)
        assert abs(v['step_cpu_seconds'] - (v['run_cpu_seconds'] - v['setup_cpu_seconds'])) <= 1e-9, (k, v)
" "$work/k1/cost.json"

# The example external solver: exact passes the 24 Hertz cases, x1.05 fails them readably.
"$bin" validate "$src/validation/cases/hertz" --out "$work/s1" -q --junit "$work/s1.xml" \
  --solver-cmd "$solver {scene} {out}"
check "exact example solver passes the Hertz cases" test $? -eq 0
check "JUnit: no failure" grep -q 'failures="0" errors="0"' "$work/s1.xml"
"$bin" validate "$src/validation/cases/hertz" --out "$work/s2" -q --junit "$work/s2.xml" \
  --solver-cmd "$solver {scene} {out} --force-scale 1.05"
check "x1.05 example solver fails" test $? -eq 1
check "JUnit: 24 peak-force failures" test "$(grep -c '<testcase classname="[^"]*" name="peak_force"[^/]*>' "$work/s2.xml")" -eq 24
check "JUnit: readable message" grep -q 'failure message="peak_force: got [0-9.e+-]*, expected [0-9.e+-]* (hertz), rel error 0.019[0-9]*, tolerance 0.005 rel"' "$work/s2.xml"

# A solver that fails, or writes no summary.json: the case fails (JUnit <error>), exit 1.
"$bin" validate "$plane" --out "$work/s3" -q --junit "$work/s3.xml" --solver-cmd "false {scene} {out}" 2> "$work/s3.err"
check "failing solver exits 1" test $? -eq 1
check "failing solver: one line" grep -q "solver-cmd: exited 1 on record-on-plane-normal" "$work/s3.err"
check "failing solver: JUnit error" grep -q '<error message="--solver-cmd: exited 1' "$work/s3.xml"
"$bin" validate "$plane" --out "$work/s4" -q --solver-cmd "true {scene} {out}" 2> "$work/s4.err"
check "silent solver exits 1" test $? -eq 1
check "silent solver: no summary.json named" grep -q "wrote no summary.json for record-on-plane-normal" "$work/s4.err"

report_checks
