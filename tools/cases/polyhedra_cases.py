"""Writes the rigid-polyhedra validation cases (validation/cases/polyhedra/) and their convex
meshes (data/meshes/convex/): run from the repository root with a python that has numpy and scipy,
after building the program (it generates the particle and simplifies its hull).

  /usr/bin/python3 tools/cases/polyhedra_cases.py [build/bin/asperity]
  (Debian python3-numpy, python3-scipy)

Meshes: a cube; a regular octahedron turned to land on a vertex, an edge and a face; the convex
hull of the repository's generated particle (data/meshes/particle-seed3-320.off); the convex hulls
of the same generated particle at full resolution (`asperity particle --seed 3`: 20,480 triangles,
a hull of 3178 vertices) simplified by `asperity mesh --faces 2n-4` to n = 50, 250, 1000 and 2000
vertices (simplifying a convex surface keeps every vertex on its hull; the hull is taken again so
that the body is exactly convex); a geodesic sphere (frequency 16, 5120 faces). Orientation is baked into the file (a scene places a mesh by
its centroid, unrotated). Cases: each convex body dropped straight and obliquely on a plane under
volume-linear (F = kv V, the YADE cross-check's law), and the faceted sphere under volume-hertz
against Hertz. Every expected value is analytic: momentum (impulse 2 m v_n for a symmetric drop),
elasticity (restitution 1), the linear spring of a face (peak v √(k m), duration π √(m/k)), Hertz.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.spatial import ConvexHull

ROOT = os.getcwd()
MESH_DIR = os.path.join(ROOT, "data", "meshes", "convex")
CASE_DIR = os.path.join(ROOT, "validation", "cases", "polyhedra")
DENSITY = 2650.0  # granite, kg/m³
KV = 1e11         # N/m³: a 2 cm face pressed 10 µm carries ~400 N, a stone-like stiffness


def read_off(path):
    with open(path) as f:
        tokens = f.read().split()
    assert tokens[0] == "OFF"
    nv, nf = int(tokens[1]), int(tokens[2])
    v = np.array(tokens[4:4 + 3 * nv], dtype=float).reshape(nv, 3)
    return v


def hull_mesh(points):
    """Outward-oriented triangles of the convex hull; returns (vertices, faces)."""
    h = ConvexHull(points)
    used = sorted(set(h.simplices.ravel()))
    index = {old: new for new, old in enumerate(used)}
    v = points[used]
    c = v.mean(axis=0)
    faces = []
    for s in h.simplices:
        a, b, d = (index[i] for i in s)
        if np.dot(np.cross(v[b] - v[a], v[d] - v[a]), v[a] - c) < 0:
            b, d = d, b
        faces.append((a, b, d))
    return v, np.array(faces)


def write_off(path, v, f):
    with open(path, "w") as out:
        out.write(f"OFF\n{len(v)} {len(f)} 0\n")
        for p in v:
            out.write(f"{p[0]!r} {p[1]!r} {p[2]!r}\n")
        for t in f:
            out.write(f"3 {t[0]} {t[1]} {t[2]}\n")


def rotation_to_down(direction):
    """Rotation taking `direction` to −z (Rodrigues)."""
    a = direction / np.linalg.norm(direction)
    b = np.array([0.0, 0.0, -1.0])
    v = np.cross(a, b)
    c = float(np.dot(a, b))
    if np.linalg.norm(v) < 1e-15:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + k + k @ k / (1 + c)


def volume_of(v, f):
    return sum(np.dot(v[a], np.cross(v[b], v[c])) for a, b, c in f) / 6.0


def geodesic_sphere(n):
    t = (1 + math.sqrt(5)) / 2
    ico = np.array([[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
                    [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]], float)
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    pts = []
    for a, b, c in faces:
        for i in range(n + 1):
            for j in range(n + 1 - i):
                k = n - i - j
                p = (i * ico[a] + j * ico[b] + k * ico[c]) / n
                pts.append(p / np.linalg.norm(p))
    pts = np.unique(np.round(np.array(pts), 12), axis=0)
    return hull_mesh(pts)


def mesh_file(name, v, f):
    write_off(os.path.join(MESH_DIR, name + ".off"), v, f)
    return os.path.relpath(os.path.join(MESH_DIR, name + ".off"), CASE_DIR)


def case(name, description, mesh, velocity, expected, law="volume-linear", duration=None,
         young=5e10, density=DENSITY, poisson=0.25, tags=("polyhedra", "volume-linear", "yade")):
    contact = {"law": law}
    if law == "volume-linear":
        contact["kv"] = KV
    scene = {
        "name": name,
        "duration": duration,
        "dt": "auto",
        "materials": {"granite": {"density": density, "young": young, "poisson": poisson,
                                  "friction": 0.0, "restitution": 1.0}},
        "bodies": [
            {"name": "particle", "material": "granite", "model": "rigid",
             "shape": {"type": "mesh", "file": mesh}, "position": [0, 0, 0], "velocity": velocity},
            {"name": "ground", "material": "granite",
             "shape": {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}},
        ],
        "contact": contact,
        "record": {"force_on": "particle", "every": 1, "end_after_separation": 1e-5},
    }
    return {"case": name, "description": description, "tags": list(tags), "scene": scene,
            "expected": expected}


def centroid_of(v, f):
    """Volume centroid (a scene places a mesh body by it)."""
    vol, first = 0.0, np.zeros(3)
    for a, b, c in f:
        t = np.dot(v[a], np.cross(v[b], v[c])) / 6.0
        vol += t
        first += t * (v[a] + v[b] + v[c]) / 4.0
    return first / vol


def place(v, f, gap):
    """The centroid's z that puts the lowest point `gap` above z = 0."""
    return gap - (v[:, 2].min() - centroid_of(v, f)[2])


# The generated particles' hulls: vertices, and the explicit step of their cases. At the auto step
# (1 % of the predicted contact time, the face bound) a vertex-first contact takes ~5000 steps,
# and YADE's Polyhedra costs up to 80 ms per contact step at 2000 vertices: the gates would take
# many minutes. Both codes integrate the same law at the same step, so they agree to round-off at
# any stable step; 8 µs resolves the ~0.9 ms contacts in ~110 steps, below every body's
# predicted critical step (≥ 16 µs).
HULL_VERTICES = (50, 250, 1000, 2000)
HULL_DT = 8e-6


def generated_hulls(asperity):
    """{name: (vertices, faces)}: the hull of `asperity particle --seed 3`, simplified to n
    vertices by `asperity mesh` and taken again."""
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        full = os.path.join(tmp, "particle.off")
        subprocess.run([asperity, "particle", "--seed", "3", "--out", full], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        v, f = hull_mesh(read_off(full))
        write_off(os.path.join(tmp, "hull.off"), v, f)
        for n in HULL_VERTICES:
            dst = os.path.join(tmp, f"m{n}")
            subprocess.run([asperity, "mesh", os.path.join(tmp, "hull.off"), "--faces",
                            str(2 * n - 4), "--out", dst], check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            p = read_off(os.path.join(dst, "surface.off"))
            hv, hf = hull_mesh(p - p.mean(axis=0))
            assert len(hv) == n, f"hull of {n}: {len(hv)} vertices"
            out[f"hull-seed3-{n}"] = (hv, hf)
    return out


# Coulomb friction of the volume laws: μ and the tangential spring kt (N/m; a quarter of the
# cube face's normal stiffness kv a² = 4e7 N/m, so the step the face sets resolves it too).
MU = 0.3
KT = 1e7


def friction_cases(cube):
    """A cube sliding on a plane under gravity (both volume laws), and the cube's oblique drop with
    friction (the YADE cross-check's case)."""
    v, f = cube
    a = 0.02
    mass = DENSITY * a ** 3
    g = 9.81
    out = []
    v0, duration = 0.5, 0.05
    for law in ("volume-linear", "volume-hertz"):
        name = f"{law}-cube-sliding-friction"
        speed = v0 - MU * g * duration
        expected = {
            "status": "ok",
            "final_speed": {
                "value": speed, "rel_tol": 0.002,
                "why": "Coulomb: a block sliding on a plane decelerates at μ g, v(T) = v0 − μ g T; "
                       "0.2 % for the normal force's ringing about m g (the cube starts at rest "
                       "on its face, not at the law's equilibrium depth) and the spring's "
                       "start-up, both measured below 0.05 %"},
            "energy_drift": {
                "max": 1e-3,
                "why": "the energy dissipated equals the friction work μ m g d: the balance "
                       "kinetic + contact (normal and spring) + gravity + dissipated is kept to "
                       "the integrator's error"},
        }
        contact = {"law": law, "friction": MU}
        if law == "volume-linear":
            contact["kt"] = KT
            contact["kv"] = KV
        else:
            expected["final_speed"]["rel_tol"] = 0.01
            expected["final_speed"]["why"] = (
                "Coulomb: a block sliding on a plane decelerates at μ g, v(T) = v0 − μ g T (measured "
                "+0.55 %). 1 % of v(T) (2.4 % of the speed lost) because the undamped cube rocks "
                "onto its leading edge and hops: friction at the base tips it, and an energy of V "
                "alone has no rocking stiffness on a flat face (tilting about the face's centre "
                "keeps V), so the tipping moment is balanced only by lifting the rear edge; the "
                "cube touches in 6 % of the steps. At any instant the normal impulse then differs "
                "from m g t by the hop's momentum (±1.6 % of m g T measured, ±0.7 % of v(T)), and "
                "each touch-down starts the tangential spring from zero (Mindlin's stick phase)")
            expected["energy_drift"]["why"] = (
                "the energy dissipated equals the friction work μ m g d: the balance kinetic + "
                "contact (normal and spring) + gravity + dissipated is kept to the integrator's "
                "error (measured 6.2e-5)")
        scene = {
            "name": name, "duration": duration, "dt": "auto", "gravity": [0, 0, -g],
            "materials": {"granite": {"density": DENSITY, "young": 5e10, "poisson": 0.25,
                                      "friction": MU, "restitution": 1.0}},
            "bodies": [
                {"name": "cube", "material": "granite", "model": "rigid",
                 "shape": {"type": "mesh", "file": mesh_file("cube-face", v, f)},
                 "position": [0.0, 0.0, a / 2], "velocity": [v0, 0.0, 0.0]},
                {"name": "ground", "material": "granite",
                 "shape": {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}},
            ],
            "contact": contact,
            # dt_safety 0.1 (the default 0.01 resolves the face's ringing 10× finer for nothing
            # this case measures: 44,000 steps instead of 441,000, final speed the same to 3e-5).
            "dt_safety": 0.1,
            "record": {"force_on": "cube", "every": 100},
        }
        out.append({"case": name,
                    "description": f"A {a} m granite cube sliding on its face at {v0} m/s on a "
                                   f"plane under gravity, {law} with Coulomb friction μ = {MU} "
                                   + (f"(kt = {KT:g} N/m)" if law == "volume-linear"
                                      else "(Mindlin's k_t)")
                                   + ": deceleration μ g, dissipated energy = friction work",
                    "tags": ["polyhedra", law, "friction"], "scene": scene,
                    "expected": expected})
    # The oblique drop of the cube with friction: YADE's volumetric law with its friction.
    name = "volume-linear-cube-face-oblique-friction"
    c = case(name, f"Rigid cube dropped face-first at (0.6, 0, -0.8) m/s on a plane under "
             f"volume-linear (kv = {KV:g} N/m³) with Coulomb friction μ = {MU}, kt = {KT:g} N/m: "
             "the YADE polyhedra cross-check with friction", mesh_file("cube-face", v, f),
             [0.6, 0.0, -0.8],
             {"status": "ok",
              "energy_drift": {
                  "max": 0.12,
                  "why": "measured 0.094: friction spins the cube up to 28 rad/s while the face "
                         "is pressed, and volume-linear's normal force applied at the overlap's "
                         "centroid is not conservative in a turning contact (the 50-vertex hull "
                         "shows 2.5 % without friction); friction's own booking is checked to "
                         "1.6e-5 by the sliding cube. YADE's law does the same (final speed and "
                         "spin agree to 2e-12). A bound against a blow-up, not a conservation "
                         "check"}},
             duration=0.005)
    c["scene"]["contact"]["friction"] = MU
    c["scene"]["contact"]["kt"] = KT
    c["scene"]["materials"]["granite"]["friction"] = MU
    c["scene"]["bodies"][0]["position"] = [0.0, 0.0, place(v, f, 2e-5)]
    out.append(c)
    return out


def main():
    asperity = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "bin", "asperity")
    os.makedirs(MESH_DIR, exist_ok=True)
    os.makedirs(CASE_DIR, exist_ok=True)
    bodies = {}
    a = 0.02
    cube = np.array([[x, y, z] for x in (-a / 2, a / 2) for y in (-a / 2, a / 2) for z in (-a / 2, a / 2)])
    bodies["cube-face"] = hull_mesh(cube)
    r = 0.015
    octa = np.array([[r, 0, 0], [-r, 0, 0], [0, r, 0], [0, -r, 0], [0, 0, r], [0, 0, -r]])
    for feature, direction in (("vertex", [0, 0, -1]), ("edge", [1, 0, -1]), ("face", [1, 1, -1])):
        rot = rotation_to_down(np.array(direction, float))
        bodies["octahedron-" + feature] = hull_mesh(octa @ rot.T)
    particle = read_off(os.path.join(ROOT, "data", "meshes", "particle-seed3-320.off"))
    bodies["hull-seed3"] = hull_mesh(particle - particle.mean(axis=0))
    bodies.update(generated_hulls(asperity))
    sphere_v, sphere_f = geodesic_sphere(16)
    bodies["geodesic-sphere-16"] = (sphere_v * 0.05, sphere_f)

    gap = 2e-5
    written = []
    for name, (v, f) in bodies.items():
        path = mesh_file(name, v, f)
        vol = volume_of(v, f)
        mass = DENSITY * vol
        centroid_z = place(v, f, gap)
        if name == "geodesic-sphere-16":
            continue
        for kind, vel in (("straight", [0.0, 0.0, -1.0]), ("oblique", [0.6, 0.0, -0.8])):
            if kind == "oblique" and name.startswith("octahedron") and name != "octahedron-edge":
                continue
            vn = -vel[2]
            symmetric = not name.startswith("hull-seed3")
            expected = {"status": "ok"}
            if symmetric:
                expected["impulse"] = {
                    "value": 2 * mass * vn, "rel_tol": 0.005,
                    "why": "momentum: a frictionless elastic drop on a feature whose overlap is "
                           "symmetric about the vertical reverses the normal momentum, impulse "
                           "2 m v_n; 0.5 % for the integration at the default step"}
                expected["restitution"] = {
                    "value": 1.0, "abs_tol": 1e-3,
                    "why": "no damping in volume-linear, and the force depends on the approach "
                           "alone in a straight symmetric drop: elastic to the integrator's error"}
            if name == "cube-face":
                k = KV * a * a
                expected["peak_force"] = {
                    "value": vn * math.sqrt(k * mass), "rel_tol": 0.005,
                    "why": "a face on a plane is a linear spring k = kv a² (V = a² δ): "
                           "peak v √(k m); 0.5 % for sampling the peak at the default step"}
                expected["contact_duration"] = {
                    "value": math.pi * math.sqrt(mass / k), "rel_tol": 0.01,
                    "why": "half period π √(m/k) of the same spring; 1 % because the contact's "
                           "ends are found to within a step (no signed gap while apart)"}
            expected["energy_drift"] = {
                "max": 1e-3,
                "why": "volume-linear's work is kept as ∫ s dV; it is a potential along a fixed "
                       "direction, and spin changes the direction only slightly here"}
            if name == "hull-seed3-50":
                expected["energy_drift"] = {
                    "max": 0.03,
                    "why": "volume-linear applies F at the overlap's centroid (YADE's law), which "
                           "is not the gradient of a potential once the body turns: the 50-vertex "
                           "hull's large facets make it spin onto a face, and the law itself gains "
                           "or loses energy, 2.5 % (straight) and 1.6 % (oblique), the same at "
                           "steps of 8, 4 and 2 µs (not integration error)"}
            cname = f"volume-linear-{name}-{kind}"
            # Gap, then the contact (≈ π √(m/(kv A)) for the stiffest face, far less than 5 ms).
            c = case(cname, f"Rigid convex {name} (mass {mass:.4g} kg) dropped {kind} on a plane "
                     f"under volume-linear (kv = {KV:g} N/m³): the YADE polyhedra cross-check's case",
                     path, vel, expected, duration=0.005)
            c["scene"]["bodies"][0]["position"] = [0.0, 0.0, centroid_z]
            if name.startswith("hull-seed3-"):
                c["scene"]["dt"] = HULL_DT
                c["description"] += (f" ({len(v)} vertices: the generated particle's hull; "
                                     f"dt {HULL_DT:g} s, about 110 steps per contact)")
            written.append(c)
    written += friction_cases(bodies["cube-face"])
    # The faceted sphere under volume-hertz: Hertz within 3 %.
    # The regime of tests/fdem/test_volume_refinement.cpp: a soft sphere (E = 10 MPa, ρ = 2500,
    # R = 0.05 m) at 0.18 m/s, peak approach δ ≈ 0.02 R, so the contact disc (a ≈ 0.2 R) spans
    # about six facets at frequency 16.
    v, f = bodies["geodesic-sphere-16"]
    rs = 0.05
    density, young, poisson = 2500.0, 1e7, 0.3
    mass = density * 4 / 3 * math.pi * rs ** 3
    e_star = 1 / (2 * (1 - poisson ** 2) / young)  # plane of the same material
    vn = 0.18
    d = (15 * mass * vn * vn / (16 * e_star * math.sqrt(rs))) ** 0.4
    hertz_force = 4 / 3 * e_star * math.sqrt(rs) * d ** 1.5
    hertz_time = 2.9432 * d / vn
    name = "volume-hertz-geodesic-sphere-16-plane"
    why = ("Hertz (Johnson 1985, §11.4) for the sphere the facets approximate; 3 % is the issue's "
           "gate: at frequency 16 (5120 faces) the contact disc spans ~5 facets and the law's own "
           "O(δ/R) departure from Hertz is 0.3 % here (docs/physics.md)")
    expected = {
        "status": "ok",
        "peak_force": {"value": hertz_force, "rel_tol": 0.03, "why": why},
        "contact_duration": {"value": hertz_time, "rel_tol": 0.03, "why": why},
        "restitution": {"value": 1.0, "abs_tol": 1e-3,
                        "why": "volume-hertz is the gradient of W(V): elastic, to the integrator's error"},
        "energy_drift": {"max": 1e-3, "why": "conservative law, symplectic step: the issue's bound"},
    }
    c = case(name, "Rigid faceted sphere (geodesic, 5120 faces, R = 0.05 m, E = 10 MPa) on a plane under "
             "volume-hertz, against Hertz", mesh_file("geodesic-sphere-16", v, f), [0, 0, -vn],
             expected, law="volume-hertz", duration=0.05, young=young, density=density,
             poisson=poisson, tags=("polyhedra", "volume-hertz", "hertz"))
    c["scene"]["bodies"][0]["position"] = [0.0, 0.0, place(v, f, gap)]
    written.append(c)
    for c in written:
        with open(os.path.join(CASE_DIR, c["case"] + ".json"), "w") as out:
            json.dump(c, out, indent=2, ensure_ascii=False)
            out.write("\n")
    print(f"{len(written)} cases, {len(bodies)} meshes")


if __name__ == "__main__":
    main()
