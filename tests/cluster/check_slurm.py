#!/usr/bin/python3
"""The study through a real Slurm cluster on this machine gives one process's results (issue 30).

Usage: check_slurm.py ASPERITY STUDY.json SOURCE_DIR WORK_DIR MPI(ON|OFF). Starts the local cluster
(scripts/slurm/local-cluster.sh) in WORK_DIR/cluster, submits through scripts/slurm/submit.sh and
stops the cluster again. Checks, each against a one-process run of the study (same results:
study_results.py):
  1. the job array of 3 shards, then its collect job;
  2. the srun (MPI) job, 2 ranks of 1 thread (an MPI build only: said so otherwise);
  3. a shard cancelled (scancel) while it runs, its collect refusing the unfinished study, the
     shard resubmitted alone: it keeps its finished cases, and the result is equal;
  4. a partition that does not exist, and a node or size the cluster cannot give: one line,
     exit 2, nothing submitted, nothing written.
Exit 0 when every check passes, 1 on any failure (each printed), 77 (ctest: skipped) only for a
reason checked here and printed: not root, or (outside CI) Slurm or munge not installed. Under
CI=true a Slurm that is not installed is a failure: scripts/install-deps.sh installs it.
"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import time

from study_results import case_count, differing, results

binary, study_file, source, work = (os.path.abspath(a) for a in sys.argv[1:5])
mpi = sys.argv[5]
scripts = os.path.join(source, "scripts", "slurm")
cluster_dir = os.path.join(work, "cluster")
failures = []


def check(name, ok, detail=""):
    print(f"{'ok' if ok else 'FAIL'}: {name}" + ("" if ok else f" {detail}"), flush=True)
    if not ok:
        failures.append(name)


def skip(reason):
    print(f"SKIP: {reason}")
    sys.exit(77)


# Why the cluster cannot start, when the reason is one this test can check.
if os.geteuid() != 0:
    skip("the local Slurm cluster's daemons (munged, slurmctld, slurmd) run as root; this is uid "
         f"{os.geteuid()}")
missing = [p for p in ["munged", "slurmctld", "slurmd", "sbatch", "squeue", "scancel", "scontrol"]
           if shutil.which(p) is None]
if missing:
    if os.environ.get("CI") == "true":
        print(f"FAIL: {', '.join(missing)} not installed, under CI (deps/debian-packages.txt has them)")
        sys.exit(1)
    skip(f"{', '.join(missing)} not installed (deps/debian-packages.txt: slurmctld, slurmd, "
         "slurm-client, munge)")

# A cluster left running in this folder by an earlier run that was killed: its pid files go
# with the folder, so it is stopped first.
subprocess.run([os.path.join(scripts, "local-cluster.sh"), "stop", cluster_dir], capture_output=True,
               timeout=120)
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
os.environ["SLURM_CONF"] = os.path.join(cluster_dir, "slurm.conf")
os.environ["ASPERITY"] = binary
with open(study_file) as f:
    spec = json.load(f)
n_cases = case_count(spec)
shards = spec["particles"]["count"]  # one particle per shard
per_shard = n_cases // shards


# Seconds any one step may take: the study's 13 s of CPU took 130 s of wall at load 18 on the
# shared 2-core machine.
LIMIT = 400


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, cwd=work, timeout=LIMIT, **kw)


def submit(*args):
    """scripts/slurm/submit.sh ARGS: (exit code, job ids, stderr)."""
    r = run([os.path.join(scripts, "submit.sh"), *args])
    return r.returncode, r.stdout.split(), r.stderr


def job_state(job):
    """JobState and ExitCode of a job the controller still holds (no accounting on this cluster)."""
    text = run(["scontrol", "show", "job", job]).stdout
    state = re.search(r"JobState=(\S+)", text)
    code = re.search(r"ExitCode=(\S+)", text)
    return (state.group(1) if state else "gone", code.group(1) if code else "?")


def wait_gone(jobs, limit=LIMIT):
    """Waits until none of the jobs (ids, arrays included) is pending or running."""
    deadline = time.time() + limit
    while time.time() < deadline:
        q = run(["squeue", "--noheader", "--format=%i", "--jobs=" + ",".join(jobs)])
        if q.returncode == 0 and not q.stdout.strip():
            return True
        time.sleep(0.2)
    return False


def shard_cases(out, particle):
    return glob.glob(os.path.join(out, "cases", particle, "*", "case.json"))


def particles():
    """The study's particles in plan order (the set's first `count`)."""
    with open(os.path.join(os.path.dirname(study_file), spec["particles"]["set"])) as f:
        return [p["name"] for p in json.load(f)["particles"]][:shards]


def start_cluster():
    r = subprocess.run([os.path.join(scripts, "local-cluster.sh"), "start", cluster_dir],
                       capture_output=True, text=True, timeout=120)
    print(r.stdout + r.stderr, end="")
    return r.returncode == 0


def stop_cluster():
    r = subprocess.run([os.path.join(scripts, "local-cluster.sh"), "stop", cluster_dir],
                       capture_output=True, text=True, timeout=120)
    print(r.stdout + r.stderr, end="")
    left = [name for name, pid_file in [("slurmd", "slurmd.pid"), ("slurmctld", "slurmctld.pid"),
                                        ("munged", "munge/munged.pid")]
            if os.path.exists(os.path.join(cluster_dir, pid_file))]
    check("stop ends the cluster's daemons", r.returncode == 0 and not left, (r.returncode, left))


# The reference: one process, two threads.
one = os.path.join(work, "one")
r = run([binary, "study", study_file, "--out", one, "-q", "-j", "2"])
check("one process exits 0", r.returncode == 0, r.stderr)
ref = results(one)
check("every case has a summary", sum(k.endswith("summary.json") for k in ref) == n_cases, len(ref))

t0 = time.time()
if not start_cluster():
    print("FAIL: the local Slurm cluster did not start (its log above)")
    sys.exit(1)
print(f"cluster started in {time.time() - t0:.1f} s")
try:
    # 1. The job array of 3 shards (one CPU each), then the collect job.
    out = os.path.join(work, "array")
    t0 = time.time()
    code, jobs, err = submit("--array", str(shards), study_file, out, "--cpus-per-task=1")
    check("array: submitted", code == 0 and len(jobs) == 2, (code, err))
    check("array: every job ended", wait_gone(jobs))
    check("array: collect job completed", job_state(jobs[1]) == ("COMPLETED", "0:0"), job_state(jobs[1]))
    logs = glob.glob(os.path.join(out, "slurm", "asperity-shard-*.out"))
    check(f"array: {shards} shard logs in OUT/slurm", len(logs) == shards, logs)
    for p in particles():
        check(f"array: {p} has its shard's {per_shard} cases", len(shard_cases(out, p)) == per_shard)
    diff = differing(ref, results(out))
    check("array + collect: results equal one process's", not diff, diff[:5])
    print(f"array: {time.time() - t0:.1f} s wall")

    # 2. The srun job: 2 MPI ranks of 1 thread on the node.
    if mpi == "ON":
        out = os.path.join(work, "srun")
        t0 = time.time()
        code, jobs, err = submit("--srun", study_file, out, "--ntasks-per-node=2", "--cpus-per-task=1")
        check("srun: submitted", code == 0 and len(jobs) == 1, (code, err))
        check("srun: the job ended", wait_gone(jobs))
        check("srun: the job completed", job_state(jobs[0]) == ("COMPLETED", "0:0"), job_state(jobs[0]))
        log = "".join(open(p).read() for p in glob.glob(os.path.join(out, "slurm", "*.out")))
        check("srun: 2 ranks of 1 worker each", "2 ranks, 2 workers" in log, log[-2000:])
        diff = differing(ref, results(out))
        check("srun: results equal one process's", not diff, diff[:5])
        print(f"srun: {time.time() - t0:.1f} s wall")
    else:
        print("srun part not run: this asperity is built without MPI (ASPERITY_MPI=OFF)")

    # 3. Shard 2 cancelled while it runs; its collect refuses; shard 2 resubmitted alone.
    out = os.path.join(work, "cancel")
    victim = particles()[1]
    code, jobs, err = submit("--array", str(shards), study_file, out, "--cpus-per-task=1")
    check("cancel: submitted", code == 0 and len(jobs) == 2, (code, err))
    deadline = time.time() + LIMIT
    while time.time() < deadline and not shard_cases(out, victim):
        time.sleep(0.02)
    subprocess.run(["scancel", f"{jobs[0]}_2"], check=False)
    done_before = len(shard_cases(out, victim))
    check("cancel: shard 2 was cancelled mid-way (some of its cases done, not all)",
          0 < done_before < per_shard, done_before)
    check("cancel: every job ended", wait_gone(jobs))
    check("cancel: shard 2 ended as cancelled", job_state(f"{jobs[0]}_2")[0] == "CANCELLED",
          job_state(f"{jobs[0]}_2"))
    check("cancel: its collect job failed (cases missing)", job_state(jobs[1])[0] == "FAILED",
          job_state(jobs[1]))
    check("cancel: no tables from the unfinished study", not os.path.exists(os.path.join(out, "cases.csv")))
    check("cancel: the cancelled shard left no lock", not glob.glob(os.path.join(out, "*.lock*")),
          glob.glob(os.path.join(out, "*.lock*")))
    code, jobs, err = submit("--array", str(shards), "--tasks", "2", study_file, out, "--cpus-per-task=1")
    check("cancel: shard 2 resubmitted", code == 0 and len(jobs) == 2, (code, err))
    check("cancel: the resubmitted jobs ended", wait_gone(jobs))
    check("cancel: the second collect completed", job_state(jobs[1]) == ("COMPLETED", "0:0"), job_state(jobs[1]))
    log = "".join(open(p).read() for p in glob.glob(os.path.join(out, "slurm", f"asperity-shard-{jobs[0]}_2.out")))
    kept = re.search(r"(\d+) kept from before", log)
    check("cancel: the resubmitted shard kept its finished cases",
          kept is not None and int(kept.group(1)) >= done_before, (done_before, log[-1000:]))
    diff = differing(ref, results(out))
    check("cancelled, resubmitted and collected: results equal one process's", not diff, diff[:5])

    # 4. Requests the cluster cannot satisfy: one line, exit 2, nothing submitted or written.
    def refused(name, args, words):
        out = os.path.join(work, "refused")
        before = sorted(os.listdir(work))
        queued = run(["squeue", "--noheader"]).stdout
        code, jobs, err = submit(*args[:-1], study_file, out, args[-1])
        check(f"{name}: exit 2", code == 2 and not jobs, (code, jobs, err))
        check(f"{name}: one line naming it", err.count("\n") == 1 and all(w in err for w in words), err)
        check(f"{name}: nothing written", sorted(os.listdir(work)) == before, sorted(os.listdir(work)))
        check(f"{name}: nothing submitted", run(["squeue", "--noheader"]).stdout == queued)

    refused("a partition that does not exist", ["--srun", "--partition=nosuch"], ["partition", "nosuch"])
    refused("a node that does not exist", ["--array", "3", "--nodelist=ghost01"], ["node", "ghost01"])
    refused("more CPUs than the node has", ["--array", "3", "--cpus-per-task=4096"],
            ["--cpus-per-task=4096", "not available"])
finally:
    stop_cluster()

print(f"{len(failures)} failures" if failures else "all Slurm checks pass")
sys.exit(1 if failures else 0)
