#!/usr/bin/env python3
"""The two scenes of the peer cost table (tools/report/peer_cost.py): the same material, law
and step, two spheres and 10,000.

    bed_scene.py DIR [--bed-steps N] [--pair-steps N]   writes DIR/pair.json and DIR/bed-10k.json

Material and law: glass (E 63 GPa, nu 0.23, rho 2500 kg/m^3, mu 0.3, e 0.8), radius 1 mm,
Hertz-Mindlin, as benchmarks/dem_bench.cpp. Step: DT = 2.5e-7 s in both, below the step
asperity's predictor gives the bed with dt_safety 0.1 (2.6e-7 s; the free-fall speed over the
bed's height sizes it), the usual fraction of the critical step for a dense bed.

- pair: two spheres head-on at 0.1 m/s each (the contact lasts ~50 steps), then flying apart: the
  per-step overhead of each code when there is almost nothing to compute.
- bed-10k: the lattice of BM_Packing10k, 25 x 20 x 20 spheres on a simple-cubic lattice resting on
  the plane z = 0 under gravity. The scene loader refuses bodies that start overlapping, so
  neighbours start 1e-9 r apart (2 pm) instead of pressed into each other: the bottom layer meets
  the plane within a few steps and the compaction runs up the columns (asperity: ~2,900 touching
  contacts per step on average over 500 steps), and every lattice neighbour is a candidate pair
  in the neighbour lists (28,600 nearest-neighbour pairs). The run is too short for the columns to buckle, so
  every code sees the same contact set.
"""
import json
import pathlib
import sys

NX, NY, NZ = 25, 20, 20
RADIUS = 1e-3  # m
DT = 2.5e-7  # s
GAP = 1e-9  # relative to the radius
GLASS = {"density": 2500.0, "young": 6.3e10, "poisson": 0.23, "friction": 0.3, "restitution": 0.8}


def sphere(name, position, velocity=(0, 0, 0)):
    return {"name": name, "material": "glass", "shape": {"type": "sphere", "radius": RADIUS},
            "position": list(position), "velocity": list(velocity)}


def scene(name, bodies, steps, record, every, gravity=(0, 0, 0)):
    return {"name": name, "duration": steps * DT, "dt": DT, "gravity": list(gravity),
            "materials": {"glass": GLASS}, "bodies": bodies, "contact": {"law": "hertz-mindlin"},
            "record": {"force_on": record, "every": every}}


def pair(steps):
    gap = GAP * RADIUS
    bodies = [sphere("a", (0, 0, RADIUS + gap), (0, 0, -0.1)),
              sphere("b", (0, 0, -RADIUS - gap), (0, 0, 0.1))]
    return scene("pair", bodies, steps, "a", max(1, steps // 100))


def bed(steps):
    spacing = 2 * RADIUS * (1 + GAP)
    bodies = [sphere(f"s{x}_{y}_{z}", (x * spacing, y * spacing, RADIUS * (1 + GAP) + z * spacing))
              for z in range(NZ) for y in range(NY) for x in range(NX)]
    bodies.append({"name": "floor", "material": "glass",
                   "shape": {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}})
    return scene("bed-10k", bodies, steps, "floor", max(1, steps // 10), gravity=(0, 0, -9.81))


def write(out, bed_steps=500, pair_steps=1_000_000):
    """Writes both scenes into `out`; returns their paths (pair, bed)."""
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for s in (pair(pair_steps), bed(bed_steps)):
        p = out / f"{s['name']}.json"
        p.write_text(json.dumps(s) + "\n")
        paths.append(p)
    return paths


def main(argv):
    if not argv:
        print(__doc__)
        return 2
    opts = {"--bed-steps": 500, "--pair-steps": 1_000_000}
    for k in opts:
        if k in argv:
            opts[k] = int(argv[argv.index(k) + 1])
    for p in write(argv[0], opts["--bed-steps"], opts["--pair-steps"]):
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
