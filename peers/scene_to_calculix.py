#!/usr/bin/env python3
"""CalculiX (ccx 2.20) on a deformable sphere or particle striking a rigid plane, as the calculix
peer adapter hands it over (docs/crosscheck.md, "CalculiX").

Usage: scene_to_calculix.py INPUT.json DIR

INPUT.json (written by peers/calculix.cpp) gives the problem in the plane's frame: the plane is
z = 0 with its normal +z into the free side, the strike point on the z axis `gap` above it, the
body moving at -`speed` along z. `shape` "sphere": the sphere's centre at (0, 0, gap + R), meshed
as its quarter x >= 0, y >= 0; `shape` "surface": the closed triangulated surface `points`,
`triangles` (outward), its volume centroid at `centroid`, meshed whole (a particle has no
symmetry), every triangle a plane surface of gmsh so the meshed geometry is the file's facets,
as asperity's (docs/geometry.md, "Element size"). DIR receives

- ball.geo, mesh.inp (gmsh), impact.inp (the deck), impact.dat / impact.sta (ccx's own output),
  ccx.log;
- raw.csv: per ccx increment t, fx, fy, fz (the contact force on the recorded body, in the
  scene's frame), s, nx, ny, nz (the strike point's penetration of the plane, m, negative while
  apart, and the contact normal into the recorded body), then the body's centroid position and
  velocity (momentum balance of the meshed mass under the contact force and gravity);
- raw.json: the mesh's counts, the meshed mass, ccx's CPU and wall seconds, its version, and the
  body's spin at the end (rad/s, the impact frame: zero for the sphere by symmetry; for a
  particle its angular impulse about the centroid, the force taken at the strike node, over the
  meshed inertia).

On failure it writes error.txt (one line) and exits 1.
"""

import json
import os
import re
import resource
import subprocess
import sys
import time

from peer_files import write_atomically, write_json  # beside this file


def fail(out_dir, why):
    with open(os.path.join(out_dir, "error.txt"), "w") as f:
        f.write(why.replace("\n", " ") + "\n")
    sys.exit(1)


def geo_text(p):
    """gmsh geometry: the sphere's quarter x >= 0, y >= 0 (the two planes of symmetry through
    the strike point) or the particle's whole surface, with the scene's element size graded to
    the focus: size + growth * max(0, d - focus_radius), capped at far
    (geometry/element_size.hpp), d the distance from the focus."""
    fx, fy, fz = p["focus"]
    # Every coordinate in parentheses: gmsh's MathEval rejects "y--1e-18".
    distance = "Sqrt((x-(%.12g))^2+(y-(%.12g))^2+(z-(%.12g))^2)" % (fx, fy, fz)
    size = "Min(%.12g, %.12g + %.12g*Max(0, %s - %.12g))" % (
        p["far"], p["size"], p["growth"], distance, p["focus_radius"])
    lines = sphere_geo(p) if p["shape"] == "sphere" else surface_geo(p)
    lines += ["Field[1] = MathEval;",
              'Field[1].F = "%s";' % size,
              "Background Field = 1;",
              "Mesh.MeshSizeExtendFromBoundary = 0;",
              "Mesh.MeshSizeFromPoints = 0;",
              "Mesh.MeshSizeFromCurvature = 0;",
              "Mesh.Algorithm3D = 1;",
              "Mesh.Optimize = 1;",
              "Mesh.RandomSeed = 1;",
              "General.NumThreads = 1;"]
    return "\n".join(lines) + "\n"


def sphere_geo(p):
    r = p["radius"]
    return ['SetFactory("OpenCASCADE");',
            "Sphere(1) = {0, 0, %.12g, %.12g};" % (p["gap"] + r, r),
            "Box(2) = {0, 0, %.12g, %.12g, %.12g, %.12g};" % (p["gap"], 2 * r, 2 * r, 2 * r),
            "BooleanIntersection(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };",
            'Physical Volume("BALL") = {3};']


def surface_geo(p):
    """The facets as gmsh's built-in geometry: a point per vertex, a line per edge, a plane
    surface per triangle (meshing subdivides each in its own plane, the geometry unchanged)."""
    out = ["Point(%d) = {%.17g, %.17g, %.17g};" % (i + 1, *x) for i, x in enumerate(p["points"])]
    edges = {}
    loops = []
    for tri in p["triangles"]:
        loop = []
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            key = (min(a, b), max(a, b))
            if key not in edges:
                edges[key] = len(edges) + 1
                out.append("Line(%d) = {%d, %d};" % (edges[key], key[0] + 1, key[1] + 1))
            loop.append(edges[key] if a < b else -edges[key])
        loops.append(loop)
    for k, loop in enumerate(loops):
        out += ["Curve Loop(%d) = {%d, %d, %d};" % (k + 1, *loop),
                "Plane Surface(%d) = {%d};" % (k + 1, k + 1)]
    out += ["Surface Loop(1) = {1:%d};" % len(loops), "Volume(1) = {1};",
            'Physical Volume("BALL") = {1};']
    return out


def read_mesh(path):
    nodes, tets = {}, []
    mode = None
    with open(path) as f:
        for line in f:
            if line.startswith("*"):
                u = line.upper().replace(" ", "")
                mode = ("node" if u.startswith("*NODE") else
                        "tet" if u.startswith("*ELEMENT") and "TYPE=C3D4" in u else None)
                continue
            if mode == "node":
                v = line.split(",")
                nodes[int(v[0])] = (float(v[1]), float(v[2]), float(v[3]))
            elif mode == "tet":
                v = [int(x) for x in line.split(",") if x.strip()]
                tets.append(v[1:5])
    return nodes, tets


def tet_volume(a, b, c, d):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = [d[i] - a[i] for i in range(3)]
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
            u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0


def boundary_nodes(tets):
    count = {}
    for t in tets:
        for f in ((t[0], t[1], t[2]), (t[0], t[1], t[3]), (t[0], t[2], t[3]), (t[1], t[2], t[3])):
            k = tuple(sorted(f))
            count[k] = count.get(k, 0) + 1
    return [k for k, n in count.items() if n == 1]


def write_deck(p, nodes, tets, path):
    gap, zone = p["gap"], p["slave_height"]
    sphere = p["shape"] == "sphere"
    tol = 1e-9 * p["length"]
    # Slave: the body's surface within `slave_height` of the plane at the start, above any
    # approach this model reaches (faces on a plane of symmetry are not surface).
    slave = set()
    for f in boundary_nodes(tets):
        xs = [nodes[n] for n in f]
        if sphere and (all(abs(x[0]) < tol for x in xs) or all(abs(x[1]) < tol for x in xs)):
            continue
        if all(x[2] < gap + zone for x in xs):
            slave.update(f)
    # The strike point: the sphere's lowest node on the axis; the particle's lowest vertex, at
    # (0, 0, gap), a node of the facets.
    if sphere:
        pole = min((n for n in nodes if abs(nodes[n][0]) + abs(nodes[n][1]) < tol),
                   key=lambda n: nodes[n][2])
    else:
        pole = min(nodes, key=lambda n: nodes[n][0] ** 2 + nodes[n][1] ** 2 +
                   (nodes[n][2] - gap) ** 2)
    # The plane: one fixed hexahedron under the contact zone (its top face the master surface).
    # The sphere's quarter: [-0.05 R, 0.9 R]² (R = `length`); the particle: the slave nodes'
    # footprint widened by the zone.
    top, depth = 0.0, -0.2 * p["length"]
    if sphere:
        x0 = y0 = -0.05 * p["length"]
        x1 = y1 = 0.9 * p["length"]
    else:
        xs = [nodes[n][0] for n in slave]
        ys = [nodes[n][1] for n in slave]
        (x0, x1), (y0, y1) = ((min(v) - zone, max(v) + zone) for v in (xs, ys))
    base = max(nodes) + 1
    hexn = [(x0, y0, depth), (x1, y0, depth), (x1, y1, depth), (x0, y1, depth),
            (x0, y0, top), (x1, y0, top), (x1, y1, top), (x0, y1, top)]
    out = ["*HEADING", "asperity calculix peer: %s" % p["scene"], "*NODE, NSET=NALL"]
    out += ["%d, %.12g, %.12g, %.12g" % (n, *nodes[n]) for n in sorted(nodes)]
    out += ["*NODE, NSET=NPLANE"]
    out += ["%d, %.12g, %.12g, %.12g" % (base + i, *x) for i, x in enumerate(hexn)]
    out += ["*ELEMENT, TYPE=C3D4, ELSET=EBALL"]
    out += ["%d, %d, %d, %d, %d" % (i + 1, *t) for i, t in enumerate(tets)]
    eplane = len(tets) + 1
    out += ["*ELEMENT, TYPE=C3D8, ELSET=EPLANE",
            "%d, %s" % (eplane, ", ".join(str(base + i) for i in range(8)))]
    out += ["*NSET, NSET=NSLAVE"] + chunks(sorted(slave))
    out += ["*NSET, NSET=NPOLE", str(pole)]
    if sphere:
        out += ["*NSET, NSET=NSYMX"] + chunks([n for n in nodes if abs(nodes[n][0]) < tol])
        out += ["*NSET, NSET=NSYMY"] + chunks([n for n in nodes if abs(nodes[n][1]) < tol])
    out += ["*SURFACE, NAME=SSLAVE, TYPE=NODE", "NSLAVE",
            "*SURFACE, NAME=SPLANE, TYPE=ELEMENT", "%d, S2" % eplane]
    law = p["law"]
    out += ["*MATERIAL, NAME=BALL"]
    if law == "linear":
        out += ["*ELASTIC", "%.12g, %.12g" % (p["young"], p["poisson"])]
    else:
        # ccx's compressible neo-Hooke: W = C10 (I1bar - 3) + (J - 1)^2 / D1, C10 = mu / 2,
        # D1 = 2 / K: asperity's neo-Hookean to first order in the strain.
        e, nu = p["young"], p["poisson"]
        mu, k = e / (2 * (1 + nu)), e / (3 * (1 - 2 * nu))
        out += ["*HYPERELASTIC, NEO HOOKE", "%.12g, %.12g" % (mu / 2, 2 / k)]
    out += ["*DENSITY", "%.12g" % p["density"],
            "*MATERIAL, NAME=PLANE", "*ELASTIC", "%.12g, 0.3" % p["young"], "*DENSITY",
            "%.12g" % p["density"],
            "*SOLID SECTION, ELSET=EBALL, MATERIAL=BALL",
            "*SOLID SECTION, ELSET=EPLANE, MATERIAL=PLANE",
            "*SURFACE INTERACTION, NAME=SI",
            "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
            # slope (N/m^3) and the small tension sigma_inf of ccx's node-to-face law (Pa)
            "%.12g, %.12g" % (p["penalty_slope"], p["sigma_inf"]),
            "*CONTACT PAIR, INTERACTION=SI, TYPE=NODE TO SURFACE",
            "SSLAVE, SPLANE",
            "*INITIAL CONDITIONS, TYPE=VELOCITY",
            "NALL, 3, %.12g" % (-p["speed"]),
            "*BOUNDARY", "NPLANE, 1, 3"]
    if sphere:
        out += ["NSYMX, 1, 1", "NSYMY, 2, 2"]
    nl = ", NLGEOM" if law != "linear" else ""
    out += ["*STEP, INC=1000000%s" % nl,
            "*DYNAMIC, DIRECT, ALPHA=%.12g" % p["alpha"],
            "%.12g, %.12g" % (p["dt"], p["t_end"])]
    if p["gravity_z"] != 0:
        out += ["*DLOAD", "EBALL, GRAV, %.12g, 0, 0, -1" % (-p["gravity_z"])]
    out += ["*NODE PRINT, NSET=NPLANE, TOTALS=ONLY, FREQUENCY=1", "RF",
            "*NODE PRINT, NSET=NPOLE, FREQUENCY=1", "U",
            "*END STEP"]
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    return len(slave), pole


def chunks(ids, per=8):
    return [", ".join(str(i) for i in ids[k:k + per]) for k in range(0, len(ids), per)]


def read_dat(path):
    """Per increment: the plane's total reaction force and the pole's displacement."""
    force, pole = {}, {}
    what, t = None, None
    num = r"([-+]?\d*\.?\d+(?:[eE][-+]?\d+)?)"
    with open(path) as f:
        for line in f:
            m = re.search(r"total force \(fx,fy,fz\) for set NPLANE and time\s+" + num, line)
            if m:
                what, t = "force", float(m.group(1))
                continue
            m = re.search(r"displacements \(vx,vy,vz\) for set NPOLE and time\s+" + num, line)
            if m:
                what, t = "u", float(m.group(1))
                continue
            v = line.split()
            if what == "force" and len(v) == 3:
                force[t] = [float(x) for x in v]
                what = None
            elif what == "u" and len(v) == 4:
                pole[t] = [float(x) for x in v[1:]]
                what = None
    return force, pole


def write_trace(out_dir, p, body, pole):
    """raw.csv from impact.dat; returns the number of increments and the spin at the end."""
    force, pole_u = read_dat(os.path.join(out_dir, "impact.dat"))
    times = sorted(set(force) & set(pole_u))
    if not times:
        fail(out_dir, "ccx wrote no force history (impact.dat)")
    if force[times[-1]][2] > 0:
        fail(out_dir, "the contact is still on at the end of the step (t = %g s): the run ends "
             "too soon for this body" % times[-1])
    gap, g, mass = p["gap"], p["gravity_z"], body["mass"]
    cx, cy, cz = body["centroid"]
    # (t, contact force on the body along z, the strike node's penetration s, centroid height,
    # velocity)
    rows = [(0.0, 0.0, -gap, cz, -p["speed"])]
    # The particle's angular impulse about its centroid, the force at the strike node (a
    # frictionless force on a plane is along z, so only its arm's x and y count).
    lx = ly = 0.0
    for t in times:
        # The supports' reaction RF balances the body's push on the fixed plane, so it equals
        # the contact force on the body (the plane's is its opposite); by symmetry the whole
        # sphere's (4 quarters) is along z. The centroid moves by the momentum balance.
        fz = body["copies"] * force[t][2]
        t0, f0, _, z0, v0 = rows[-1]
        a0, a1, dt = f0 / mass + g, fz / mass + g, t - t0
        rows.append((t, fz, -(pole[2] + pole_u[t][2]), z0 + v0 * dt + (2 * a0 + a1) * dt * dt / 6,
                     v0 + 0.5 * (a0 + a1) * dt))
        fm = 0.5 * (f0 + fz) * dt
        lx += (pole[1] + pole_u[t][1] - cy) * fm
        ly -= (pole[0] + pole_u[t][0] - cx) * fm
    spin = solve3(body["inertia"], [lx, ly, 0.0]) if body["copies"] == 1 else [0.0, 0.0, 0.0]
    rows = with_contact_ends(rows)
    e1, e2, e3, origin = (p["frame"][k] for k in ("e1", "e2", "e3", "origin"))
    sign = 1.0 if p["record"] == "ball" else -1.0
    def trace(f):
        f.write("t,fx,fy,fz,s,nx,ny,nz,x,y,z,vx,vy,vz\n")
        for t, fz, s, z, v in rows:
            values = ([t] + [sign * fz * c for c in e3] + [s] + [sign * c for c in e3] +
                      [origin[i] + cx * e1[i] + cy * e2[i] + z * e3[i] for i in range(3)] +
                      [v * c for c in e3])
            f.write(",".join("%.12g" % c for c in values) + "\n")
    write_atomically(os.path.join(out_dir, "raw.csv"), trace)
    return len(times), [sum(spin[j] * p["frame"][k][i] for j, k in enumerate(("e1", "e2", "e3")))
                        for i in range(3)]


def solve3(m, b):
    """x with m x = b, 3 x 3, by Cramer's rule."""
    def det(a):
        return (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))
    d = det(m)
    return [det([[b[r] if c == k else m[r][c] for c in range(3)] for r in range(3)]) / d
            for k in range(3)]


def mass_properties(nodes, tets, density, copies):
    """The meshed body's mass, centroid and inertia tensor about the centroid (kg, m, kg m²),
    from its tetrahedra (the quarter sphere's: mass × 4, centroid and inertia not used)."""
    volume, moment = 0.0, [0.0, 0.0, 0.0]
    for t in tets:
        x = [nodes[n] for n in t]
        v = tet_volume(*x)
        volume += v
        for i in range(3):
            moment[i] += v * sum(y[i] for y in x) / 4
    c = [m / volume for m in moment]
    # Second moments about the centroid: a tetrahedron's ∫ x_i x_j dV = V/20 (Σ a_i a_j + s_i s_j),
    # the vertices a relative to the centroid and s their sum.
    cov = [[0.0] * 3 for _ in range(3)]
    for t in tets:
        x = [[nodes[n][i] - c[i] for i in range(3)] for n in t]
        v = tet_volume(*(nodes[n] for n in t))
        s = [sum(y[i] for y in x) for i in range(3)]
        for i in range(3):
            for j in range(3):
                cov[i][j] += v / 20 * (sum(y[i] * y[j] for y in x) + s[i] * s[j])
    tr = cov[0][0] + cov[1][1] + cov[2][2]
    inertia = [[density * ((tr if i == j else 0.0) - cov[i][j]) for j in range(3)]
               for i in range(3)]
    return {"mass": copies * volume * density, "volume": volume, "centroid": c,
            "inertia": inertia, "copies": copies}


def with_contact_ends(rows):
    """Each contact's start and end placed between increments, where the strike point's
    penetration s (asperity's overlap, from which the measures place both) would put them.

    Start: while apart the body moves rigidly, so s is exact and linear in time, but from the
    first increment in contact it is the penalty layer's (micrometres, not the approach), so
    interpolating s between the two would put the start near that increment, up to a whole
    increment late (measured: 0.077 ms of the scan AAA's 8.4 ms, s at 0.983 ms −3.37 µm, at
    1.092 ms +0.56 µm, where the free flight reaches the plane at 1.000 ms). The start is the zero
    of the free flight's line through the last two increments apart, and a sample with no force
    and no penetration is inserted there.

    End: the pole's penetration jumps to the rebound's clearance once out, so interpolating it
    would put the end at the last increment with a force, up to a whole increment (1 % of T_H)
    early. At the end the last nodes in contact leave the penalty layer at a finite speed, so the
    force, K times their penetration, falls linearly to zero (measured: decrements of 1.8 N per
    T_H/200 over the last four increments of a/R = 0.15, s = 1): the end is the zero of the line
    through the force at the last two increments with a force, and a sample with no force and no
    penetration is inserted there."""
    out = []
    for k, row in enumerate(rows):
        # Approaching in free flight (no force yet) at k - 2 and k - 1, in contact at k.
        if k >= 2 and rows[k - 2][2] < rows[k - 1][2] < 0 < row[2] and rows[k - 1][1] <= 0:
            (t0, _, s0, _, _), (t1, _, s1, z1, v1) = rows[k - 2], rows[k - 1]
            t2, z2, v2 = row[0], row[3], row[4]
            ts = min(t2, t1 - s1 * (t1 - t0) / (s1 - s0))
            w = (ts - t1) / (t2 - t1)
            out.append((ts, 0.0, 0.0, z1 + w * (z2 - z1), v1 + w * (v2 - v1)))
        out.append(row)
        if 0 < k < len(rows) - 1 and row[1] > 0 and rows[k + 1][1] <= 0 and rows[k - 1][1] > row[1]:
            (t0, f0, *_), (t1, f1, _, z1, v1), t2 = rows[k - 1], row, rows[k + 1][0]
            te = min(t2, t1 + f1 * (t1 - t0) / (f0 - f1))
            w = (te - t1) / (t2 - t1)
            z2, v2 = rows[k + 1][3], rows[k + 1][4]
            out.append((te, 0.0, 0.0, z1 + w * (z2 - z1), v1 + w * (v2 - v1)))
    return out


def main():
    inp, out_dir = sys.argv[1], sys.argv[2]
    with open(inp) as f:
        p = json.load(f)
    wall0 = time.time()
    with open(os.path.join(out_dir, "ball.geo"), "w") as f:
        f.write(geo_text(p))
    gmsh = subprocess.run([p["gmsh"], "-3", "ball.geo", "-format", "inp", "-o", "mesh.inp"],
                          cwd=out_dir, capture_output=True, text=True)
    with open(os.path.join(out_dir, "gmsh.log"), "w") as f:
        f.write(gmsh.stdout + gmsh.stderr)
    if gmsh.returncode != 0 or not os.path.exists(os.path.join(out_dir, "mesh.inp")):
        fail(out_dir, "gmsh failed (exit %d): %s" % (gmsh.returncode,
                                                      (gmsh.stdout + gmsh.stderr)[-300:]))
    nodes, tets = read_mesh(os.path.join(out_dir, "mesh.inp"))
    if not tets:
        fail(out_dir, "gmsh wrote no tetrahedra (mesh.inp)")
    copies = 4 if p["shape"] == "sphere" else 1  # the quarter model, or the whole particle
    body = mass_properties(nodes, tets, p["density"], copies)
    if body["volume"] < 0:
        fail(out_dir, "gmsh's tetrahedra are inverted")
    if copies == 4:
        body["centroid"] = [0.0, 0.0, p["gap"] + p["radius"]]
    nslave, pole = write_deck(p, nodes, tets, os.path.join(out_dir, "impact.inp"))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
    with open(os.path.join(out_dir, "ccx.log"), "w") as log:
        code = subprocess.run([p["ccx"], "impact"], cwd=out_dir, stdout=log, stderr=log,
                              stdin=subprocess.DEVNULL, env=env).returncode
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    ccx_wall = time.time() - t0
    ccx_cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    log = open(os.path.join(out_dir, "ccx.log")).read()
    if code != 0 or "Job finished" not in log:
        why = [ln for ln in log.splitlines() if "ERROR" in ln.upper()]
        fail(out_dir, "ccx failed (exit %d): %s" % (code, (why[-1] if why else log[-300:]).strip()))
    nincrements, spin = write_trace(out_dir, p, body, nodes[pole])
    version = re.search(r"Version\s+([\d.]+)", log)
    write_json(os.path.join(out_dir, "raw.json"),
               {"ccx_version": version.group(1) if version else "",
                "nodes": len(nodes), "tets": len(tets),
                "symmetry": "quarter" if copies == 4 else "none",
                "slave_nodes": nslave, "meshed_mass": body["mass"], "increments": nincrements,
                "spin": spin,
                "cpu_seconds": ccx_cpu, "wall_seconds": ccx_wall,
                "total_wall_seconds": time.time() - wall0})


if __name__ == "__main__":
    main()
