# Runs an asperity sphere scene in YADE: `yade -n -x scene_to_yade.py INPUT.json OUTDIR`.
#
# The YADE adapter (peers/yade.cpp) writes INPUT.json (the scene as asperity resolved
# it: materials, bodies, law, dt, step count, the damping of each material pair) and reads back
# what this script writes:
#   OUTDIR/raw.csv   every step: t, YADE's total contact force on the recorded body (whichever body
#                    it is: sphere, plane or box), then x,y,z,vx,vy,vz of each free sphere in scene
#                    order; the adapter measures overlap, contact times and rebound from these with
#                    the code that measures asperity's runs
#   OUTDIR/raw.json  final angular velocities, CPU seconds of a run without the per-step recorder,
#                    the stiffness each contact got, YADE's version
# With "cost_only" in INPUT.json it makes the plain run alone and writes raw.json with its CPU and
# wall seconds and YADE's version (the cost table: no recorder, nothing per step).
# On any error it writes OUTDIR/error.txt and exits with status 2.
#
# The mapping (docs/crosscheck.md explains each choice):
#   hertz-mindlin, hertz  -> Ip2_FrictMat_FrictMat_MindlinPhys + Law2_ScGeom_MindlinPhys_Mindlin
#                            (hertz: friction 0, so the shear force is capped at zero)
#   linear (elastic)      -> Ip2_FrictMat_FrictMat_FrictPhys(kn, ks) + Law2_ScGeom_FrictPhys_CundallStrack
#   plane (axis-aligned)  -> Wall with Ig2_Wall_Sphere_ScGeom(hertzian=True): R* = r (not r/2)
#   box                   -> Box with Ig2_Box_Sphere_ScGeom (R = r/2 there; see yade_box_material)
# Ip2_FrictMat_FrictMat_MindlinPhys (2023.02a, measured) computes the true Hertz E* and Mindlin G*
# from the two materials and R from the geometry functor's radii, once, at contact creation. The
# default Wall functor gives R = r/2; hertzian=True gives the wall 1e8 r, so R* = r (1 - 1e-8).
# The box functor has no such switch, so each box gets a YADE material that compensates R = r/2.
# The viscous damping uses YADE's linear-in-velocity betan/betas form, which equals asperity's
# Tsuji form zeta sqrt(m* K) delta^(1/4) when betan = betas = zeta / sqrt(6).
import json
import math
import os
import sys
import time
import traceback

import yade.config
from yade import O, utils
from yade.wrapper import (Bo1_Box_Aabb, Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, FrictMat,
                          Ig2_Box_Sphere_ScGeom, Ig2_Sphere_Sphere_ScGeom, Ig2_Wall_Sphere_ScGeom,
                          InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys,
                          Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                          Law2_ScGeom_MindlinPhys_Mindlin, MatchMaker, NewtonIntegrator, PyRunner)

# The scripts beside this one (peer_files.py, yade_polyhedra.py): yade -x sets argv[0] to it.
sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
from peer_files import write_atomically, write_json  # noqa: E402


class MappingError(Exception):
    pass


def shear_modulus(m):
    return m["young"] / (2 * (1 + m["poisson"]))


def e_star(a, b):
    return 1 / ((1 - a["poisson"] ** 2) / a["young"] + (1 - b["poisson"] ** 2) / b["young"])


def g_star(a, b):
    return 1 / ((2 - a["poisson"]) / shear_modulus(a) + (2 - b["poisson"]) / shear_modulus(b))


def yade_box_material(sphere, box):
    """Young's modulus and Poisson ratio to give a fixed box in YADE so that, against `sphere`,
    Ip2_FrictMat_FrictMat_MindlinPhys computes kno = 4/3 E* sqrt(r) and kso = 8 G* sqrt(r) with the
    true Hertz E* and Mindlin G* of the pair, although Ig2_Box_Sphere_ScGeom hands it R = r/2.

    YADE 2023.02a (measured): kno = 4/3 E_y sqrt(R), 1/E_y = (1-vs^2)/Es + (1-vb^2)/Eb, and
    kso = 8 G_y sqrt(R), 1/G_y = (2-vs)/Gs + (2-vb)/Gb. With q = sqrt(r / R) = sqrt(2) we need
    E_y = q E*, G_y = q G*: two compliances cE = (1-vb^2)/Eb and cG = (2-vb)/Gb = 2(2-vb)(1+vb)/Eb,
    whose ratio fixes vb = (4 - rho)/(2 - rho), rho = cG/cE. The pair need not be a physical
    material (Eb < 0 for a rigid box): it only feeds YADE's two formulas, and the recorder checks
    the stiffness YADE computed."""
    q = math.sqrt(2.0)
    es, gs, vs = sphere["young"], shear_modulus(sphere), sphere["poisson"]
    c_e = 1 / (q * e_star(sphere, box)) - (1 - vs * vs) / es
    c_g = 1 / (q * g_star(sphere, box)) - (2 - vs) / gs
    rho = c_g / c_e
    vb = (4 - rho) / (2 - rho)
    eb = (1 - vb * vb) / c_e
    if not (math.isfinite(eb) and eb != 0 and abs(1 + vb) > 1e-12):
        raise MappingError("no YADE box material reproduces this sphere-box stiffness")
    return eb, vb


def axis_of(normal):
    for ax in range(3):
        if abs(abs(normal[ax]) - 1) < 1e-12 and all(abs(normal[k]) < 1e-12 for k in range(3) if k != ax):
            return ax, (1 if normal[ax] > 0 else -1)
    return None, None


def build(spec, record):
    """Builds the YADE scene; returns the recorder state (or None)."""
    O.reset()
    law = spec["law"]
    mats = spec["materials"]
    names = list(mats)
    bodies = spec["bodies"]
    spheres = [b for b in bodies if b["shape"]["type"] == "sphere"]
    walls = [b for b in bodies if b["shape"]["type"] in ("plane", "box")]
    for b in bodies:
        if b["shape"]["type"] not in ("sphere", "plane", "box"):
            raise MappingError(f"body \"{b['name']}\": shape {b['shape']['type']} has no YADE counterpart here")
    friction = spec.get("friction_override")

    def friction_angle(m):
        mu = friction if friction is not None else mats[m]["friction"]
        return math.atan(mu)

    # Sphere materials: as given. Each wall gets one YADE copy per sphere material that may touch
    # it, with collision masks so that a sphere meets only its own copy.
    sphere_mats = sorted({b["material"] for b in spheres}, key=names.index)
    if len(sphere_mats) > 29:
        raise MappingError("more than 29 sphere materials with walls: too many collision-mask bits")
    mat_id = {}
    for m in sphere_mats:
        mm = mats[m]
        mat_id[m] = O.materials.append(FrictMat(young=mm["young"], poisson=mm["poisson"], density=mm["density"],
                                                frictionAngle=friction_angle(m), label="s_" + m))
    for m in names:
        if m not in mat_id and any(b["material"] == m for b in spheres):
            raise MappingError("internal: sphere material missing")
    zeta = {(p["a"], p["b"]): p["zeta"] for p in spec["pairs"]}
    zeta.update({(p["b"], p["a"]): p["zeta"] for p in spec["pairs"]})

    ids = {}     # scene body name -> YADE id (a wall's first copy)
    owner = {}   # YADE id -> scene body
    mindlin = law in ("hertz-mindlin", "hertz")
    wall_copies = []  # (yade material id, sphere material, wall material) for the damping table
    for b in spheres:
        s = b["shape"]
        mask = 1 | (1 << (1 + sphere_mats.index(b["material"])))
        bid = O.bodies.append(utils.sphere(b["position"], s["radius"], material=mat_id[b["material"]],
                                           fixed=b["fixed"], mask=mask))
        st = O.bodies[bid].state
        st.vel = b["velocity"]
        st.angVel = b["angular_velocity"]
        ids[b["name"]] = bid
        owner[bid] = b
    for b in walls:
        s = b["shape"]
        wm = mats[b["material"]]
        for k, m in enumerate(sphere_mats):
            ew, vw = wm["young"], wm["poisson"]
            if s["type"] == "plane":
                ax, sense = axis_of(s["normal"])
                if ax is None:
                    raise MappingError(f"body \"{b['name']}\": YADE's Wall is axis-aligned; the plane normal {s['normal']} is not")
            elif mindlin:
                ew, vw = yade_box_material(mats[m], wm)
            mid = O.materials.append(FrictMat(young=ew, poisson=vw, density=wm["density"],
                                              frictionAngle=friction_angle(b["material"]), label=f"w_{b['name']}_{m}"))
            wall_copies.append((mid, m, b["material"]))
            mask = 1 << (1 + k)
            if s["type"] == "plane":
                body = utils.wall(s["point"][ax], axis=ax, sense=sense, material=mid, mask=mask)
            else:
                lo, hi = s["min"], s["max"]
                body = utils.box([(lo[i] + hi[i]) / 2 for i in range(3)], [(hi[i] - lo[i]) / 2 for i in range(3)],
                                 fixed=True, material=mid, mask=mask)
            bid = O.bodies.append(body)
            ids.setdefault(b["name"], bid)
            owner[bid] = b

    # Damping per YADE material pair: betan = betas = zeta / sqrt(6) (see the header).
    matches = []
    for a in sphere_mats:
        for c in sphere_mats:
            if mat_id[a] <= mat_id[c]:
                matches.append((mat_id[a], mat_id[c], zeta[(a, c)] / math.sqrt(6)))
    for mid, m, w in wall_copies:
        matches.append((mat_id[m], mid, zeta[(m, w)] / math.sqrt(6)))
    any_damping = any(v != 0 for _, _, v in matches)

    if mindlin:
        if any_damping:
            ip2 = Ip2_FrictMat_FrictMat_MindlinPhys(betan=MatchMaker(matches=matches), betas=MatchMaker(matches=matches))
        else:
            ip2 = Ip2_FrictMat_FrictMat_MindlinPhys()
        law2 = Law2_ScGeom_MindlinPhys_Mindlin()
    elif law == "linear":
        if any_damping:
            raise MappingError("linear law with restitution < 1: YADE's Law2_ScGeom_FrictPhys_CundallStrack has no "
                               "viscous damping, so there is no faithful mapping (use restitution 1)")
        ip2 = Ip2_FrictMat_FrictMat_FrictPhys(kn=MatchMaker(algo="val", val=spec["kn"]), ks=MatchMaker(algo="val", val=spec["kt"]))
        law2 = Law2_ScGeom_FrictPhys_CundallStrack()
    else:
        raise MappingError(f"contact law {law} has no YADE counterpart here")

    engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb(), Bo1_Box_Aabb()]),
        # Relative velocity at the contact point (not the anti-ratcheting branch), as asperity does.
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom(avoidGranularRatcheting=False),
                         Ig2_Wall_Sphere_ScGeom(hertzian=True, noRatch=False), Ig2_Box_Sphere_ScGeom()],
                        [ip2], [law2]),
    ]
    rec = None
    if record:
        rec = Recorder(spec, ids, owner, mats, law)
        engines.append(PyRunner(command="RECORDER.step()", iterPeriod=1, initRun=True))
    engines.append(NewtonIntegrator(gravity=spec["gravity"], damping=0))
    O.engines = engines
    O.dt = spec["dt"]
    return rec


class Recorder:
    """Per step, after the interaction loop (forces at the current positions): the recorded body's
    total contact force and every free sphere's position and velocity."""

    def __init__(self, spec, ids, owner, mats, law):
        self.spec, self.ids, self.owner, self.law, self.mats = spec, ids, owner, law, mats
        rec_name = spec["record_body"]
        # A wall has one YADE copy per sphere material (see build): its force is their sum.
        self.rec_ids = [bid for bid, b in owner.items() if b["name"] == rec_name]
        self.free = [ids[b["name"]] for b in spec["bodies"]
                     if b["shape"]["type"] == "sphere" and not b["fixed"]]
        self.stiffness = {}
        self.n_interactions = -1
        self.out = None  # raw.csv, streamed: long runs must not hold every row in memory

    def check_stiffness(self):
        """The stiffness YADE gave each new contact of the recorded body, against asperity's
        4/3 E* sqrt(R*) and 8 G* sqrt(R*) (R* = r for a plane or box)."""
        n = O.interactions.countReal()
        if n == self.n_interactions:
            return
        self.n_interactions = n
        for rid in self.rec_ids:
            for i in O.interactions.withBody(rid):
                if not i.isReal or (i.id1, i.id2) in self.stiffness:
                    continue
                a, b = self.owner[i.id1], self.owner[i.id2]
                if a["shape"]["type"] != "sphere":
                    a, b = b, a
                ma, mb = self.mats[a["material"]], self.mats[b["material"]]
                r_eff = a["shape"]["radius"]
                if b["shape"]["type"] == "sphere":
                    r_eff = r_eff * b["shape"]["radius"] / (r_eff + b["shape"]["radius"])
                if self.law == "linear":
                    got = {"kn": i.phys.kn, "ks": i.phys.ks}
                    want = {"kn": self.spec["kn"], "ks": self.spec["kt"]}
                else:
                    got = {"kno": i.phys.kno, "kso": i.phys.kso}
                    want = {"kno": 4 / 3 * e_star(ma, mb) * math.sqrt(r_eff),
                            "kso": 8 * g_star(ma, mb) * math.sqrt(r_eff)}
                self.stiffness[(i.id1, i.id2)] = {
                    "partner": b["name"] if a["name"] == self.spec["record_body"] else a["name"],
                    "yade": got, "asperity": want,
                    "rel_diff": max(abs(got[k] - want[k]) / abs(want[k]) for k in want if want[k] != 0)
                    if any(want.values()) else 0.0}

    def step(self):
        fx = fy = fz = 0.0
        for rid in self.rec_ids:
            f = O.forces.f(rid, sync=True)
            fx, fy, fz = fx + f[0], fy + f[1], fz + f[2]
        cols = [O.time, fx, fy, fz]
        for bid in self.free:
            st = O.bodies[bid].state
            cols += [st.pos[0], st.pos[1], st.pos[2], st.vel[0], st.vel[1], st.vel[2]]
        self.check_stiffness()
        self.out.write(",".join(repr(c) for c in cols) + "\n")


def main():
    spec_file, out = sys.argv[1], sys.argv[2]
    with open(spec_file) as fh:
        spec = json.load(fh)
    if spec["law"] == "volume-linear":
        # Rigid polyhedra: their own translator beside this file (yade_polyhedra.py).
        import yade_polyhedra
        yade_polyhedra.run(spec, out)
        return
    steps = int(spec["steps"])

    # 1. Cost: the plain engine list, no Python in the loop.
    build(spec, record=False)
    t0, w0 = time.process_time(), time.perf_counter()
    if steps > 0:  # a cost run of 0 steps times the set-up alone (YADE reads nSteps <= 0 as "no limit")
        O.run(steps, True)
    cpu, wall = time.process_time() - t0, time.perf_counter() - w0

    if spec.get("cost_only"):
        # The cost table (tools/report/peer_cost.py): the plain run alone.
        raw = {"yade_version": yade.config.version, "steps": steps, "dt": O.dt, "cpu_seconds": cpu,
               "wall_seconds": wall}
        write_json(os.path.join(out, "raw.json"), raw)
        return

    # 2. The force history: the same scene with a recorder after the interaction loop. One extra
    #    iteration gives the row at t = steps * dt (forces at the final positions), as asperity's.
    rec = build(spec, record=True)
    globals()["RECORDER"] = rec
    def record(fh):
        names = [b["name"] for b in spec["bodies"] if b["shape"]["type"] == "sphere" and not b["fixed"]]
        fh.write("t,fx,fy,fz" + "".join(f",{b}.x,{b}.y,{b}.z,{b}.vx,{b}.vy,{b}.vz" for b in names) + "\n")
        rec.out = fh
        O.run(steps + 1, True)
    write_atomically(os.path.join(out, "raw.csv"), record)
    final = {}
    for b in spec["bodies"]:
        st = O.bodies[rec.ids[b["name"]]].state
        final[b["name"]] = {"velocity": list(st.vel), "angular_velocity": list(st.angVel)}
    raw = {
        "yade_version": yade.config.version,
        "steps": steps,
        "dt": O.dt,
        "cpu_seconds": cpu,
        "wall_seconds": wall,
        "final": final,
        "stiffness": list(rec.stiffness.values()),
    }
    write_json(os.path.join(out, "raw.json"), raw)


try:
    main()
except Exception as e:  # noqa: BLE001 - every failure must reach asperity with its text
    out = sys.argv[2] if len(sys.argv) > 2 else "."
    msg = f"{type(e).__name__}: {e}"
    try:
        with open(os.path.join(out, "error.txt"), "w") as fh:
            fh.write(msg + "\n" + traceback.format_exc())
    finally:
        sys.stderr.write("scene_to_yade: " + msg + "\n")
        sys.stderr.flush()
        os._exit(2)
