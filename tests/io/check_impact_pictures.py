#!/usr/bin/python3
"""The report's Hertz picture (tools/report/impact_pictures.py) from a real run's frames:
the files are pictures, and the numbers they draw hold.

usage: check_impact_pictures.py ASPERITY SOURCE_DIR WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

asperity, src, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
failed = []


def check(what, ok, detail=""):
    if not ok:
        failed.append(what)
        print(f"FAIL: {what} {detail}")


script = os.path.join(src, "tools", "report", "impact_pictures.py")
scene = os.path.join(src, "tools", "report", "scenes", "hertz-fem-sphere-block.json")
r = subprocess.run(["/usr/bin/python3", script, "--asperity", asperity, "--hertz", scene, "--hertz-out", work],
                   capture_output=True, text=True)
check("exit 0", r.returncode == 0, r.stderr)
if r.returncode == 0:
    with open(os.path.join(work, "hertz_contact_zone.png"), "rb") as fh:
        check("PNG signature", fh.read(8) == b"\x89PNG\r\n\x1a\n")
    check("SVG parses", ET.parse(os.path.join(work, "hertz_contact_zone.svg")).getroot().tag.endswith("svg"))
    with open(os.path.join(work, "hertz_contact_zone.json")) as fh:
        n = json.load(fh)
    # The frame drawn is the peak: its nodal contact forces add up to the run's peak force
    # (force.csv's sum of the same forces) to round-off, 1e-9 relative.
    check("peak frame's nodal forces add up to the peak force",
          abs(n["nodal_force_resultant"] / n["peak_force"] - 1) < 1e-9,
          f"{n['nodal_force_resultant']} against {n['peak_force']}")
    # The pressure drawn is each node's |contact force| over its area share, so the picture carries
    # the whole load: frictionless on a flat face, the nodal forces are normal to it up to the
    # potential's lean across element faces, so the magnitudes exceed the resultant by < 1e-4.
    check("pressure drawn carries the peak force",
          0 <= n["nodal_force_sum"] / n["nodal_force_resultant"] - 1 < 1e-4,
          f"{n['nodal_force_sum']} against {n['nodal_force_resultant']}")
    # The loaded patch against Hertz's contact radius at that force: a mesh resolves a patch edge to
    # a node spacing, so the farthest loaded node lies within one surface edge of a.
    a, h = n["contact_radius_hertz"], n["longest_edge_near_contact"]
    check("loaded patch within one edge of Hertz a", abs(n["patch_radius"] - a) <= h,
          f"patch {n['patch_radius']}, a {a}, edge {h}")
    # The peak pressure drawn is the Hertz p0 at that force within the mesh's reach: a node
    # spacing of order a (a/h about 1.4 here) leaves a factor, not a percentage: between 0.5 and 2.
    check("peak nodal pressure within a factor 2 of Hertz p0", 0.5 < n["max_pressure"] / n["p0_hertz"] < 2,
          f"{n['max_pressure']} against {n['p0_hertz']}")
if failed:
    sys.exit(1)
shutil.rmtree(work, ignore_errors=True)
print("impact pictures: ok")
