# Rigid rock drop on a wall in YADE's level-set DEM (LS_DEM, Debian YADE 2023.02a): exploratory,
# not a gate (docs/crosscheck.md, "Non-convex particles: YADE's level-set DEM").
#
#   LS_OFF=data/meshes/particle-seed3-320.off LS_OUT=ls.json [LS_CELLS=30] [LS_NODES=2000] \
#   [LS_KN=1e6] [LS_V='[0,0,-1]'] yade -n -x peers/yade_levelset_drop.py
#
# The rock (a closed OFF surface) becomes a LevelSet: YADE takes no triangle mesh, so its signed
# distance is computed here on a regular grid of LS_CELLS cells across the rock's longest side, in
# the rock's principal frame (YADE assumes the body frame is principal); YADE then ray-traces
# LS_NODES surface nodes from the centre (star-shaped bodies only). It strikes a wall 20 µm below
# its lowest vertex at LS_V, frictionless, with Law2_ScGeom_FrictPhys_CundallStrack (F = kn u_n on
# the deepest node; sphericalBodies=False, else the force passes through the centre and the rock
# cannot spin) and no damping. Writes impulse, rebound velocity and spin, mass and inertia (LS
# against the exact mesh values) and timings to LS_OUT; the distance field is cached beside it.
import json, os, sys, time
import numpy as np
from yade import *
from yade import utils

off, out = os.environ["LS_OFF"], os.environ["LS_OUT"]
kn = float(os.environ.get("LS_KN", "1e6"))
cells = int(os.environ.get("LS_CELLS", "40"))
nodes = int(os.environ.get("LS_NODES", "2000"))
v0 = np.array(json.loads(os.environ.get("LS_V", "[0,0,-1]")), float)
density = 2650.0
tok = open(off).read().split()
nv, nf = int(tok[1]), int(tok[2])
V = np.array(tok[4:4 + 3 * nv], float).reshape(nv, 3)
F = np.array(tok[4 + 3 * nv:4 + 3 * nv + 4 * nf], int).reshape(nf, 4)[:, 1:]
# Exact volume, centroid, inertia (tetrahedra from the origin).
a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
vol6 = np.einsum("ij,ij->i", a, np.cross(b, c))
vol = vol6.sum() / 6
cen = ((a + b + c) * vol6[:, None]).sum(0) / 24 / vol
P = np.zeros((3, 3))
for t, w in zip(zip(a - cen, b - cen, c - cen), vol6 / 6):
    s = t[0] + t[1] + t[2]
    P += w / 20 * (np.outer(s, s) + sum(np.outer(q, q) for q in t))
I = density * (np.trace(P) * np.eye(3) - P)
ev, R = np.linalg.eigh(I)
if np.linalg.det(R) < 0:
    R[:, 2] *= -1
L = (V - cen) @ R  # local (principal) coordinates
h = (L.max(0) - L.min(0)).max() / cells
lo = L.min(0) - 3 * h
n = np.ceil((L.max(0) + 3 * h - lo) / h).astype(int) + 1
gx, gy, gz = (lo[i] + h * np.arange(n[i]) for i in range(3))
X, Y, Z = np.meshgrid(gx, gy, gz, indexing="ij")
pts = np.stack([X.ravel(), Y.ravel(), Z.ravel()], 1)
A, B, C = L[F[:, 0]], L[F[:, 1]], L[F[:, 2]]


def closest_dist(p, a, b, c):
    # Ericson's closest point on triangle, vectorized over points p.
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = ap @ ab, ap @ ac
    bp = p - b
    d3, d4 = bp @ ab, bp @ ac
    cp = p - c
    d5, d6 = cp @ ab, cp @ ac
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    denom = va + vb + vc
    denom = np.where(denom == 0, 1e-300, denom)
    v = vb / denom
    w = vc / denom
    q = a + v[:, None] * ab + w[:, None] * ac
    # regions
    m = (d1 <= 0) & (d2 <= 0); q[m] = a
    m = (d3 >= 0) & (d4 <= d3); q[m] = b
    m = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
    t = d1 / np.where(d1 - d3 == 0, 1e-300, d1 - d3); q[m] = a + t[m, None] * ab
    m = (d6 >= 0) & (d5 <= d6); q[m] = c
    m = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
    t = d2 / np.where(d2 - d6 == 0, 1e-300, d2 - d6); q[m] = a + t[m, None] * ac
    m = (va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0)
    t = (d4 - d3) / np.where((d4 - d3) + (d5 - d6) == 0, 1e-300, (d4 - d3) + (d5 - d6))
    q[m] = b + t[m, None] * (c - b)
    return np.linalg.norm(p - q, axis=1)


t0 = time.time()
cache = f"{out}.phi{cells}.npy"
if os.path.exists(cache):
    phi = np.load(cache)
else:
    phi = None
dist = np.full(len(pts) if phi is None else 0, np.inf)
for k in range(len(F) if phi is None else 0):
    dist = np.minimum(dist, closest_dist(pts, A[k], B[k], C[k]))
# Inside: parity of the triangles crossed by the ray +z from each point.
cross = np.zeros(len(pts), int)
for k in range(len(F) if phi is None else 0):
    a, b, c = A[k], B[k], C[k]
    det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
    if det == 0:
        continue
    u = ((pts[:, 0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (pts[:, 1] - a[1])) / det
    v = ((b[0] - a[0]) * (pts[:, 1] - a[1]) - (pts[:, 0] - a[0]) * (b[1] - a[1])) / det
    inside = (u >= 0) & (v >= 0) & (u + v <= 1)
    z = a[2] + u * (b[2] - a[2]) + v * (c[2] - a[2])
    cross += inside & (z > pts[:, 2])
if phi is None:
    phi = np.where(cross % 2 == 1, -dist, dist).reshape(n[0], n[1], n[2])
    np.save(cache, phi)
sdf_s = time.time() - t0

mat = O.materials.append(FrictMat(young=5e10, poisson=0.25, density=density, frictionAngle=0))
q = Quaternion(Matrix3(*R.ravel()))
low = (V[:, 2] - cen[2]).min()
start = Vector3(0, 0, -low + 2e-5)  # lowest vertex 20 µm above the wall
grid = RegularGrid(min=Vector3(*lo), nGP=Vector3i(*[int(x) for x in n]), spacing=h)
rock = levelSetBody(grid=grid, distField=phi.tolist(), center=start, orientation=q,
                    nSurfNodes=nodes, nodesPath=2, material=mat, dynamic=True)
rid = O.bodies.append(rock)
wid = O.bodies.append(utils.wall(0, axis=2, sense=1, material=mat))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_LevelSet_Aabb(), Bo1_Wall_Aabb()], verletDist=0),
    InteractionLoop([Ig2_Wall_LevelSet_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys(kn=MatchMaker(algo="val", val=kn),
                                                     ks=MatchMaker(algo="val", val=0))],
                    [Law2_ScGeom_FrictPhys_CundallStrack(sphericalBodies=False)]),
    NewtonIntegrator(damping=0, gravity=(0, 0, 0)),
]
st = O.bodies[rid].state
st.vel = Vector3(*v0)
m = st.mass
O.dt = 0.02 * 2 * (m / kn) ** 0.5
imp = np.zeros(3)
touched, steps, t1 = False, 0, time.time()
while steps < 2000000:
    O.step()
    steps += 1
    f = np.array(O.forces.f(rid))
    imp += f * O.dt
    if np.linalg.norm(f) > 0:
        touched = True
    elif touched:
        break
res = {"mass_ls": m, "mass_mesh": density * vol, "inertia_ls": list(st.inertia),
       "inertia_mesh": list(ev), "h": h, "grid": [int(x) for x in n], "nodes": nodes,
       "impulse": imp.tolist(), "v_after": list(st.vel), "w_after": list(st.angVel),
       "steps": steps, "dt": O.dt, "sdf_s": sdf_s, "run_s": time.time() - t1,
       # LevelSet.center(): YADE's own centroid of the level set, in local axes (0 if exact).
       "centre_ls": list(O.bodies[rid].shape.center())}
json.dump(res, open(out, "w"), indent=1)
print(json.dumps(res))
