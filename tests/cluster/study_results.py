"""A study folder's results with the timing fields dropped, for the checks that a study run
elsewhere (over MPI ranks, in shards, through Slurm) equals one process's (check_mpi.py,
check_slurm.py). Same results means: every case's summary.json and the tables cases.csv,
classification.csv and particle_classes.csv equal, byte for byte, once the timing fields are
dropped (CPU and wall seconds, the profile): they are measurements of the machine, not results.
"""
import csv
import glob
import io
import json
import os


def timing(key):
    return "cpu" in key or "wall" in key or key == "profile"


def results(folder):
    """Every result of a study folder with the timing fields dropped: {name: text}."""
    out = {}
    for table in ["cases.csv", "classification.csv", "particle_classes.csv"]:
        path = os.path.join(folder, table)
        if not os.path.exists(path):
            out[table] = None
            continue
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
        keep = [i for i, name in enumerate(rows[0]) if not timing(name)]
        buf = io.StringIO()
        csv.writer(buf).writerows([[r[i] for i in keep] for r in rows])
        out[table] = buf.getvalue()
    for path in sorted(glob.glob(os.path.join(folder, "cases", "*", "*", "summary.json"))):
        with open(path) as f:
            summary = json.load(f)
        for key in [k for k in summary if timing(k)]:
            del summary[key]
        out[os.path.relpath(path, folder)] = json.dumps(summary, sort_keys=True)
    return out


def differing(a, b):
    """The names whose results differ between two results() (or exist in one only)."""
    return sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k))


def case_count(spec):
    """The number of cases a study definition (parsed JSON) plans."""
    # the spheres ("sphere", "sphere-local") have no resolution: one case per particle and placement
    meshed = [m for m in spec["models"] if m not in ("sphere", "sphere-local")]
    n = spec["particles"]["count"] * (len(spec["resolutions"]) * len(meshed) + len(spec["models"]) -
                                      len(meshed)) * len(spec["placements"])
    # fem's refined element sizes (issue 12): a case per size, refined resolution and placement
    ref = spec.get("refinement", {})
    n += spec["particles"]["count"] * len(ref.get("sizes", [])) * \
        len(ref.get("resolutions", spec["resolutions"])) * len(ref.get("placements", spec["placements"]))
    return n
