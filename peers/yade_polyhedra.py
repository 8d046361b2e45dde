# The polyhedra path of the YADE cross-check: rigid convex polyhedra under the volumetric law
# (asperity's contact.law "volume-linear"), run by `yade -n -x`.
#
# run(spec, outdir) reads the input `asperity crosscheck` writes for a volume-linear scene:
#   law "volume-linear", kv (N/m³), gravity, dt, steps, record_body, materials, and bodies, each
#   {name, material, fixed, vertices (world frame, m), velocity, angular_velocity}
# (planes and boxes arrive as the vertices of the slab or box asperity collides with), and writes
# the files the YADE adapter (peers/yade.cpp) reads: OUTDIR/raw.csv (per step
# t,fx,fy,fz,s,nx,ny,nz, then x,y,z,vx,vy,vz of each free body in scene order) and OUTDIR/raw.json
# (final motions, CPU seconds of a run without the recorder, the stiffness YADE used, the CPU time
# of each kind of step).
#
# The mapping (docs/crosscheck.md):
#   body       -> yade.polyhedra_utils.polyhedra(material, v=vertices): YADE takes the convex hull
#                 (CGAL), its mass, centroid and principal inertia from it; asperity refuses a
#                 non-convex body before YADE runs (exit 2), so the hulls are the bodies.
#   law        -> Ig2_Polyhedra_Polyhedra_PolyhedraGeom + Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys
#                 + Law2_PolyhedraGeom_PolyhedraPhys_Volumetric (volumePower 1): F_n = kn V with
#                 kn = 1/(1/young₁ + 1/young₂), so every PolyhedraMat gets young = 2 kv and
#                 kn = kv; friction: YADE's ks = 1/(1/(young₁ poisson₁) + 1/(young₂ poisson₂)), so
#                 poisson = kt/kv gives ks = kt, and frictionAngle = atan μ (spec "friction",
#                 "kt"; 0 and no shear force without friction).
#   s (overlap) -> PolyhedraGeom.penetrationVolume / equivalentCrossSection: asperity's recorded
#                 depth V/|S|; -1e300 while apart, as asperity records it; n its normal, into the
#                 recorded body (the restitution's direction).
import math
import os
import sys
import time

import yade.config
from yade import O, polyhedra_utils
from yade.wrapper import (Bo1_Polyhedra_Aabb, ForceResetter, Ig2_Polyhedra_Polyhedra_PolyhedraGeom,
                          InsertionSortCollider, InteractionLoop,
                          Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys,
                          Law2_PolyhedraGeom_PolyhedraPhys_Volumetric, NewtonIntegrator, PolyhedraMat)
from yade.minieigenHP import Vector3

from peer_files import write_atomically, write_json  # beside this file (scene_to_yade.py's path)


class MappingError(Exception):
    pass


def build(spec):
    """The YADE scene of `spec`; returns {body name: YADE id}."""
    O.reset()
    if spec["law"] != "volume-linear":
        raise MappingError(f"law {spec['law']}: the polyhedra path runs volume-linear only")
    kv = spec["kv"]
    mu, kt = spec.get("friction", 0.0), spec.get("kt", 0.0)
    mat_id = {}
    for name, m in spec["materials"].items():
        # kn = 1/(1/young_a + 1/young_b) = kv for any pair when every young is 2 kv; likewise
        # ks = kt when every poisson is kt/kv.
        mat_id[name] = O.materials.append(
            PolyhedraMat(young=2 * kv, poisson=kt / kv if mu > 0 else 1.0, density=m["density"],
                         frictionAngle=math.atan(mu), label=name))
    ids = {}
    for b in spec["bodies"]:
        verts = [Vector3(*v) for v in b["vertices"]]
        body = polyhedra_utils.polyhedra(O.materials[mat_id[b["material"]]], v=verts, fixed=b["fixed"])
        if not b["fixed"]:
            body.state.vel = Vector3(*b["velocity"])
            body.state.angVel = Vector3(*b["angular_velocity"])
        ids[b["name"]] = O.bodies.append(body)
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Polyhedra_Aabb()]),
        InteractionLoop([Ig2_Polyhedra_Polyhedra_PolyhedraGeom()],
                        [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
                        [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric(volumePower=1.0)]),
        NewtonIntegrator(damping=0.0, gravity=Vector3(*spec["gravity"])),
    ]
    O.dt = spec["dt"]
    return ids


def contacts_of(rid):
    return [i for i in O.interactions.withBody(rid) if i.isReal]


def record_row(rid, free):
    """t, force on the recorded body, its overlap's mean depth V/A (A YADE's cross-section) and
    normal (into the recorded body), then each free body's position and velocity."""
    f = O.forces.f(rid)
    s, n_best = -1e300, Vector3(0, 0, 1)
    for i in contacts_of(rid):
        g = i.geom
        if g.penetrationVolume <= 0:
            continue
        other = i.id2 if i.id1 == rid else i.id1
        n = Vector3(g.normal)
        # Normal from the partner into the recorded body.
        if n.dot(O.bodies[rid].state.pos - O.bodies[other].state.pos) < 0:
            n = -n
        depth = g.penetrationVolume / g.equivalentCrossSection if g.equivalentCrossSection > 0 else 0
        if depth > s:
            s, n_best = depth, n
    row = [O.time, f[0], f[1], f[2], s, n_best[0], n_best[1], n_best[2]]
    for bid in free:
        st = O.bodies[bid].state
        row += [st.pos[0], st.pos[1], st.pos[2], st.vel[0], st.vel[1], st.vel[2]]
    return row


def run(spec, outdir):
    ids = build(spec)
    rid = ids[spec["record_body"]]
    free = [ids[b["name"]] for b in spec["bodies"] if not b["fixed"]]
    steps = int(spec["steps"])
    rows = []
    stiffness = []
    in_contact = []
    # Each O.step() computes the forces at the positions it starts from and then moves the bodies,
    # so its row is dated at the start (O.time − dt): rows at t = 0 … steps·dt, as asperity's.
    for _ in range(steps + 1):
        O.step()
        rows.append(record_row(rid, free))
        rows[-1][0] = O.time - O.dt
        in_contact.append(rows[-1][4] > -1e299)
        for i in contacts_of(rid):
            if not stiffness and i.phys.kn > 0:
                stiffness.append({"kn": i.phys.kn, "expected": spec["kv"],
                                  "rel_diff": abs(i.phys.kn / spec["kv"] - 1)})
    in_contact = in_contact[:steps]
    final = {b["name"]: {"velocity": list(O.bodies[ids[b["name"]]].state.vel),
                         "angular_velocity": list(O.bodies[ids[b["name"]]].state.angVel)}
             for b in spec["bodies"]}
    # The cost: the same run again without the recorder, each step's CPU seconds timed (Python's
    # call overhead, about a microsecond, is below the polyhedra intersection's cost by orders of
    # magnitude; CPU rather than wall time, so that a loaded machine does not inflate it).
    build(spec)
    step_cpu = []
    cpu0, wall0 = time.process_time(), time.perf_counter()
    for _ in range(steps):
        t0 = time.process_time()
        O.step()
        step_cpu.append(time.process_time() - t0)
    cpu, wall = time.process_time() - cpu0, time.perf_counter() - wall0
    contact_steps = [w for w, c in zip(step_cpu, in_contact) if c]
    free_steps = [w for w, c in zip(step_cpu, in_contact) if not c]
    first = in_contact.index(True) if any(in_contact) else None
    last = len(in_contact) - 1 - in_contact[::-1].index(True) if any(in_contact) else None
    step_seconds = {
        "free_mean": sum(free_steps) / len(free_steps) if free_steps else None,
        "contact_mean": sum(contact_steps) / len(contact_steps) if contact_steps else None,
        "contact_steps": len(contact_steps),
        "first_contact_step": step_cpu[first] if first is not None else None,
        "last_contact_step": step_cpu[last] if last is not None else None,
        "max": max(step_cpu) if step_cpu else None,
    }
    def trace(out):
        names = [b["name"] for b in spec["bodies"] if not b["fixed"]]
        out.write("t,fx,fy,fz,s,nx,ny,nz" +
                  "".join(f",{b}.x,{b}.y,{b}.z,{b}.vx,{b}.vy,{b}.vz" for b in names) + "\n")
        for r in rows:
            out.write(",".join(repr(float(x)) for x in r) + "\n")
    write_atomically(os.path.join(outdir, "raw.csv"), trace)
    write_json(os.path.join(outdir, "raw.json"),
               {"final": final, "cpu_seconds": cpu, "wall_seconds": wall, "dt": spec["dt"],
                "steps": steps, "stiffness": stiffness, "step_seconds": step_seconds,
                "yade_version": yade.config.version})
