#!/usr/bin/env python3
"""The sanitizer workflow builds only the targets listed in CMakePresets.json (build preset
"sanitize"). A test executable missing from that list would drop its tests silently (ctest's
placeholder for an unbuilt gtest executable has no label, so the label filter skips it). This
check reads the release build's tests (build/, where everything is built), selects them with the
sanitize test preset's filter, and fails naming every program under build/bin/ they run that the
list lacks. Usage: .ci/check_sanitize_targets.py [BUILD_DIR]"""
import json
import os
import re
import subprocess
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build")
presets = json.load(open(os.path.join(root, "CMakePresets.json")))
targets = set(next(p for p in presets["buildPresets"] if p["name"] == "sanitize")["targets"])
flt = next(p for p in presets["testPresets"] if p["name"] == "sanitize")["filter"]
include = re.compile(flt["include"]["label"])
exclude_label = re.compile(flt["exclude"]["label"])
exclude_name = re.compile(flt["exclude"].get("name", "(?!)"))

shown = subprocess.run(["ctest", "--test-dir", build, "--show-only=json-v1"], check=True,
                       capture_output=True, text=True).stdout
bin_dir = os.path.join(os.path.realpath(build), "bin") + os.sep
missing = {}
for test in json.loads(shown)["tests"]:
    props = {p["name"]: p["value"] for p in test.get("properties", [])}
    labels = props.get("LABELS", [])
    if not any(include.search(label) for label in labels):
        continue
    if any(exclude_label.search(label) for label in labels) or exclude_name.search(test["name"]):
        continue
    for arg in test.get("command", []):
        for path in re.findall(re.escape(bin_dir) + r"([\w.-]+)", os.path.realpath(arg)
                               if os.path.isabs(arg) else arg):
            if path not in targets:
                missing.setdefault(path, test["name"])
if missing:
    for exe, name in sorted(missing.items()):
        print(f"CMakePresets.json: the sanitize build preset lacks target \"{exe}\", which "
              f"{name} (and maybe others) runs", file=sys.stderr)
    sys.exit(1)
print(f"asperity CI: the sanitize preset builds every program its tests run ({len(targets)} targets)")
