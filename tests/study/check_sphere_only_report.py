#!/usr/bin/python3
"""A study of sphere models alone through `asperity report` (tests/study/CMakeLists.txt): every
table but cases.csv is a header without rows (there is no fem reference to measure against), and
the report must take them: exit 0, report.md and report.html written, each case's peak force
printed as cases.csv holds it.

Usage: check_sphere_only_report.py ASPERITY SPHERE_ONLY_STUDY.json WORK_DIR. Exit 0 when every
check passes; each failure is printed."""
import csv
import os
import shutil
import subprocess
import sys


def rows(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


def checks(binary, study_file, work):
    """(name, passed, detail) of every check, in order."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    study, report = os.path.join(work, "study"), os.path.join(work, "report")
    r = subprocess.run([binary, "study", study_file, "--out", study, "-q"], capture_output=True, text=True)
    yield "study exits 0", r.returncode == 0, r.stderr
    cases = rows(os.path.join(study, "cases.csv"))
    yield "4 cases", len(cases) == 5, len(cases) - 1
    for t in ("classification.csv", "references.csv", "candidates.csv"):
        yield f"{t}: a header, no rows (no fem reference)", len(rows(os.path.join(study, t))) == 1, ""
    r = subprocess.run([binary, "report", study, "--out", report], capture_output=True, text=True)
    yield "report exits 0", r.returncode == 0, r.stderr.strip()
    for name in ("report.md", "report.html", "cases.md"):
        yield f"{name} written", os.path.isfile(os.path.join(report, name)), ""
    if os.path.isfile(os.path.join(report, "cases.md")):
        with open(os.path.join(report, "cases.md")) as f:
            table = f.read()
        peak = cases[0].index("peak_force")
        for c in cases[1:]:
            yield f"{c[0]} {c[5]}: peak force {c[peak]} printed", f"| {c[peak]} |" in table, ""


failed = [(name, detail) for name, ok, detail in checks(*sys.argv[1:4]) if not ok]
for name, detail in failed:
    print(f"FAIL: {name} {detail}")
sys.exit(1 if failed else 0)
