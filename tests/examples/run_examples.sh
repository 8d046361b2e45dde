#!/usr/bin/env bash
# Runs every scene in examples/ as a newcomer would (`asperity run`): each must finish with exit 0
# and status "ok", and every top-level key of its summary.json must be documented in
# docs/scenes.md (the output half of the reference; the scene keys have their own test).
set -u
bin=$1
src=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
count=0
for scene in "$src"/examples/*.json; do
  name=$(basename "$scene" .json)
  count=$((count + 1))
  "$bin" run "$scene" --out "$work/$name" -q
  rc=$?
  if [ $rc -ne 0 ]; then echo "FAIL: $name: exit $rc"; failed=1; continue; fi
  grep -q '"status": "ok"' "$work/$name/summary.json" || { echo "FAIL: $name: status not ok"; failed=1; }
  grep -q "\`$name.json\`" "$src/examples/README.md" || { echo "FAIL: $name: not in examples/README.md"; failed=1; }
  /usr/bin/python3 - "$work/$name/summary.json" "$src/docs/scenes.md" <<'PY' || failed=1
import json, re, sys
doc = open(sys.argv[2]).read()
section = doc[doc.index("### `summary.json`"):]
section = section[:section.index("\n### ", 1)]
documented = set(re.findall(r"`([a-z_]+)`", section))
missing = [k for k in json.load(open(sys.argv[1])) if k not in documented]
if missing:
    print(f"FAIL: {sys.argv[1]}: summary keys not in docs/scenes.md: {missing}")
    sys.exit(1)
PY
done
[ $count -ge 5 ] || { echo "FAIL: only $count examples"; failed=1; }
exit $failed
