#!/usr/bin/python3
"""How many surface edges the contact spans at peak force, per particle and resolution, in a study
folder (asperity study --out DIR): why the geometry term of the study does not close in N.

For each particle, Hertz's contact radius at the converged peak force of the reference (the fem
limit at the finest resolution, cases.csv `answer`), on the particle's local radius of curvature
at its lowest vertex (the sphere-local case's `local_radii`, R = sqrt(R1 R2)), against the mean
edge h of the surface at each resolution:

    a = (3 F R / (4 E*))^(1/3),   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2   (Johnson 1985, eq. 4.22)

While a/h < 1 the contact at peak lies inside the fan of faces around the lowest vertex: the
particle meets the block at a faceted corner whose face angles come from the simplification, not
from the particle's curvature, and the converged answer at N is that corner's. Since h ~ N^-1/2,
a/h reaches k at N_k = N (k h / a)^2.

Usage: contact_edge_ratio.py STUDY_DIR [--csv OUT.csv]. Prints the table and the medians.
Exit 2 with one line when the folder is not a study folder with sphere-local cases.
"""
import argparse
import csv
import json
import math
import os
import statistics
import sys

from tabular import read_csv  # beside this file


def read_off_vertices_faces(path):
    with open(path) as f:
        lines = [ln.split("#")[0].strip() for ln in f]
    lines = [ln for ln in lines if ln]
    if not lines or lines[0] != "OFF":
        raise ValueError(f"{path}: not an OFF file")
    nv, nf = (int(x) for x in lines[1].split()[:2])
    v = [tuple(float(x) for x in lines[2 + i].split()[:3]) for i in range(nv)]
    fa = [tuple(int(x) for x in lines[2 + nv + i].split()[1:4]) for i in range(nf)]
    return v, fa


def mean_edge(v, faces):
    edges = {(min(a, b), max(a, b)) for f in faces for a, b in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0]))}
    return sum(math.dist(v[a], v[b]) for a, b in edges) / len(edges)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study")
    ap.add_argument("--csv")
    a = ap.parse_args()
    try:
        with open(os.path.join(a.study, "study.json")) as f:
            definition = json.load(f)
        cases = read_csv(os.path.join(a.study, "cases.csv"))
    except (OSError, ValueError) as e:
        print(f"contact_edge_ratio: {a.study}: not a study folder ({e})", file=sys.stderr)
        sys.exit(2)
    m1 = definition["material"]
    m2 = definition.get("block_material") or m1
    e_star = 1 / ((1 - m1["poisson"] ** 2) / m1["young"] + (1 - m2["poisson"] ** 2) / m2["young"])
    rows = []
    for p in dict.fromkeys(c["particle"] for c in cases):
        answers = {int(c["resolution"]): float(c["extrapolated_peak_force"]) for c in cases
                   if c["particle"] == p and c["model"] == "fem" and c["answer"] == "true"
                   and c["placement"] == "lowest" and c["extrapolated_peak_force"]}
        local = os.path.join(a.study, "cases", p, "sphere-local-lowest", "case.json")
        if not answers or not os.path.exists(local):
            continue
        with open(local) as f:
            r1, r2 = json.load(f)["local_radii"]
        if not (r1 and r2 and r1 > 0 and r2 > 0):
            continue
        reference = max(answers)
        radius = math.sqrt(r1 * r2)
        contact = (3 * answers[reference] * radius / (4 * e_star)) ** (1 / 3)
        for n in sorted(int(x) for x in os.listdir(os.path.join(a.study, "meshes", p)) if x.isdigit()):
            v, faces = read_off_vertices_faces(os.path.join(a.study, "meshes", p, str(n), "surface.off"))
            h = mean_edge(v, faces)
            rows.append({"particle": p, "resolution": n, "mean_edge": h, "local_radius": radius,
                         "contact_radius": contact, "contact_over_edge": contact / h,
                         "converged_peak_force": answers.get(n, ""),
                         "faces_for_three_edges": n * (3 * h / contact) ** 2})
    if not rows:
        print(f"contact_edge_ratio: {a.study}: no particle with a converged fem answer and a sphere-local case",
              file=sys.stderr)
        sys.exit(2)
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    print("| N | particles | a/h median | a/h max | faces for a = 3 h, median |")
    print("|---|---|---|---|---|")
    for n in sorted({r["resolution"] for r in rows}):
        here = [r for r in rows if r["resolution"] == n]
        print(f"| {n} | {len(here)} | {statistics.median([r['contact_over_edge'] for r in here]):.3g} | "
              f"{max(r['contact_over_edge'] for r in here):.3g} | "
              f"{statistics.median([r['faces_for_three_edges'] for r in here]):.3g} |")


if __name__ == "__main__":
    main()
