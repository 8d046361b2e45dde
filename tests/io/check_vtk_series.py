#!/usr/bin/python3
"""Checks a run's ParaView series (DIR/vtk/, run/vtk_series.hpp) with VTK's own readers.

usage: check_vtk_series.py RUN_DIR SCENE.json

- run.pvd parses with VTK's XML parser, lists its frames in time order, and every file it lists
  exists and loads with VTK's XML readers without an error;
- point counts equal the bodies' nodes (mesh scenes: summary.json "bodies") or the spheres;
- at the last frame, displacement equals position minus the first frame's position (round-off:
  1e-12 of the scene's extent, since both are differences of the same doubles);
- at the peak frame the contact force summed over the recorded body's points equals force.csv
  at that time to 1e-9 relative (force.csv keeps 10 significant digits: 5e-10 at worst), and its
  magnitude equals summary.json's peak_force to the same tolerance.
Exit 0 when all hold; otherwise one line per failure and exit 1.
"""
import csv
import json
import os
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


class Errors:
    """Collects VTK's error events, which the readers raise instead of returning a status."""

    def __init__(self):
        self.seen = []

    def __call__(self, obj, event):
        self.seen.append(event)


def load(path):
    reader = vtk.vtkXMLGenericDataObjectReader()
    errors = Errors()
    reader.AddObserver("ErrorEvent", errors)
    reader.SetFileName(path)
    reader.Update()
    out = reader.GetOutput()
    check(not errors.seen and out is not None, f"{path}: VTK could not read it")
    return out


def array(data, name, cells=False):
    fields = data.GetCellData() if cells else data.GetPointData()
    a = fields.GetArray(name)
    check(a is not None, f"missing array {name}")
    return vtk_to_numpy(a) if a is not None else None


def main(run_dir, scene_file):
    summary = json.load(open(os.path.join(run_dir, "summary.json")))
    scene = json.load(open(scene_file))
    vtk_dir = os.path.join(run_dir, "vtk")
    parser = vtk.vtkXMLDataParser()
    parser.SetFileName(os.path.join(vtk_dir, "run.pvd"))
    check(parser.Parse() == 1, "run.pvd: VTK's XML parser rejects it")
    root = parser.GetRootElement()
    check(root.GetAttribute("type") == "Collection", "run.pvd: not a Collection")
    collection = root.GetNestedElement(0)
    entries = []
    for i in range(collection.GetNumberOfNestedElements()):
        e = collection.GetNestedElement(i)
        entries.append((float(e.GetAttribute("timestep")), int(e.GetAttribute("part")),
                        e.GetAttribute("file")))
    times = [t for t, _, _ in entries]
    check(times == sorted(times), "run.pvd: frames not in time order")
    frames = [(t, f) for t, p, f in entries if p == 0]
    check(len(frames) >= 3, f"run.pvd: {len(frames)} frames (want the first, the peak, the last)")
    data = {}
    for _, _, f in entries:
        if f not in data:
            check(os.path.exists(os.path.join(vtk_dir, f)), f"run.pvd lists {f}, which is absent")
            data[f] = load(os.path.join(vtk_dir, f))

    mesh = summary.get("model") == "fdem"
    if mesh:
        moving = sum(b["nodes"] for b in summary["bodies"] if b["model"] != "fixed")
        fixed = sum(b["nodes"] for b in summary["bodies"] if b["model"] == "fixed")
        names = [b["name"] for b in summary["bodies"]]
        for t, p, f in entries:
            want = moving if p == 0 else fixed
            check(data[f].GetNumberOfPoints() == want,
                  f"{f}: {data[f].GetNumberOfPoints()} points, the mesh has {want} nodes")
    else:
        spheres = [b for b in scene["bodies"] if b["shape"]["type"] == "sphere"]
        names = [b["name"] for b in scene["bodies"]]
        for t, f in frames:
            check(data[f].GetNumberOfPoints() == len(spheres),
                  f"{f}: {data[f].GetNumberOfPoints()} points for {len(spheres)} spheres")

    first = data[frames[0][1]]
    x0 = vtk_to_numpy(first.GetPoints().GetData())
    regular = [(t, f) for t, f in frames if "peak" not in f]
    last = data[regular[-1][1]]
    x1 = vtk_to_numpy(last.GetPoints().GetData())
    extent = max(np.ptp(x0, axis=0).max(), 1e-3)
    u = array(last, "displacement")
    err = np.abs(u - (x1 - x0)).max()
    check(err <= 1e-12 * extent, f"last frame: displacement differs from x - x0 by {err:.3g} m")
    check(abs(regular[-1][0] - summary["simulated_time"]) <= 1e-12 * summary["simulated_time"],
          "last frame is not at the run's end")

    peaks = [(t, f) for t, f in frames if "peak" in f]
    recorded = names.index(summary["recorded_body"])
    if peaks:
        t_peak, f_peak = peaks[0]
        frame = data[f_peak]
    else:  # the peak step was a regular frame
        rows = list(csv.DictReader(open(os.path.join(run_dir, "force.csv"))))
        best = max(rows, key=lambda r: float(r["f"]))
        t_peak = float(best["t"])
        t_peak, f_name = min(frames, key=lambda tf: abs(tf[0] - t_peak))
        frame = data[f_name]
    force = array(frame, "contact_force")
    if mesh:
        cells = vtk_to_numpy(frame.GetCells().GetConnectivityArray()).reshape(-1, 4)
        body = array(frame, "body_id", cells=True)
        nodes = np.unique(cells[body == recorded])
        total = force[nodes].sum(axis=0)
    else:
        body = array(frame, "body_id")
        total = force[body == recorded].sum(axis=0)
    rows = list(csv.DictReader(open(os.path.join(run_dir, "force.csv"))))
    row = min(rows, key=lambda r: abs(float(r["t"]) - t_peak))
    csv_f = np.array([float(row["fx"]), float(row["fy"]), float(row["fz"])])
    scale = np.linalg.norm(csv_f)
    check(scale > 0, "force.csv: no force at the peak frame's time")
    rel = np.abs(total - csv_f).max() / scale
    check(rel <= 1e-9, f"peak frame t = {t_peak}: summed contact force {total} vs force.csv "
          f"{csv_f} ({rel:.3g} relative)")
    rel_peak = abs(np.linalg.norm(total) - summary["peak_force"]) / summary["peak_force"]
    check(rel_peak <= 1e-9, f"peak frame: |F| = {np.linalg.norm(total)} vs peak_force "
          f"{summary['peak_force']} ({rel_peak:.3g} relative)")
    if mesh:
        vm = array(frame, "von_mises", cells=True)
        deformable = [i for i, b in enumerate(summary["bodies"]) if b["model"] == "fem"]
        if deformable:
            check(vm[np.isin(body, deformable)].max() > 0, "peak frame: no stress in a fem body")
    for f in failures:
        print(f"{run_dir}: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
