#!/usr/bin/python3
"""Pictures of impacts at peak force, rendered from a run's ParaView frames (issue 15).

Each picture comes from a fresh `asperity run SCENE --vtk-every N` whose peak frame
(vtk/bodies_peak.vtu) is read with VTK's own XML reader (Debian's python3-vtk9) and drawn with
matplotlib (Agg). VTK's render window in Debian 12's python3-vtk9 (9.1) is X11 only (no OSMesa or
EGL build), so offscreen VTK rendering would need an X server (xvfb) that CI does not install;
matplotlib's 3-D polygons and 2-D triangles need nothing beyond deps/debian-packages.txt.

  --hertz SCENE --hertz-out DIR   a deformable sphere on a block: DIR/hertz_contact_zone.png and
                                  .svg (contact pressure seen from below with the Hertz contact
                                  radius, the von Mises section under the contact, pressure
                                  against radius beside Hertz's) and .json (the numbers); Hertz's
                                  numbers, his pressure curve and shear depth included, are
                                  asperity's (hertz_numbers, built beside ASPERITY:
                                  solver/contact/hertz_impact.hpp), this script measures the mesh
  --study DIR [--resolution N] [--placement P]  (P: the first placement the study ran)
                                  each particle of an `asperity study` folder, fem and rigid at
                                  N triangles side by side: DIR/pictures/impact_PARTICLE.png,
                                  which `asperity report` shows beside the force curves

Each picture (its runs and its drawing) is made in a process of its own, as many at once as there
are cores.

Exit 2 with one line for a missing input, 1 when a run fails.
"""
import argparse
import concurrent.futures
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402
import vtk  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

import study_report  # noqa: E402  (beside this file: the particles the report charts)

# A frame every this many steps: only frame 0, the peak and the last are written.
EVERY = 10**9
# Deterministic SVG (no date, fixed ids) so a re-run changes nothing that did not change.
matplotlib.rcParams["svg.hashsalt"] = "asperity"
SVG_META = {"Date": None}


class BadInput(Exception):
    pass


def run_scene(asperity, scene, out):
    """Runs the scene with frames; returns its summary."""
    r = subprocess.run([asperity, "run", scene, "--out", out, "--vtk-every", str(EVERY), "-q"],
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{scene}: asperity run exit {r.returncode}: {r.stderr.strip()[:200]}")
    with open(os.path.join(out, "summary.json")) as fh:
        return json.load(fh)


class Frame:
    """The moving bodies of one .vtu frame as numpy arrays, and their outer surface."""

    def __init__(self, path):
        if not os.path.exists(path):
            raise RuntimeError(f"{path}: no such frame")
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(path)
        reader.Update()
        grid = reader.GetOutput()
        if grid is None or grid.GetNumberOfPoints() == 0:
            raise RuntimeError(f"{path}: no points")
        self.grid = grid
        self.x = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
        pd, cd = grid.GetPointData(), grid.GetCellData()
        self.f = vtk_to_numpy(pd.GetArray("contact_force")).astype(float)
        self.u = vtk_to_numpy(pd.GetArray("displacement")).astype(float)
        self.von_mises = vtk_to_numpy(cd.GetArray("von_mises")).astype(float)
        self.body = vtk_to_numpy(cd.GetArray("body_id"))
        conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
        self.tets = conn.reshape(-1, 4)
        self.tris, self.tri_cell = self._surface()
        self.pressure = self._nodal_pressure()

    def _surface(self):
        """Boundary triangles (faces of one tetrahedron only), outward, with their tetrahedron."""
        faces = {}
        for k, t in enumerate(self.tets):
            for a, b, c, d in ((t[1], t[2], t[3], t[0]), (t[0], t[3], t[2], t[1]),
                               (t[0], t[1], t[3], t[2]), (t[0], t[2], t[1], t[3])):
                key = tuple(sorted((a, b, c)))
                if key in faces:
                    faces[key] = None
                else:
                    faces[key] = (a, b, c, d, k)
        tris, cells = [], []
        for v in faces.values():
            if v is None:
                continue
            a, b, c, d, k = v
            n = np.cross(self.x[b] - self.x[a], self.x[c] - self.x[a])
            if np.dot(n, self.x[d] - self.x[a]) > 0:  # the fourth node must lie behind the face
                b, c = c, b
            tris.append((a, b, c))
            cells.append(k)
        return np.array(tris, dtype=int), np.array(cells, dtype=int)

    def _nodal_pressure(self):
        """|contact force| of each surface node over its share (a third) of its triangles' area, Pa."""
        x = self.x
        area = 0.5 * np.linalg.norm(np.cross(x[self.tris[:, 1]] - x[self.tris[:, 0]],
                                             x[self.tris[:, 2]] - x[self.tris[:, 0]]), axis=1)
        share = np.zeros(len(x))
        for j in range(3):
            np.add.at(share, self.tris[:, j], area / 3)
        p = np.zeros(len(x))
        on = share > 0
        p[on] = np.linalg.norm(self.f[on], axis=1) / share[on]
        return p

    def volume(self):
        x, t = self.x - self.u, self.tets  # the undeformed mesh
        return float(np.sum(np.einsum("ij,ij->i", np.cross(x[t[:, 1]] - x[t[:, 0]], x[t[:, 2]] - x[t[:, 0]]),
                                      x[t[:, 3]] - x[t[:, 0]])) / 6)


def peak_time(vtk_dir):
    """The simulated time run.pvd lists for the peak frame, s."""
    m = re.search(r'timestep="([^"]+)" part="0" file="bodies_peak.vtu"', open(os.path.join(vtk_dir, "run.pvd")).read())
    if not m:
        raise RuntimeError(f"{vtk_dir}/run.pvd: no peak frame listed")
    return float(m.group(1))


def material(scene_path, body):
    with open(scene_path) as fh:
        s = json.load(fh)
    b = next(b for b in s["bodies"] if b["name"] == body)
    m = s["materials"][b["material"]]
    return m, b


def hertz_numbers(asperity, work, sphere):
    """Hertz's numbers for a sphere on a rigid flat (sphere: mass, radius, young, poisson, speed,
    and the force to draw the contact at), from the formulas' one place: the hertz_numbers
    program beside asperity (solver/contact/hertz_impact.hpp)."""
    program = os.path.join(os.path.dirname(os.path.abspath(asperity)), "hertz_numbers")
    given, got = os.path.join(work, "hertz_sphere.json"), os.path.join(work, "hertz_numbers.json")
    with open(given, "w") as fh:
        json.dump(sphere, fh)
    r = subprocess.run([program, given, got], stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{program}: exit {r.returncode}: {r.stderr.strip()[:200]}")
    with open(got) as fh:
        return json.load(fh)


def save(fig, out_dir, stem, svg):
    fig.savefig(os.path.join(out_dir, stem + ".png"), dpi=90, metadata={"Software": None})
    if svg:
        fig.savefig(os.path.join(out_dir, stem + ".svg"), metadata=SVG_META, dpi=90)
    plt.close(fig)


# ---------------------------------------------------------------------------------------------
# A deformable sphere on a block against Hertz

def hertz_picture(asperity, scene, out_dir, work):
    summary = run_scene(asperity, scene, os.path.join(work, "hertz"))
    frame = Frame(os.path.join(work, "hertz", "vtk", "bodies_peak.vtu"))
    m, b = material(scene, "ball")
    x0 = frame.x - frame.u
    centre0 = x0.mean(axis=0)
    radius = float(np.max(np.linalg.norm(x0 - centre0, axis=1)))
    f_peak = summary["peak_force"]
    # Hertz for the meshed sphere (its radius, its volume's mass) on the block, fixed and so rigid
    # in the model: the contact radius a, the pressure p0 √(1 − r²/a²) and the depth of the
    # deepest shear at the run's peak force (Johnson 1985, §4.2), and the impact's peak force for
    # the caption (§11.4).
    hertz = hertz_numbers(asperity, os.path.join(work, "hertz"),
                          {"mass": m["density"] * frame.volume(), "radius": radius, "young": m["young"],
                           "poisson": m["poisson"], "speed": abs(b["velocity"][2]), "force": f_peak})
    e_star, a, p0, f_hertz = hertz["e_star"], hertz["contact_radius"], hertz["peak_pressure"], hertz["peak_force"]

    x = frame.x
    centre = x.mean(axis=0)
    bottom = float(x[:, 2].min())
    r_xy = np.hypot(x[:, 0] - centre[0], x[:, 1] - centre[1])
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.4))

    # (1) the contact face from below: nodal pressure on the lower cap, and the Hertz circle.
    ax = axes[0]
    cap = frame.tris[np.all(x[frame.tris, 2] < bottom + 0.5 * radius, axis=1)]
    tri = Triangulation((x[:, 0] - centre[0]) * 1e3, (x[:, 1] - centre[1]) * 1e3, cap)
    pc = ax.tripcolor(tri, frame.pressure / 1e3, shading="gouraud", cmap="inferno", vmin=0,
                      rasterized=True)  # the SVG keeps its lines and text as vectors
    ax.triplot(tri, color="0.6", lw=0.25)
    t = np.linspace(0, 2 * math.pi, 200)
    ax.plot(a * 1e3 * np.cos(t), a * 1e3 * np.sin(t), "c-", lw=1.5, label=f"Hertz a = {a * 1e3:.1f} mm")
    lim = 3 * a * 1e3
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title("contact pressure seen from below (kPa)", fontsize=10)
    ax.legend(fontsize=8, loc="upper right")
    fig.colorbar(pc, ax=ax, shrink=0.85)

    # (2) the section y = centre: von Mises of the tetrahedra it cuts, under the contact.
    ax = axes[1]
    plane = vtk.vtkPlane()
    plane.SetOrigin(*centre)
    plane.SetNormal(0, 1, 0)
    cutter = vtk.vtkCutter()
    cutter.SetCutFunction(plane)
    cutter.SetInputData(frame.grid)
    cutter.Update()
    cut = cutter.GetOutput()
    pts = vtk_to_numpy(cut.GetPoints().GetData())
    vm = vtk_to_numpy(cut.GetCellData().GetArray("von_mises"))
    polys = []
    for i in range(cut.GetNumberOfCells()):
        ids = cut.GetCell(i).GetPointIds()
        polys.append([((pts[ids.GetId(j), 0] - centre[0]) * 1e3, (pts[ids.GetId(j), 2] - bottom) * 1e3)
                      for j in range(ids.GetNumberOfIds())])
    col = PolyCollection(polys, array=vm / 1e3, cmap="viridis", edgecolors="0.3", linewidths=0.15,
                         rasterized=True)
    ax.add_collection(col)
    ax.axvline(-a * 1e3, color="c", lw=1)
    ax.axvline(a * 1e3, color="c", lw=1, label="±a (Hertz)")
    depth = hertz["max_shear_depth"]
    ax.plot([0], [depth * 1e3], "w+", ms=10, mew=2, label=f"{depth / a:.2f}a: Hertz's deepest shear peak")
    ax.set_xlim(-lim, lim)
    ax.set_ylim(0, 1.5 * lim)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("height above the lowest point (mm)")
    ax.set_title("von Mises stress, section through the axis (kPa)", fontsize=10)
    ax.legend(fontsize=7, loc="upper right")
    fig.colorbar(col, ax=ax, shrink=0.85)

    # (3) pressure against radius, every loaded surface node, beside p0 √(1 − r²/a²).
    ax = axes[2]
    loaded = frame.pressure > 0
    ax.plot(r_xy[loaded] * 1e3, frame.pressure[loaded] / 1e3, "o", ms=3, label="nodes (|F| / area share)")
    profile = hertz["pressure_profile"]
    ax.plot(np.array(profile["radius"]) * 1e3, np.array(profile["pressure"]) / 1e3, "c-", lw=1.5,
            label=f"Hertz, p0 = {p0 / 1e3:.0f} kPa")
    ax.set_xlim(0, 2 * a * 1e3)
    ax.set_xlabel("r (mm)")
    ax.set_ylabel("contact pressure (kPa)")
    ax.set_title("pressure against radius", fontsize=10)
    ax.legend(fontsize=8)
    fig.suptitle(f"{os.path.basename(scene)} at peak force (t = {peak_time(os.path.join(work, 'hertz', 'vtk')) * 1e3:.2f} ms): "
                 f"F = {f_peak:.1f} N (Hertz impact of the meshed mass: {f_hertz:.1f} N, "
                 f"{100 * (f_peak / f_hertz - 1):+.1f} %); {len(frame.tets)} tetrahedra. Hertz lines at the run's F.",
                 fontsize=10)
    fig.tight_layout()
    save(fig, out_dir, "hertz_contact_zone", svg=True)
    # The numbers behind the picture: the load it shows, and the loaded patch against a.
    lower = frame.tris[np.all(x[frame.tris, 2] < bottom + 2 * a, axis=1)]
    edges = np.concatenate([x[lower[:, j]] - x[lower[:, (j + 1) % 3]] for j in range(3)])
    numbers = {"scene": os.path.basename(scene), "tetrahedra": int(len(frame.tets)),
               "peak_force": f_peak, "hertz_impact_force": f_hertz, "radius": radius, "e_star": e_star,
               "contact_radius_hertz": a, "p0_hertz": p0,
               "nodal_force_sum": float(np.linalg.norm(frame.f, axis=1).sum()),
               "nodal_force_resultant": float(np.linalg.norm(frame.f.sum(axis=0))),
               "patch_radius": float(r_xy[loaded].max()) if loaded.any() else 0.0,
               "longest_edge_near_contact": float(np.linalg.norm(edges, axis=1).max()),
               "max_pressure": float(frame.pressure.max()), "max_von_mises": float(frame.von_mises.max())}
    with open(os.path.join(out_dir, "hertz_contact_zone.json"), "w") as fh:
        json.dump(numbers, fh, indent=1)
        fh.write("\n")
    return numbers


# ---------------------------------------------------------------------------------------------
# A study particle, fem and rigid

def surface_panel(ax, frame, values, vmax, cmap, title):
    x = frame.x * 1e3
    polys = x[frame.tris]
    norm = matplotlib.colors.Normalize(vmin=0, vmax=vmax if vmax > 0 else 1)
    colours = plt.get_cmap(cmap)(norm(values))
    col = Poly3DCollection(polys, facecolors=colours, edgecolors="0.35", linewidths=0.1)
    ax.add_collection3d(col)
    lo, hi = x.min(axis=0), x.max(axis=0)
    mid, half = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_zlim(mid[2] - half, mid[2] + half)
    ax.set_box_aspect((1, 1, 1), zoom=1.4)
    ax.view_init(elev=-35, azim=-60)  # from below: the contact side faces the camera
    ax.set_axis_off()
    ax.set_title(title, fontsize=9)
    sm = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
    plt.colorbar(sm, ax=ax, shrink=0.6, pad=0.0)


def study_plan(study, resolution, placement):
    """The study's particles with fem and rigid cases at `resolution`: (particle, placement, cases)."""
    cases = os.path.join(study, "cases")
    if not os.path.isdir(cases):
        raise BadInput(f"{study}: no cases/ folder (not an asperity study folder)")
    # The particles the report charts (study_report.chart_particles: all of a small study, a selection
    # of a large one), when the study has written its table.
    chosen = None
    if os.path.exists(os.path.join(study, "cases.csv")):
        chosen = set(study_report.chart_particles(study_report.read_csv(os.path.join(study, "cases.csv")))[0])
    plan = []
    for particle in sorted(os.listdir(cases)):
        if chosen is not None and particle not in chosen:
            continue
        # Without --placement, the first placement the study ran for this particle.
        placements = [placement] if placement else ["centroid", "lowest"]
        placement_here = next((p for p in placements if all(
            os.path.exists(os.path.join(cases, particle, f"{m}-{resolution}-{p}", "scene.json"))
            for m in ("fem", "rigid"))), placements[0])
        dirs = {m: os.path.join(cases, particle, f"{m}-{resolution}-{placement_here}") for m in ("fem", "rigid")}
        if all(os.path.exists(os.path.join(d, "scene.json")) for d in dirs.values()):
            plan.append((particle, placement_here, dirs))
    return plan


def particle_picture(asperity, particle, placement_here, dirs, resolution, out_dir, work):
    """One particle's fem and rigid impact side by side: out_dir/impact_PARTICLE.png."""
    runs = {}
    for model in ("fem", "rigid"):
        case = dirs[model]
        out = os.path.join(work, particle, model)
        summary = run_scene(asperity, os.path.join(case, "scene.json"), out)
        with open(os.path.join(case, "summary.json")) as fh:
            study_peak = json.load(fh).get("peak_force")
        if study_peak and abs(summary["peak_force"] / study_peak - 1) > 1e-9:
            print(f"impact_pictures: warning: {particle} {model}: peak {summary['peak_force']} N, "
                  f"the study's {study_peak} N (a different build?)", file=sys.stderr)
        runs[model] = (summary, Frame(os.path.join(out, "vtk", "bodies_peak.vtu")))
    fem, rigid = runs["fem"][1], runs["rigid"][1]
    # Each surface triangle takes its tetrahedron's stress, and the mean of its nodes' pressure.
    p_fem = fem.pressure[fem.tris].mean(axis=1)
    p_rigid = rigid.pressure[rigid.tris].mean(axis=1)
    p_max = max(p_fem.max(), p_rigid.max()) / 1e6
    fig = plt.figure(figsize=(13, 4.6))
    vm = fem.von_mises[fem.tri_cell] / 1e6
    surface_panel(fig.add_subplot(1, 3, 1, projection="3d"), fem, vm, vm.max(), "viridis",
                  f"fem: von Mises stress (MPa), max {vm.max():.0f}")
    surface_panel(fig.add_subplot(1, 3, 2, projection="3d"), fem, p_fem / 1e6, p_max, "YlOrRd",
                  f"fem: contact pressure (MPa)\npeak force {runs['fem'][0]['peak_force']:.0f} N")
    surface_panel(fig.add_subplot(1, 3, 3, projection="3d"), rigid, p_rigid / 1e6, p_max, "YlOrRd",
                  (f"rigid: contact pressure (MPa)\npeak force {runs['rigid'][0]['peak_force']:.0f} N"
                   if p_rigid.max() > 0 else
                   # The volume laws act on the body at the overlap's centroid: no nodal forces.
                   f"rigid (volume law): one force at the overlap centroid,\nno surface pressure; "
                   f"peak force {runs['rigid'][0]['peak_force']:.0f} N"))
    fig.suptitle(f"{particle}, {resolution} triangles, placed by {placement_here}: the peak-force frames, "
                 "seen from below", fontsize=10)
    fig.subplots_adjust(left=0.01, right=0.97, top=0.86, bottom=0.02, wspace=0.08)
    save(fig, out_dir, f"impact_{particle}", svg=False)
    return particle


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--asperity", required=True)
    ap.add_argument("--hertz")
    ap.add_argument("--hertz-out")
    ap.add_argument("--study")
    ap.add_argument("--resolution", default="1000")
    ap.add_argument("--placement", help="centroid or lowest (default: the first the study ran)")
    a = ap.parse_args()
    if a.hertz and not os.path.exists(a.hertz):
        raise BadInput(f"{a.hertz}: --hertz: no such scene")
    if a.study and not os.path.isdir(a.study):
        raise BadInput(f"{a.study}: --study: no such folder")
    work = tempfile.mkdtemp(prefix="asperity_pictures_")
    try:
        # Each picture (its runs, then its drawing) in a process of its own, on every core: the
        # particles first, the Hertz picture (the cheapest) last.
        plan = study_plan(a.study, a.resolution, a.placement) if a.study else []
        if a.study:
            os.makedirs(os.path.join(a.study, "pictures"), exist_ok=True)
        if a.hertz:
            os.makedirs(a.hertz_out, exist_ok=True)
        with concurrent.futures.ProcessPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
            pictures = [pool.submit(particle_picture, a.asperity, particle, placement_here, dirs,
                                    a.resolution, os.path.join(a.study, "pictures"), work)
                        for particle, placement_here, dirs in plan]
            hertz = pool.submit(hertz_picture, a.asperity, a.hertz, a.hertz_out, work) if a.hertz else None
            if hertz:
                h = hertz.result()
                print(f"impact_pictures: {a.hertz_out}/hertz_contact_zone.png: peak {h['peak_force']:.1f} N "
                      f"(Hertz {h['hertz_impact_force']:.1f} N), a = {h['contact_radius_hertz'] * 1e3:.2f} mm, "
                      f"p0 = {h['p0_hertz'] / 1e3:.0f} kPa, nodal max {h['max_pressure'] / 1e3:.0f} kPa")
            made = [f.result() for f in pictures]
        if a.study:
            print(f"impact_pictures: {len(made)} particle pictures in {a.study}/pictures")
            if not made:
                print(f"impact_pictures: warning: no particle of {a.study} has fem and rigid cases at "
                      f"{a.resolution} triangles" + (f", placed by {a.placement}" if a.placement else ""),
                      file=sys.stderr)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    try:
        main()
    except BadInput as e:
        print(f"impact_pictures: {e}", file=sys.stderr)
        sys.exit(2)
    except RuntimeError as e:
        print(f"impact_pictures: {e}", file=sys.stderr)
        sys.exit(1)
