#!/usr/bin/python3
"""How many surface edges the contact spans at peak force, per particle and resolution, in a study
folder (asperity study --out DIR): why the geometry term of the study does not close in N.

For each particle, Hertz's contact radius a at the converged peak force of the reference, on the
particle's local radius of curvature at its lowest vertex, against the mean edge h of the surface
at each resolution; a/h reaches k at N_k = N (k h / a)^2. build/bin/contact_edge_ratio
(study/contact_edge_ratio.cpp, where the formulas and their source stand) computes the rows and
the medians; this script only prints them.

Usage: contact_edge_ratio.py STUDY.json STUDY_DIR [--csv OUT.csv] [--program PATH] (the
definition the folder was run from, as `asperity study --collect` takes it). Prints the table of
the medians. Exit 2 with one line when the folder is not that study's folder with sphere-local
cases.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

from tabular import num, read_csv  # beside this file

PROGRAM = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "bin",
                       "contact_edge_ratio")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("definition")
    ap.add_argument("study")
    ap.add_argument("--csv")
    ap.add_argument("--program", default=PROGRAM, help="build/bin/contact_edge_ratio (the C++ that "
                    "computes the rows and the medians)")
    a = ap.parse_args()
    if not os.access(a.program, os.X_OK):
        sys.exit(f"{a.program}: not built (cmake --build build --target contact_edge_ratio); it "
                 "computes the table")
    with tempfile.TemporaryDirectory() as d:
        rows, summary = os.path.join(d, "rows.csv"), os.path.join(d, "summary.csv")
        code = subprocess.run([a.program, a.definition, a.study, rows, summary]).returncode
        if code:
            sys.exit(code)
        if a.csv:
            shutil.copyfile(rows, a.csv)
        medians = read_csv(summary)
    print("| N | particles | a/h median | a/h max | faces for a = 3 h, median |")
    print("|---|---|---|---|---|")
    for r in medians:
        print(f"| {r['resolution']} | {r['particles']} | {num(r['contact_over_edge_median']):.3g} | "
              f"{num(r['contact_over_edge_max']):.3g} | {num(r['faces_for_three_edges_median']):.3g} |")


if __name__ == "__main__":
    main()
