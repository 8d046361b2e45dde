#!/usr/bin/python3
"""The study over MPI ranks and shards gives the same results as one process (issue 16).

Usage: check_mpi.py ASPERITY MPIRUN SMOKE_STUDY.json CASES_DIR WORK_DIR. Exit 0 when every check passes;
each failure is printed. Same results: study_results.py.
"""
import csv
import glob
import json
import os
import shutil
import signal
import subprocess
import sys
import time

from study_results import case_count, differing, results, timing

binary, mpirun, study_file, cases_dir, work = sys.argv[1:6]
# --oversubscribe: more ranks than this machine's cores; --allow-run-as-root: CI runs as root.
MPI = [mpirun, "--oversubscribe", "--allow-run-as-root"]
failures = []


def check(name, ok, detail=""):
    if not ok:
        failures.append(name)
        print(f"FAIL: {name} {detail}")


def study(out, *extra, ranks=None):
    cmd = [binary, "study", study_file, "--out", out, "-q", *extra]
    if ranks:
        cmd = MPI + ["-n", str(ranks)] + cmd
    return subprocess.run(cmd, capture_output=True, text=True, timeout=300)


def same(name, a, b):
    differ = differing(a, b)
    check(name, not differ and len(a) > 3, f"differ: {differ[:5]}")


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
with open(study_file) as f:
    spec = json.load(f)
n_cases = case_count(spec)

# 1. The reference: one process, two threads.
one = os.path.join(work, "one")
r = study(one, "-j", "2")
check("one process exits 0", r.returncode == 0, r.stderr)
ref = results(one)
check("every case has a summary", sum(k.endswith("summary.json") for k in ref) == n_cases, len(ref))

# 2. Two and four ranks (one thread each; four ranks on two cores) give the same results.
for ranks in [2, 4]:
    out = os.path.join(work, f"ranks{ranks}")
    t0 = time.time()
    r = study(out, "-j", "1", ranks=ranks)
    check(f"mpirun -n {ranks} exits 0", r.returncode == 0, r.stderr[-2000:])
    same(f"mpirun -n {ranks} results equal one process's", ref, results(out))
    with open(os.path.join(out, "study_summary.json")) as f:
        last = json.load(f)["last_run"]
    check(f"mpirun -n {ranks} ran every case", last["ran"] == n_cases and last["failed"] == 0, last)
    print(f"mpirun -n {ranks}: {time.time() - t0:.1f} s wall")

# 3. A launch killed mid-way, resumed with another rank count, ends with the same results.
out = os.path.join(work, "killed")
p = subprocess.Popen(MPI + ["-n", "2", binary, "study", study_file, "--out", out, "-q", "-j", "1"],
                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
deadline = time.time() + 120
while time.time() < deadline and len(glob.glob(os.path.join(out, "cases", "*", "*", "case.json"))) < 3:
    time.sleep(0.05)
os.killpg(p.pid, signal.SIGKILL)
p.wait()
# mpirun may have put its ranks in process groups of their own (Open MPI does, on some machines):
# they outlive the kill of mpirun's group and hold the folder's lock. Kill every process still
# working in this folder and wait until none is left, as a user who pressed Ctrl-C twice would.
def working_here():
    pids = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                if out.encode() in f.read():
                    pids.append(int(pid))
        except OSError:
            pass
    return pids
deadline = time.time() + 60
while working_here() and time.time() < deadline:
    for pid in working_here():
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
    time.sleep(0.1)
check("the killed launch's ranks are gone", not working_here(), working_here())
finished = len(glob.glob(os.path.join(out, "cases", "*", "*", "case.json")))
check("the killed launch had finished some cases, not all", 0 < finished < n_cases, finished)
r = study(out, "-j", "1", ranks=3)
check("resumed with 3 ranks exits 0", r.returncode == 0, r.stderr[-2000:])
with open(os.path.join(out, "study_summary.json")) as f:
    last = json.load(f)["last_run"]
check("the resumed launch keeps the finished cases", last["kept"] >= finished and last["ran"] + last["kept"] == n_cases, (finished, last))
same("killed and resumed: results equal one process's", ref, results(out))

# 4. Two shards in sequence, then --collect, equal one run; the shards' cases are disjoint.
out = os.path.join(work, "shards")
r = study(out, "--shard", "1/2", "-j", "2")
check("shard 1/2 exits 0", r.returncode == 0, r.stderr)
first = set(glob.glob(os.path.join(out, "cases", "*", "*", "case.json")))
check("shard 1/2 writes no tables", not os.path.exists(os.path.join(out, "cases.csv")))
r = subprocess.run([binary, "study", study_file, "--out", out, "--collect", "-q"], capture_output=True, text=True)
check("--collect with shard 2/2 not run: exit 1, saying how many cases have not run, no table",
      r.returncode == 1 and f"{n_cases // 2} of {n_cases} cases" in r.stderr and
      not os.path.exists(os.path.join(out, "cases.csv")), (r.returncode, r.stderr))
r = study(out, "--shard", "2/2", "-j", "2")
check("shard 2/2 exits 0", r.returncode == 0, r.stderr)
both = set(glob.glob(os.path.join(out, "cases", "*", "*", "case.json")))
check("each shard half the cases, disjoint", len(first) == n_cases // 2 and len(both) == n_cases, (len(first), len(both)))
r = subprocess.run([binary, "study", study_file, "--out", out, "--collect", "-q"], capture_output=True, text=True)
check("--collect exits 0", r.returncode == 0, r.stderr)
same("two shards collected: results equal one run's", ref, results(out))

# 5. Bad input: exit 2, one line naming the problem, nothing written.
def bad(name, args, words, folder):
    before = sorted(os.listdir(folder)) if os.path.exists(folder) else None
    r = subprocess.run([binary, "study", *args], capture_output=True, text=True)
    check(f"{name}: exit 2", r.returncode == 2, (r.returncode, r.stderr))
    check(f"{name}: one line naming it", r.stderr.count("\n") == 1 and all(w in r.stderr for w in words), r.stderr)
    after = sorted(os.listdir(folder)) if os.path.exists(folder) else None
    check(f"{name}: nothing written", before == after)


bad("--shard 3/2", [study_file, "--out", os.path.join(work, "bad"), "--shard", "3/2"], ["--shard", "3/2"], os.path.join(work, "bad"))
bad("--shard 0/0", [study_file, "--out", os.path.join(work, "bad"), "--shard", "0/0"], ["--shard", "0/0"], os.path.join(work, "bad"))
other = os.path.join(work, "other.json")
spec["resolutions"] = [100, 500]
if "refinement" in spec:  # its resolutions must be the study's (else refused before the folder is read)
    spec["refinement"]["resolutions"] = [500]
spec["particles"]["set"] = os.path.join(os.path.dirname(os.path.abspath(study_file)), spec["particles"]["set"])
spec["name"] = "smoke"
with open(other, "w") as f:
    json.dump(spec, f)
bad("another study's folder", [other, "--out", one], ["study.json", "resolutions", "500"], one)
same("the refused run left the folder's results alone", ref, results(one))

# 6. validate over two ranks: the same checks, in the same order, as one process.
def validation_results(folder):
    with open(os.path.join(folder, "results.csv"), newline="") as f:
        rows = list(csv.reader(f))
    keep = [i for i, name in enumerate(rows[0]) if not timing(name)]
    with open(os.path.join(folder, "validation.json")) as f:
        checks = json.load(f)["results"]
    return [[r[i] for i in keep] for r in rows], checks


v1, v2 = os.path.join(work, "validate1"), os.path.join(work, "validate2")
r1 = subprocess.run([binary, "validate", cases_dir, "--out", v1, "-q"], capture_output=True, text=True)
r2 = subprocess.run(MPI + ["-n", "2", binary, "validate", cases_dir, "--out", v2, "-q"], capture_output=True, text=True)
check("validate exits 0, alone and over 2 ranks", r1.returncode == 0 and r2.returncode == 0, (r1.stderr, r2.stderr[-2000:]))
a, b = validation_results(v1), validation_results(v2)
check("validate over 2 ranks: the same checks", a == b and len(a[1]) > 1, (len(a[1]), len(b[1])))

print(f"{len(failures)} failures" if failures else "all MPI checks pass")
sys.exit(1 if failures else 0)
