#!/usr/bin/env python3
"""Writes the 10,000-sphere scene of the peer cost table (validation/report/peer_cost.py).

    bed_scene.py OUT.json [--steps N]

The lattice of benchmarks/dem_bench.cpp (BM_Packing10k): 25 x 20 x 20 glass spheres of radius
1 mm on a simple-cubic lattice, resting on the plane z = 0 under gravity, one material, the
Hertz-Mindlin law with e = 0.8 and mu = 0.3. The scene loader refuses bodies that start
overlapping, so neighbours start 1e-9 r apart (2 nm) instead of pressed 0.1 % into each other:
gravity closes every vertical gap within the first few hundred steps, so most of the run has
every sphere in contact with the one below and the one above (~10,000 contacts), and every
horizontal neighbour a candidate pair in the neighbour lists (~20,000 more). A settled bed is
what a DEM code spends most of its time on; a run this short leaves no time for the columns to
buckle, so all codes see the same contact set.

The step is asperity's "auto" step; `duration` is N times the step asperity resolves for this
scene (`asperity run` prints it), so every code runs N steps.
"""
import json
import math
import sys

NX, NY, NZ = 25, 20, 20
RADIUS = 1e-3  # m
GLASS = {"density": 2500.0, "young": 6.3e10, "poisson": 0.23, "friction": 0.3, "restitution": 0.8}


def bed(steps, dt):
    """The scene for `steps` steps of `dt` (asperity's resolved auto step)."""
    spacing = 2 * RADIUS * (1 + 1e-9)
    bodies = []
    for z in range(NZ):
        for y in range(NY):
            for x in range(NX):
                bodies.append({"name": f"s{x}_{y}_{z}", "material": "glass",
                               "shape": {"type": "sphere", "radius": RADIUS},
                               "position": [x * spacing, y * spacing, RADIUS * (1 + 1e-9) + z * spacing]})
    bodies.append({"name": "floor", "material": "glass",
                   "shape": {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}})
    return {"name": "bed-10k", "duration": steps * dt, "dt": "auto", "dt_safety": 0.1, "gravity": [0, 0, -9.81],
            "materials": {"glass": GLASS}, "bodies": bodies,
            "contact": {"law": "hertz-mindlin"},
            "record": {"force_on": "floor", "every": 1000}}
