"""Asserts a polyhedra cross-check's comparison.json: impulse, peak force and contact duration
within their own tolerances (validation/peer_policy.json, peers.yade.polyhedra, gives them and
their reasons; peer_gates.cmake passes them), both runs ok."""
import argparse
import json
import sys

p = argparse.ArgumentParser()
p.add_argument("comparison")
p.add_argument("--impulse", type=float, required=True)
p.add_argument("--peak", type=float, required=True)
p.add_argument("--duration", type=float, required=True)
a = p.parse_args()
with open(a.comparison) as f:
    c = json.load(f)
failed = []
if c["status"]["asperity"] != "ok" or c["status"]["yade"] != "ok":
    failed.append(f"status {c['status']}")
for key, tol in (("impulse", a.impulse), ("peak_force", a.peak), ("contact_duration", a.duration)):
    d = c[key]["rel_diff"]["yade"]
    ok = d is not None and abs(d) <= tol
    print(f"{key}: asperity {c[key]['asperity']}, YADE {c[key]['yade']}, rel diff {d} (tolerance {tol})")
    if not ok:
        failed.append(key)
if failed:
    print("FAILED: " + ", ".join(failed))
    sys.exit(1)
