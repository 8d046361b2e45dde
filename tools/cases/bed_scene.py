#!/usr/bin/env python3
"""The two scenes of the peer cost table (tools/report/peer_cost.py): the same material, law
and step, two spheres and 10,000.

    bed_scene.py DIR [--bed-steps N] [--pair-steps N]   writes DIR/pair.json and DIR/bed-10k.json
    bed_scene.py DIR --bed-size NX NY NZ [--bed-steps N]   writes DIR/bed-Nk.json alone, the same
        bed with NX x NY x NZ spheres (the set-up and memory scaling: 50 40 50 is 100k spheres,
        100 100 100 is 1M)
    bed_scene.py DIR --pressed [--pressed-steps N]   writes DIR/pressed-10k.json alone

Material and law: glass (E 63 GPa, nu 0.23, rho 2500 kg/m^3, mu 0.3, e 0.8), radius 1 mm,
Hertz-Mindlin, as benchmarks/dem_bench.cpp. Step: DT = 2.5e-7 s in both, below the step
asperity's predictor gives the bed with dt_safety 0.1 (2.6e-7 s; the free-fall speed over the
bed's height sizes it), the usual fraction of the critical step for a dense bed.

- pair: two spheres head-on at 0.1 m/s each (the contact lasts ~50 steps), then flying apart: the
  per-step overhead of each code when there is almost nothing to compute.
- bed-10k: the lattice of BM_Packing10k, 25 x 20 x 20 spheres on a simple-cubic lattice resting on
  the plane z = 0 under gravity, touching: neighbours start 1e-9 r apart (2 pm) instead of pressed
  into each other (that is pressed-10k, below): the bottom layer meets
  the plane within a few steps and the compaction runs up the columns (asperity: ~2,900 touching
  contacts per step on average over 500 steps), and every lattice neighbour is a candidate pair
  in the neighbour lists (28,600 nearest-neighbour pairs). The run is too short for the columns to buckle, so
  every code sees the same contact set.
- pressed-10k: the same lattice pressed, exactly BM_Packing10k's (benchmarks/dem_bench.cpp):
  centres 2 r (1 - 1e-3) apart and the bottom layer r (1 - 1e-3) above the plane, so lattice
  neighbours start overlapping by 2 um and the bottom layer the plane by 1 um (the scene says
  allow_initial_overlap) and the ~29,000 contacts persist from the first step: the contact-dense
  case, where the force loop is the cost. Its step is the benchmark's, PRESSED_DT = 1e-8 s (the
  pressed contacts' period is ~10 us; 500 steps are half of it).
"""
import json
import pathlib
import sys

NX, NY, NZ = 25, 20, 20
RADIUS = 1e-3  # m
DT = 2.5e-7  # s
GAP = 1e-9  # relative to the radius
PRESSED_DT = 1e-8  # s
PRESS = 1e-3  # starting overlap of lattice neighbours, relative to the diameter
GLASS = {"density": 2500.0, "young": 6.3e10, "poisson": 0.23, "friction": 0.3, "restitution": 0.8}


def size_name(n):
    """10k for 10,000 spheres; the count itself below a thousand (the CI smoke's 64)."""
    return f"{n // 1000}k" if n >= 1000 else str(n)


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


def bed(steps, nx=NX, ny=NY, nz=NZ):
    spacing = 2 * RADIUS * (1 + GAP)
    bodies = [sphere(f"s{x}_{y}_{z}", (x * spacing, y * spacing, RADIUS * (1 + GAP) + z * spacing))
              for z in range(nz) for y in range(ny) for x in range(nx)]
    bodies.append({"name": "floor", "material": "glass",
                   "shape": {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}})
    return scene(f"bed-{size_name(nx * ny * nz)}", bodies, steps, "floor", max(1, steps // 10),
                 gravity=(0, 0, -9.81))


def pressed(steps, nx=NX, ny=NY, nz=NZ):
    spacing = 2 * RADIUS * (1 - PRESS)
    bodies = [sphere(f"s{x}_{y}_{z}", (x * spacing, y * spacing, RADIUS * (1 - PRESS) + z * spacing))
              for z in range(nz) for y in range(ny) for x in range(nx)]
    bodies.append({"name": "floor", "material": "glass",
                   "shape": {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}})
    s = scene(f"pressed-{size_name(nx * ny * nz)}", bodies, steps, "floor", max(1, steps // 10),
              gravity=(0, 0, -9.81))
    s["duration"] = steps * PRESSED_DT
    s["dt"] = PRESSED_DT
    s["allow_initial_overlap"] = True
    return s


def write_one(out, s):
    """Writes one scene into `out` as NAME.json; returns its path."""
    p = pathlib.Path(out) / f"{s['name']}.json"
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(json.dumps(s) + "\n")
    return p


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
    opts = {"--bed-steps": 500, "--pair-steps": 1_000_000, "--pressed-steps": 500}
    for k in opts:
        if k in argv:
            opts[k] = int(argv[argv.index(k) + 1])
    if "--pressed" in argv:
        print(write_one(argv[0], pressed(opts["--pressed-steps"])))
        return 0
    if "--bed-size" in argv:
        i = argv.index("--bed-size")
        s = bed(opts["--bed-steps"], *(int(v) for v in argv[i + 1:i + 4]))
        p = pathlib.Path(argv[0]) / f"{s['name']}.json"
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(json.dumps(s) + "\n")
        print(p)
        return 0
    for p in write(argv[0], opts["--bed-steps"], opts["--pair-steps"]):
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
