#!/usr/bin/env bash
# Hostile input through the real program (issue 18), one block per class of defect: every bad
# input is exit 2 with one line on stderr naming the file (or option) and the key; nothing is
# written outside --out (nor inside it); it finishes within seconds under a memory cap; an
# interrupted run or study leaves nothing that looks complete and no lock.
# Usage: hostile.sh ASPERITY_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/checks.sh"
in=$work/in    # inputs, made before each check
out=$work/o    # every --out lies under here; a bad input must leave no folder
cwd=$work/cwd  # the program's working folder: nothing may appear in it
mkdir -p "$in" "$out" "$cwd"
# Memory cap for one run (bounded memory): 2 GiB of address space. AddressSanitizer reserves
# terabytes of address space up front, so a sanitized binary runs uncapped (its own checks apply).
if ldd "$bin" 2>/dev/null | grep -q libasan; then mem_kb=unlimited; else mem_kb=$((2 * 1024 * 1024)); fi
# Seconds one bad input may take: each is refused before any work, in well under a second; the
# margin covers a loaded 2-core CI machine and the sanitizer build.
limit=20

# bad NAME PATTERN ARGS...: runs `asperity ARGS` and checks exit 2 within the limit, one line on
# stderr that matches PATTERN (grep -E) and is short, and that nothing was written: no new file in
# the inputs or the working folder and nothing under $out.
bad() {
  local name=$1 pattern=$2; shift 2
  touch "$work/stamp"
  sleep 0.01
  (cd "$cwd" && ulimit -v "$mem_kb" && timeout -k 5 "$limit" "$bin" "$@") \
    > "$work/stdout" 2> "$work/stderr"
  local rc=$?
  check "$name: exit 2 (got $rc: $(head -c 300 "$work/stderr"))" test "$rc" -eq 2
  check "$name: one line on stderr" test "$(wc -l < "$work/stderr")" -eq 1
  check "$name: message matches '$pattern' (got: $(head -c 300 "$work/stderr"))" \
    grep -qE -- "$pattern" "$work/stderr"
  check "$name: message under 700 bytes" test "$(wc -c < "$work/stderr")" -lt 700
  check "$name: nothing written (found: $(find "$in" "$cwd" -newer "$work/stamp" | head -3))" \
    test -z "$(find "$in" "$cwd" -newer "$work/stamp")"
  check "$name: nothing under --out (found: $(ls -A "$out" | head -3))" test -z "$(ls -A "$out")"
  rm -rf "${out:?}"/* "$work/escape" /tmp/asperity-hostile-escape-$$
}

# A good scene to vary: the Hertz glass sphere on a plane (validation/cases/hertz/).
case_file=$src/validation/cases/hertz/hertz-glass-sphere-plane-1ms.json
/usr/bin/python3 -c "import json,sys; print(json.dumps(json.load(open(sys.argv[1]))['scene']))" \
  "$case_file" > "$in/good.json"
# edited FROM TO PYTHON-STATEMENT: TO = the JSON file FROM changed by the statement, which sees the
# document as s (a scene) or c (a case): variant, poly_variant and case_variant write through it.
edited() {
  /usr/bin/python3 - "$1" "$2" "$3" <<'PY'
import json, sys
s = c = json.load(open(sys.argv[1]))
exec(sys.argv[3])
json.dump(s, open(sys.argv[2], "w"))
PY
}
variant() {  # variant NAME PYTHON-STATEMENT: $in/NAME.json = good.json with s changed
  edited "$in/good.json" "$in/$1.json" "$2"
}

# --- 1. Deep nesting (was SIGSEGV: the message echoed the value recursively) and huge values (a
# million-element gravity was echoed whole: 47 MB of stderr for five million)
/usr/bin/python3 -c "
import json, sys
s = json.load(open(sys.argv[1]))
text = json.dumps(s).replace('\"gravity\": [0.0, 0.0, 0.0]', '\"gravity\": ' + '[' * 100000 + ']' * 100000)
if '[[[' not in text:
    s['gravity'] = 0
    text = json.dumps(s).replace('\"gravity\": 0', '\"gravity\": ' + '[' * 100000 + ']' * 100000)
open(sys.argv[2], 'w').write(text)" "$in/good.json" "$in/deep.json"
bad "nested 100,000 deep" "deep.json:.*gravity.*nested deeper than 64" run "$in/deep.json" --out "$out/r"
printf '%s' "$(printf '{"a":%.0s' $(seq 70))" > "$in/deep2.json"
bad "nested objects" "deep2.json:.*nested deeper than 64" run "$in/deep2.json" --out "$out/r"
variant huge "s['gravity'] = [1.5] * 1000000"
bad "million-element gravity, echo cut" "huge.json: gravity: must be an array of 3 numbers \(got \[1\.5,1\.5.*\.\.\. \(" \
  run "$in/huge.json" --out "$out/r"
variant longkey "s['x' * 1000000] = 1"
bad "a 1 MB key" "longkey.json: x+\.\.\. \(1000000 characters\): unknown key" run "$in/longkey.json" --out "$out/r"
variant newlinekey "s['a\nb'] = 1"
bad "a key with a newline stays one line" 'newlinekey.json: a\\x0ab: unknown key' run "$in/newlinekey.json" --out "$out/r"

# --- 5. Numbers beyond a double, duplicate keys, integers beyond their range
sed 's/"young": [0-9.e+]*/"young": 1e400/' "$in/good.json" > "$in/young.json"
bad "young 1e400" "young.json:[0-9]+:[0-9]+: materials\.[a-z]+\.young: invalid JSON: number overflow" \
  run "$in/young.json" --out "$out/r"
sed 's/"duration": /"duration": 1, "duration": /' "$in/good.json" > "$in/dup.json"
bad "duplicate key" "dup.json:.*duration: invalid JSON: duplicate key" run "$in/dup.json" --out "$out/r"
variant every "s['record'] = {'force_on': s['bodies'][0]['name'], 'every': 18446744073709551615}"
bad "record.every 2^64-1" "every.json: record\.every: must lie in \[1, 1000000000\]" run "$in/every.json" --out "$out/r"

# --- 2 / 10. Only regular files are read: a FIFO, /dev/zero, /dev/urandom, a folder, NUL bytes
mkfifo "$in/fifo.json"
bad "FIFO scene" "fifo.json: not a regular file" run "$in/fifo.json" --out "$out/r"
bad "/dev/zero scene" "/dev/zero: not a regular file" run /dev/zero --out "$out/r"
bad "/dev/urandom scene" "/dev/urandom: not a regular file" run /dev/urandom --out "$out/r"
mkdir "$in/folder.json"
bad "a folder as scene" "folder.json: is a folder" run "$in/folder.json" --out "$out/r"
printf '\0{"name": "x"}' > "$in/nul.json"
bad "NUL-led scene" "nul.json:1:1: invalid JSON: a NUL byte" run "$in/nul.json" --out "$out/r"
truncate -s 65M "$in/big.json"
bad "65 MiB scene" "big.json: 68157440 bytes, more than the 64 MiB" run "$in/big.json" --out "$out/r"
bad "FIFO case" "fifo.json: not a regular file" validate "$in/fifo.json" --out "$out/v"
bad "/dev/zero study" "/dev/zero: not a regular file" study /dev/zero --out "$out/s"
bad "/dev/zero mesh" "/dev/zero: cannot open file \(missing or not a regular file\)" \
  mesh /dev/zero --faces 100 --out "$out/m"

# --- 10. Messages that say what is wrong
variant potential "s['contact'] = {'law': 'potential'}"
bad "potential law on spheres" "potential.json: contact\.law: \"potential\" acts between meshed bodies, and bodies\[[0-9]\] is a sphere" \
  run "$in/potential.json" --out "$out/r"
variant fast "s['bodies'][0]['velocity'] = [0, 0, -1e308]"
bad "velocity 1e308" "fast.json: bodies\[0\]\.velocity: faster than light \(got \[0,0,-1e\+308\] m/s" run "$in/fast.json" --out "$out/r"
bad "run on a validation case" "hertz-glass-sphere-plane-1ms.json: this is a validation case .*asperity validate" \
  run "$case_file" --out "$out/r"
bad "validate on a scene" "good.json: this is a scene, not a validation case.*asperity run" \
  validate "$in/good.json" --out "$out/v"
bad "unknown command" "unknown command \"bogus\"" bogus

# --- 10. The volume laws of rigid polyhedra (issue 13): volume-linear without kv or with kv <= 0 in
# run and crosscheck; friction without its tangential stiffness kt; a non-convex body and volume-hertz to the YADE cross-check (YADE's Polyhedra
# is the convex hull of its vertices; volume-hertz has no YADE law).
poly_case=$src/validation/cases/polyhedra/volume-linear-cube-face-straight.json
/usr/bin/python3 -c "
import json, os, sys
s = json.load(open(sys.argv[1]))['scene']
mesh = s['bodies'][0]['shape']
mesh['file'] = os.path.normpath(os.path.join(os.path.dirname(sys.argv[1]), mesh['file']))
json.dump(s, open(sys.argv[2], 'w'))" "$poly_case" "$in/poly.json"
poly_variant() {  # poly_variant NAME PYTHON-STATEMENT: $in/NAME.json = poly.json with s changed
  edited "$in/poly.json" "$in/$1.json" "$2"
}
poly_variant nokv "del s['contact']['kv']"
bad "volume-linear without kv" "nokv.json: contact\.kv: volume-linear needs kv" run "$in/nokv.json" --out "$out/r"
bad "volume-linear without kv, crosscheck" "nokv.json: contact\.kv: volume-linear needs kv" \
  crosscheck "$in/nokv.json" --out "$out/c"
for kv in 0 -1e11; do
  poly_variant "kv$kv" "s['contact']['kv'] = $kv"
  bad "kv = $kv" "kv$kv.json: contact\.kv: .*(positive|> 0)" run "$in/kv$kv.json" --out "$out/r"
  bad "kv = $kv, crosscheck" "kv$kv.json: contact\.kv: .*(positive|> 0)" \
    crosscheck "$in/kv$kv.json" --out "$out/c"
done
poly_variant nokt "s['contact']['friction'] = 0.3"
bad "volume-law friction without kt" "nokt.json: contact\.kt: the volume laws' friction \(contact\.friction 0\.3\) needs kt" \
  run "$in/nokt.json" --out "$out/r"
poly_variant concave "s['bodies'][0]['shape']['file'] = '$src/data/meshes/particle-seed3-320.off'"
bad "non-convex body to YADE" "concave.json: bodies\[0\] \"particle\": shape: not convex" \
  crosscheck "$in/concave.json" --out "$out/c"
poly_variant vhertz "s['contact'] = {'law': 'volume-hertz'}"
bad "volume-hertz to YADE" "vhertz.json: contact\.law: yade: .*\"volume-hertz\" has no YADE counterpart" \
  crosscheck "$in/vhertz.json" --out "$out/c"

# --- 3. Case names: a case writes into --out/cases/NAME, so NAME is a plain unique name
case_variant() {  # case_variant NAME PYTHON-STATEMENT: $in/cases/NAME.json = the Hertz case, c changed
  mkdir -p "$in/cases"
  edited "$case_file" "$in/cases/$1.json" "$2"
}
case_variant escape "c['case'] = '../../../escape'"
bad "case name ../../../escape" "escape.json: case: must not contain a path separator" validate "$in/cases/escape.json" --out "$out/v"
check "nothing escaped the output folder" test ! -e "$work/escape"
case_variant absolute "c['case'] = '/tmp/asperity-hostile-escape-$$'"
bad "absolute case name" "absolute.json: case: must not contain a path separator" validate "$in/cases/absolute.json" --out "$out/v"
check "nothing written at the absolute path" test ! -e /tmp/asperity-hostile-escape-$$
case_variant dotdot "c['case'] = '..'"
bad "case name .." "dotdot.json: case: must not be \"\.\.\"" validate "$in/cases/dotdot.json" --out "$out/v"
rm -f "$in/cases/"*
case_variant one "c['case'] = 'same'"
case_variant two "c['case'] = 'same'"
bad "two cases of one name" "two.json: case: \"same\" is also the name of .*one.json" validate "$in/cases" --out "$out/v"
rm -f "$in/cases/"*
case_variant quantity "c['expected']['peak_forse'] = {'value': 1, 'rel_tol': 0.1, 'why': 'x'}"
bad "unknown expected quantity" "quantity.json: expected\.peak_forse: not a quantity summary\.json reports \(did you mean \"peak_force\"\?\)" \
  validate "$in/cases/quantity.json" --out "$out/v"
rm -f "$in/cases/"*

# --- 5. --out naming a file, /dev/null or ""
touch "$in/afile"
bad "run --out an existing file" "--out .*afile: exists and is not a folder" run "$in/good.json" --out "$in/afile"
bad "run --out /dev/null" "--out /dev/null: exists and is not a folder" run "$in/good.json" --out /dev/null
bad "run --out \"\"" "--out \"\": must name a folder" run "$in/good.json" --out ""
bad "run --out under a file" "--out .*afile/x: .*afile is not a folder" run "$in/good.json" --out "$in/afile/x"
bad "validate --out /dev/null" "--out /dev/null: exists" validate "$case_file" --out /dev/null
bad "stability --out \"\"" "--out \"\": must name a folder" stability "$in/good.json" --out ""
bad "mesh --out a file" "--out .*afile: exists and is not a folder" \
  mesh "$src/data/meshes/particle-seed3-320.off" --faces 100 --out "$in/afile"
bad "particle --out a folder" "--out .*in: is a folder" particle --seed 1 --out "$in"

# --- 8. Strict command-line numbers
for seed in -1 18446744073709551616 99999999999999999999999 "" 1e3 0x10 " 7"; do
  bad "particle --seed '$seed'" "--seed: must be a whole number from 0 to 18446744073709551615" \
    particle --seed "$seed" --out "$out/p.off"
done
bad "mesh --quality nan" "--quality: must be a finite number" \
  mesh "$src/data/meshes/particle-seed3-320.off" --quality nan --out "$out/m"
bad "mesh --faces -5" "--faces: must be a whole number from 0 to 10000000 \(got \"-5\"\)" \
  mesh "$src/data/meshes/particle-seed3-320.off" --faces -5 --out "$out/m"
bad "mesh --scale 0" "--scale: must be a finite number > 0 " \
  mesh "$src/data/meshes/particle-seed3-320.off" --scale 0 --out "$out/m"
bad "mesh --scale inf" "--scale: must be a finite number" \
  mesh "$src/data/meshes/particle-seed3-320.off" --scale inf --out "$out/m"
bad "study --jobs -3" "--jobs: must be a whole number" study "$src/data/study/default.json" -j -3 --out "$out/s"

# --- 11. element_size (issue 11): ≤ 0, not a number, larger than the particle, or more than
# ~20 M estimated tetrahedra, in a scene and on `mesh --element-size`; the message names the
# file, the key and the value (and the estimated count where that is the problem), before any
# meshing
/usr/bin/python3 - "$src/examples/rock-drop-fem.json" "$src/data/meshes/particle-seed3-320.off" "$in" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["bodies"][0]["shape"]["file"] = sys.argv[2]
for tag, v in [("zero", 0), ("negative", -1e-3), ("string", "nan"), ("large", 10.0), ("tiny", 1e-5)]:
    s["bodies"][0]["shape"]["element_size"] = v
    json.dump(s, open(f"{sys.argv[3]}/es-{tag}.json", "w"))
PY
bad "element_size 0" "es-zero.json: bodies\[0\]\.shape\.element_size: must be > 0 \(got 0\)" \
  run "$in/es-zero.json" --out "$out/r"
bad "element_size < 0" "es-negative.json: bodies\[0\]\.shape\.element_size: must be > 0 \(got -0\.001\)" \
  run "$in/es-negative.json" --out "$out/r"
bad "element_size not a number" "es-string.json: bodies\[0\]\.shape\.element_size: must be a number \(got \"nan\"\)" \
  run "$in/es-string.json" --out "$out/r"
bad "element_size larger than the particle" "es-large.json: .*shape\.element_size: 10 m is larger than the particle \(0\.06[0-9]* m across\)" \
  run "$in/es-large.json" --out "$out/r"
bad "element_size of too many tetrahedra" "es-tiny.json: .*shape\.element_size: 1e-05 m would make about [0-9]+ M tetrahedra \(limit 20 M\)" \
  run "$in/es-tiny.json" --out "$out/r"
for v in 0 -1 nan inf; do
  bad "mesh --element-size $v" "particle-seed3-320\.off: --element-size: .*(not a positive length|larger than)" \
    mesh "$src/data/meshes/particle-seed3-320.off" --faces 100 --element-size "$v" --out "$out/m"
done
bad "mesh --element-size of too many tetrahedra" "--element-size: 1e-05 m would make about [0-9]+ M tetrahedra \(limit 20 M\)" \
  mesh "$src/data/meshes/particle-seed3-320.off" --faces 100 --element-size 1e-5 --out "$out/m"

# --- 5. Mesh headers checked against the file's size before anything is allocated
printf 'OFF\n2000000000 1 0\n0 0 0\n' > "$in/huge-header.off"
bad "OFF declaring 2e9 vertices" "huge-header.off: OFF header declares 2000000000 vertices" \
  mesh "$in/huge-header.off" --faces 100 --out "$out/m"
{ printf 'OFF\n100000000 4 0\n'; head -c 15000 /dev/zero | tr '\0' ' '; } > "$in/small-1e8.off"
bad "15 KB OFF declaring 1e8 vertices" "small-1e8.off: OFF header declares 100000000 vertices" \
  mesh "$in/small-1e8.off" --faces 100 --out "$out/m"
printf 'OFF\n-4 2 0\n' > "$in/negative.off"
bad "OFF negative count" "negative.off: OFF header: vertex and face counts must be whole numbers" \
  mesh "$in/negative.off" --faces 100 --out "$out/m"
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n' > "$in/huge.ply"
bad "PLY declaring 1e9 vertices" "huge.ply: PLY header declares 1000000000 vertices" \
  mesh "$in/huge.ply" --faces 100 --out "$out/m"
# A binary STL (84-byte header, 50 bytes per triangle) with a NaN vertex coordinate.
/usr/bin/python3 - "$in/nan.stl" <<'PY'
import struct, sys
tris = [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 0, 0), (0, 1, 0), (0, 0, 1)),
        ((0, 0, 0), (0, 0, 1), (1, 0, 0)), ((1, 0, 0), (0, 0, 1), (0, 1, float("nan")))]
with open(sys.argv[1], "wb") as f:
    f.write(b"\0" * 80 + struct.pack("<I", len(tris)))
    for t in tris:
        f.write(struct.pack("<3f", 0, 0, 0))
        for v in t:
            f.write(struct.pack("<3f", *v))
        f.write(b"\0\0")
PY
bad "binary STL with a NaN vertex" "nan.stl: 1 vertices with NaN or infinite coordinates" \
  mesh "$in/nan.stl" --faces 4 --out "$out/m"

# --- 5 / 9. Study: a bad resolution is exit 2 with nothing run; an exit 2 leaves no study.lock
/usr/bin/python3 - "$src/data/study/default.json" "$in/odd.json" "$src" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["particles"]["set"] = sys.argv[3] + "/data/particles/set.json"
s["resolutions"] = [101, 250]
json.dump(s, open(sys.argv[2], "w"))
PY
bad "study resolution 101" "odd.json: resolutions\[0\]: must be an even triangle count" study "$in/odd.json" --out "$out/s"
printf 'solid open\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid open\n' > "$in/open.stl"
printf '{"particles": {"meshes": [{"file": "open.stl"}]}, "resolutions": [100], "models": ["fem"]}' > "$in/openstudy.json"
mkdir -p "$work/s-lock"
(cd "$cwd" && timeout "$limit" "$bin" study "$in/openstudy.json" --out "$work/s-lock" -q) 2> "$work/stderr"
rc=$?
check "study of an open mesh exits 2 (got $rc: $(head -c 300 "$work/stderr"))" test "$rc" -eq 2
check "exit 2 removes study.lock" test ! -e "$work/s-lock/study.lock"

# --- 6. report on a damaged study folder: exit 2, one line, no traceback, nothing written
damaged() {  # damaged NAME SHELL-COMMAND (run inside a copy of the committed study tables)
  rm -rf "$in/study-$1"
  mkdir -p "$in/study-$1"
  cp "$src"/reports/study/*.csv "$src"/reports/study/guidelines.json "$in/study-$1/"
  cp "$src"/reports/study/study_summary.json "$in/study-$1/" 2>/dev/null ||
    printf '%s' '{}' > "$in/study-$1/study_summary.json"
  (cd "$in/study-$1" && eval "$2")
}
if [ -f "$src/reports/study/study_summary.json" ]; then
  damaged binary 'head -c 3000 /dev/urandom > cases.csv'
  bad "report: binary cases.csv" "study-binary/cases.csv: (binary content|not UTF-8)" report "$in/study-binary" --out "$out/rep"
  damaged empty ': > cases.csv'
  bad "report: empty cases.csv" "study-empty/cases.csv: empty" report "$in/study-empty" --out "$out/rep"
  damaged truncated 'head -c 2000 cases.csv > t && mv t cases.csv'
  bad "report: truncated cases.csv" "study-truncated/cases.csv: line [0-9]+: [0-9]+ fields" report "$in/study-truncated" --out "$out/rep"
  damaged cell 'sed -i "2s/,ok,[0-9.e-]*,/,ok,abc,/" cases.csv'
  bad "report: non-numeric cell" "study-cell/cases.csv: line 2: peak_force: not a number" report "$in/study-cell" --out "$out/rep"
  damaged summary 'head -c 100 study_summary.json > t && mv t study_summary.json'
  bad "report: corrupt study_summary.json" "study-summary/study_summary.json: invalid JSON" report "$in/study-summary" --out "$out/rep"
  damaged guidelines 'printf "{\"a\": [1, 2" > guidelines.json'
  bad "report: corrupt guidelines.json" "study-guidelines/guidelines.json: invalid JSON" report "$in/study-guidelines" --out "$out/rep"
fi

# ===== Round 3 (issue 31) =====
mesh320=$src/data/meshes/particle-seed3-320.off

# --- 3. --junit and every output: a regular file or a new name, checked before any work; a device,
# a FIFO, a folder (empty or not) or a path under a file is refused and left as it was. The device
# is a null device of our own (never the system's /dev/null).
mkdir -p "$in/junit-folder" "$in/junit-full/x"
mkfifo "$in/junit-fifo"
if mknod -m 666 "$in/junit-dev" c 1 3 2> /dev/null; then
  bad "validate --junit a device" "--junit .*junit-dev: is a device" \
    validate "$case_file" --out "$out/v" --junit "$in/junit-dev"
  check "the device is still a device" test -c "$in/junit-dev"
  bad "crosscheck --junit a device" "--junit .*junit-dev: is a device" \
    crosscheck "$in/good.json" --out "$out/c" --junit "$in/junit-dev"
  check "the device is still a device (crosscheck)" test -c "$in/junit-dev"
  ln -s "$in/junit-dev" "$in/junit-devlink"
  bad "validate --junit a link to a device" "--junit .*junit-devlink: is a link to a device" \
    validate "$case_file" --out "$out/v" --junit "$in/junit-devlink"
  # An output the run itself writes (run's summary.json) where a device is: refused before the run.
  mkdir -p "$work/devout" && mknod -m 666 "$work/devout/summary.json" c 1 3
  (cd "$cwd" && timeout "$limit" "$bin" run "$in/good.json" --out "$work/devout" -q) 2> "$work/stderr"
  rc=$?
  check "run --out holding a device as summary.json: exit 2 (got $rc: $(head -c 300 "$work/stderr"))" test "$rc" -eq 2
  check "run: the device named summary.json is still a device" test -c "$work/devout/summary.json"
  check "run: nothing else written beside it" test "$(ls -A "$work/devout")" = summary.json
fi
bad "validate --junit an empty folder" "--junit .*junit-folder: is a folder" \
  validate "$case_file" --out "$out/v" --junit "$in/junit-folder"
check "the empty folder is still there" test -d "$in/junit-folder"
bad "validate --junit a non-empty folder" "--junit .*junit-full: is a folder" \
  validate "$case_file" --out "$out/v" --junit "$in/junit-full"
bad "validate --junit a FIFO" "--junit .*junit-fifo: is a FIFO" \
  validate "$case_file" --out "$out/v" --junit "$in/junit-fifo"
check "the FIFO is still a FIFO" test -p "$in/junit-fifo"
bad "validate --junit under a file" "--junit .*afile/j\.xml: .*afile is not a folder" \
  validate "$case_file" --out "$out/v" --junit "$in/afile/j.xml"
bad "crosscheck --out a file" "--out .*afile: exists and is not a folder" \
  crosscheck "$in/good.json" --out "$in/afile"

# --- 9. --out: a component longer than a file name may be, a kernel file system
long=$(printf 'x%.0s' $(seq 300))
bad "--out with a 300-character component" "--out .*: a component is 300 characters, more than the 255" \
  run "$in/good.json" --out "$out/$long"
if [ "$(stat -f -c %T /sys 2> /dev/null)" = sysfs ]; then
  bad "--out under /sys" "--out /sys/asperity-out: /sys is on a virtual file system" \
    run "$in/good.json" --out /sys/asperity-out
fi

# --- 2. particle --set: each name is a plain file name (the rule of case and study names), unique;
# every entry is checked before any particle is made
set_variant() {  # set_variant NAME PYTHON-LIST-OF-PARTICLES
  printf '{"format": "off", "particles": %s}' "$2" > "$in/set-$1.json"
}
set_variant escape '[{"name": "../../escape", "seed": 1, "faces": 20}]'
bad "particle --set name ../../escape" "set-escape.json: particles\[0\]\.name: must not contain a path separator" \
  particle --set "$in/set-escape.json" --out "$out/p"
check "nothing escaped --out (particle --set)" test ! -e "$work/escape.off"
set_variant absolute "[{\"name\": \"/tmp/asperity-hostile-escape-$$\", \"seed\": 1, \"faces\": 20}]"
bad "particle --set absolute name" "set-absolute.json: particles\[0\]\.name: must not contain a path separator" \
  particle --set "$in/set-absolute.json" --out "$out/p"
check "nothing written at the absolute path (particle --set)" test ! -e "/tmp/asperity-hostile-escape-$$.off"
set_variant twice '[{"name": "a", "seed": 1, "faces": 20}, {"name": "a", "seed": 2, "faces": 20}]'
bad "particle --set duplicate names" "set-twice.json: particles\[1\]\.name: \"a\" is also the name of particles\[0\]" \
  particle --set "$in/set-twice.json" --out "$out/p"
set_variant long "[{\"name\": \"$long\", \"seed\": 1, \"faces\": 20}]"
bad "particle --set 300-character name" "set-long.json: particles\[0\]\.name: longer than 200 characters" \
  particle --set "$in/set-long.json" --out "$out/p"
set_variant empty '[]'
bad "particle --set empty list" "set-empty.json: particles: lists no particle" \
  particle --set "$in/set-empty.json" --out "$out/p"
set_variant late '[{"name": "good", "seed": 1, "faces": 20}, {"name": "bad", "seed": 2, "size": -1}]'
bad "particle --set: a bad second entry, nothing made" "set-late.json: particles\[1\]: size must lie in" \
  particle --set "$in/set-late.json" --out "$out/p"

# --- 7. particle numbers beyond their usable range: exit 2 naming the option and the range
bad "particle --size 1e300" "--size must lie in \[1e-06, 1000\] m \(got 1e\+300\)" \
  particle --seed 1 --size 1e300 --out "$out/p.off"
bad "particle --size 1e-300" "--size must lie in \[1e-06, 1000\] m" particle --seed 1 --size 1e-300 --out "$out/p.off"
bad "particle --flatness 5e-324" "--flatness must lie in \[0\.05, 1\]" \
  particle --seed 1 --flatness 5e-324 --out "$out/p.off"

# --- 1. Workers: -j beyond the tasks and cores is capped (was SIGABRT, exit 134); a thread that
# cannot start leaves the work to those that did (every thread's stack made larger than the
# address space: no thread starts but the main one)
mkdir -p "$work/jobs"
if [ "$mem_kb" = unlimited ]; then cap=unlimited; else cap=$((4 * 1024 * 1024)); fi
(cd "$cwd" && ulimit -v "$cap" && timeout 120 "$bin" validate "$case_file" --out "$work/jobs/a" -q -j 100000) \
  2> "$work/stderr"
rc=$?
check "validate -j 100000 under a 4 GiB cap: exit 0 (got $rc: $(head -c 300 "$work/stderr"))" test "$rc" -eq 0
if [ "$mem_kb" != unlimited ]; then
  (cd "$cwd" && ulimit -v $((2 * 1024 * 1024)) && ulimit -s $((3 * 1024 * 1024)) &&
    timeout 120 "$bin" validate "$src/validation/cases/hertz" --out "$work/jobs/b" -q -j 2) 2> "$work/stderr"
  rc=$?
  check "validate when no worker thread can start: exit 0 (got $rc: $(head -c 300 "$work/stderr"))" test "$rc" -eq 0
fi

# --- 8 / 11. Study: what can be known from the particles is refused before the lock and any mesh
printf '{"particles": {"meshes": [{"file": "%s"}]}, "resolutions": [100, 400], "models": ["fem"]}' \
  "$mesh320" > "$in/above.json"
bad "study resolution above the particle's triangles" \
  "above.json: resolutions\[1\]: 400 triangles is more than particle \"particle-seed3-320\" has \(320\)" \
  study "$in/above.json" --out "$out/s"
printf '{"particles": {"meshes": [{"file": "%s"}]}, "resolutions": [100, 320], "models": ["fem"], "refinement": {"sizes": [0.001], "growth": 0}}' \
  "$mesh320" > "$in/finest.json"
bad "study refinement beyond the tetrahedron limit" \
  "finest.json: refinement\.sizes\[0\]: particle \"particle-seed3-320\": .* tetrahedra \(limit 20 M\)" \
  study "$in/finest.json" --out "$out/s"
# Long set-up says so at once: a study each phase's count, mesh the estimate before TetGen starts.
printf '{"particles": {"meshes": [{"file": "%s"}]}, "resolutions": [100, 320], "models": ["fem"], "refinement": {"sizes": [0.001]}}' \
  "$mesh320" > "$in/slow.json"
"$bin" study "$in/slow.json" --out "$work/slow-study" -j 1 2> "$work/slow-study.err" &
pid=$!
"$bin" mesh "$mesh320" --element-size 0.002 --out "$work/slow-mesh" 2> "$work/slow-mesh.err" &
pid2=$!
sleep 4
kill -s INT "$pid" "$pid2"
wait "$pid" "$pid2"
sleep 1
check "an interrupted mesh leaves no TetGen process behind" \
  test -z "$(pgrep -f -- "--out $work/slow-mesh")"
check "a study says its meshes at once ($(head -c 200 "$work/slow-study.err"))" grep -q '^meshes: 2 to do' "$work/slow-study.err"
check "mesh says its estimate before TetGen ($(head -c 200 "$work/slow-mesh.err"))" \
  grep -qE 'particle-seed3-320\.off: tetrahedralizing, about [0-9.e+]+ M tetrahedra estimated \(TetGen stops at 300 s\)' "$work/slow-mesh.err"

# --- 4 / 5. Scene bounds: materials (every pair is set up before the run) and restitution (its
# damping solve never separated below 1e-10)
variant materials "s['materials'].update({'m%d' % i: {'density': 1, 'young': 1, 'poisson': 0} for i in range(2000)})"
bad "2000 materials" "materials.json: materials: 2001 materials, more than the 64" run "$in/materials.json" --out "$out/r"
variant tiny_e "s['materials'][list(s['materials'])[0]]['restitution'] = 1e-10"
bad "restitution 1e-10" "tiny_e.json: materials\.[a-z]+\.restitution: must lie in \[0\.001, 1\]" \
  run "$in/tiny_e.json" --out "$out/r"
bad "restitution 1e-10, stability" "tiny_e.json: materials\.[a-z]+\.restitution: must lie in \[0\.001, 1\]" \
  stability "$in/tiny_e.json" --out "$out/r"

# --- 12. A penalty so soft that bodies pass through each other unseen ran to status ok: bounded
# as α = p/E from 1e-6 (the soft-penalty tunnel scene, α = 2e-5, stays a runaway: exit 3)
for p in 1e-300 1e4; do
  poly_variant "pen$p" "s['contact'] = {'law': 'potential', 'penalty': $p}"
  bad "contact.penalty $p" "pen$p.json: contact\.penalty: .* Pa is .* times the largest moving body's Young's modulus .*must be 1e-06 to 1e\+06 times it" \
    run "$in/pen$p.json" --out "$out/r"
done
poly_variant alpha0 "s['contact'] = {'law': 'potential', 'penalty_alpha': 1e-300}"
bad "contact.penalty_alpha 1e-300" "alpha0.json: contact\.penalty_alpha: must lie in \[1e-06, 1e\+06\]" \
  run "$in/alpha0.json" --out "$out/r"

# --- 6. A 60 MB unknown key is refused within the limit (the suggestion was 49 s)
/usr/bin/python3 -c "
import sys
open(sys.argv[1], 'w').write('{\"' + 'k' * 60_000_000 + '\": 1}')" "$in/key60.json"
bad "a 60 MB key" "key60.json: k+\.\.\. \(60000000 characters\): unknown key" run "$in/key60.json" --out "$out/r"

# --- 9. Exit codes
case_variant negtol "c['expected']['peak_force']['rel_tol'] = -0.1"
bad "negative rel_tol" "negtol.json: expected\.peak_force\.rel_tol: must lie in \[0, " validate "$in/cases/negtol.json" --out "$out/v"
rm -f "$in/cases/"*
bad "crosscheck --max-rel-diff nan" "--max-rel-diff: must be a finite number > 0" \
  crosscheck "$in/good.json" --out "$out/c" --max-rel-diff nan
for f in nan 0 1e300 -1; do
  bad "stability --reference-factor $f" "--reference-factor: must be a finite number > 0 and <= 1" \
    stability "$in/good.json" --out "$out/r" --reference-factor "$f"
done

# --- 10. Messages that say what is wrong
bad "mesh --element-size 5e-324" "--element-size: 4\.94066e-324 m would make more than 1e308 tetrahedra \(limit 20 M\)" \
  mesh "$mesh320" --faces 100 --element-size 5e-324 --out "$out/m"
bad "mesh --element-size -1e308, short" "--element-size: -1e\+308 is not a positive length" \
  mesh "$mesh320" --faces 100 --element-size -1e308 --out "$out/m"
printf 'OFF\n4 4 0\n0 0 0\n1e200 0 0\n0 1e200 0\n0 0 1e200\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$in/far.off"
bad "mesh with huge coordinates" "far\.off: 3 vertices farther than 1e\+06 m from the origin" \
  mesh "$in/far.off" --out "$out/m"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 99999999999999999999\n' > "$in/index.obj"
bad "OBJ with a huge index" "index\.obj: line 8: face vertex index \"99999999999999999999\" is out of range \(the file has 4 vertices\)" \
  mesh "$in/index.obj" --out "$out/m"
poly_variant nofile "s['bodies'][0]['shape']['file'] = ''"
bad "mesh file \"\"" "nofile.json: bodies\[0\]\.shape\.file: must name a mesh file" run "$in/nofile.json" --out "$out/r"
variant nulkey "s['a\u0000b'] = 1"
bad "a NUL in a key" 'nulkey.json: a\\x00b: unknown key' run "$in/nulkey.json" --out "$out/r"
# A scene name is echoed escaped and cut in the success line (a terminal escape, a 1 MB name).
variant loudname "s['name'] = '\u001b[31mred' + 'x' * 1000000"
(cd "$cwd" && timeout "$limit" "$bin" run "$in/loudname.json" --out "$work/loud") > /dev/null 2> "$work/stderr"
rc=$?
check "a loud scene name runs (exit $rc)" test "$rc" -eq 0
check "its name is escaped in the success line" grep -q '^\\x1b\[31mredx*\.\.\. (1000008 characters): ok' "$work/stderr"
check "the success line is short ($(wc -c < "$work/stderr") bytes)" test "$(wc -c < "$work/stderr")" -lt 700

# --- 9. Leftovers: a failed write leaves no *.partial-PID; an interrupted run leaves nothing
# that looks complete (an earlier run's outputs in the folder go before the run starts).
mkdir -p "$work/fail/summary.json"  # a folder where the summary goes: the final rename fails
(cd "$cwd" && timeout "$limit" "$bin" run "$in/good.json" --out "$work/fail" -q) 2> /dev/null
check "failed write: no *.partial-* file" test -z "$(find "$work/fail" -name '*.partial-*')"
"$bin" run "$in/good.json" --out "$work/intr" -q
check "a first run completes" test -s "$work/intr/summary.json"
variant long "s['duration'] = 50.0; s['dt'] = 1e-7; s['allow_unsafe_dt'] = True; s['record'] = {'force_on': s['bodies'][0]['name'], 'every': 100000}"
for sig in INT TERM; do
  "$bin" run "$in/long.json" --out "$work/intr" -q 2> /dev/null &
  pid=$!
  sleep 1.5
  kill -s "$sig" "$pid"
  wait "$pid"
  rc=$?
  check "SIG$sig stops the run (exit $rc)" test "$rc" -ge 128
  check "SIG$sig: no summary.json (the earlier run's is gone)" test ! -e "$work/intr/summary.json"
  check "SIG$sig: no curves from the earlier run" test ! -e "$work/intr/force.csv"
  check "SIG$sig: no *.partial-* file" test -z "$(find "$work/intr" -name '*.partial-*')"
done
# An interrupted study removes its lock (its finished cases stay: it resumes).
/usr/bin/python3 - "$src/data/study/default.json" "$in/study-int.json" "$src" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["particles"]["set"] = sys.argv[3] + "/data/particles/set.json"
json.dump(s, open(sys.argv[2], "w"))
PY
"$bin" study "$in/study-int.json" --out "$work/study-int" -q -j 1 2> /dev/null &
pid=$!
sleep 2
check "the study holds its lock while running" test -e "$work/study-int/study.lock"
kill -s INT "$pid"
wait "$pid"
rc=$?
check "SIGINT stops the study (exit $rc)" test "$rc" -ge 128
check "SIGINT removes study.lock" test ! -e "$work/study-int/study.lock"
check "SIGINT: no study_summary.json" test ! -e "$work/study-int/study_summary.json"
check "SIGINT: no *.partial-* file" test -z "$(find "$work/study-int" -name '*.partial-*')"

report_checks
