#!/usr/bin/env python3
"""Writes validation/cases/record/: a steel sphere striking a plane or a box, normally and
obliquely, with the force recorded on the plane or box rather than on the sphere (issue 14: the
cross-check must measure whichever body `record.force_on` names).

Cases are data: expected values come from the case loader ("hertz" is Johnson 1985 §11.4 for the
normal approach speed). Under the Hertz–Mindlin law the normal force depends on the overlap alone,
so the oblique impacts keep the normal Hertz overlap and contact duration; their force magnitude
includes the tangential force and is not gated against Hertz. Run from the repository root.
"""
import json
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2] / "validation" / "cases" / "record"
RADIUS = 0.01  # m
STEEL = {"density": 7850.0, "young": 2.1e11, "poisson": 0.30, "friction": 0.3, "restitution": 1.0}
WHY_HERTZ = ("Hertz impact, Johnson (1985) §11.4, at the normal approach speed; 0.5 % as the Hertz "
             "cases at the default auto step (integration and sampling errors ~1e-4)")
WHY_E = "elastic contact (e = 1): the 1e-3 bound of the Hertz cases"


def case(wall, oblique):
    name = f"record-on-{wall}-{'oblique' if oblique else 'normal'}"
    gap = 1e-4 * RADIUS
    ball = {"name": "ball", "material": "steel", "shape": {"type": "sphere", "radius": RADIUS},
            "position": [0, 0, RADIUS + gap], "velocity": [0.5 if oblique else 0, 0, -1.0]}
    if wall == "plane":
        target = {"name": "floor", "material": "steel",
                  "shape": {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}}
    else:
        target = {"name": "block", "material": "steel",
                  "shape": {"type": "box", "min": [-0.05, -0.05, -0.02], "max": [0.05, 0.05, 0]}}
    scene = {"name": name, "duration": 1.2e-4, "dt": "auto",
             "materials": {"steel": STEEL}, "bodies": [ball, target],
             "contact": {"law": "hertz-mindlin"},
             "record": {"force_on": target["name"], "every": 10}}
    expected = {"status": "ok"}
    quantities = ["max_overlap", "contact_duration"] + ([] if oblique else ["peak_force", "impulse"])
    for q in quantities:
        expected[q] = {"reference": "hertz", "rel_tol": 0.005, "why": WHY_HERTZ}
    expected["restitution"] = {"value": 1.0, "abs_tol": 0.001, "why": WHY_E}
    return {"case": name,
            "description": f"Steel sphere (R = 0.01 m) striking a steel {wall} at 1 m/s normal"
                           f"{' and 0.5 m/s tangential' if oblique else ''} speed, force recorded on "
                           f"the {wall}",
            "tags": ["hertz", "analytic", "record", "gate"], "scene": scene, "expected": expected}


def main():
    ROOT.mkdir(parents=True, exist_ok=True)
    for wall in ("plane", "box"):
        for oblique in (False, True):
            c = case(wall, oblique)
            (ROOT / f"{c['case']}.json").write_text(json.dumps(c, indent=2, ensure_ascii=False) + "\n")


if __name__ == "__main__":
    main()
