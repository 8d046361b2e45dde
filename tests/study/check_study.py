#!/usr/bin/python3
"""End-to-end check of asperity study / report / recommend (tests/study/CMakeLists.txt).

Usage: check_study.py ASPERITY SMOKE_STUDY.json WORK_DIR. Exit 0 when every check passes; each
failure is printed. Leaves WORK_DIR/report/screenshot.png (the HTML report in headless Chromium).
"""
import csv
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile

binary, study_file, work = sys.argv[1], sys.argv[2], sys.argv[3]
failures = []


def check(name, ok, detail=""):
    if not ok:
        failures.append(name)
        print(f"FAIL: {name} {detail}")


def run(*args):
    return subprocess.run([binary, *args], capture_output=True, text=True)


def png_size(path):
    """(width, height) of a PNG, or None when the file does not start as a PNG does."""
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
study = os.path.join(work, "study")
report = os.path.join(work, "report")

# 1. The study runs to the end.
r = run("study", study_file, "--out", study, "-q")
check("study exits 0", r.returncode == 0, r.stderr)
with open(os.path.join(study, "study_summary.json")) as f:
    summary = json.load(f)
# 2 particles x (fem 2 resolutions x 2 placements + 1 refined, rigid 2 x 2, sphere-local 2) = 22
NCASES = 22
check(f"{NCASES} cases, all done", summary["cases"] == NCASES and summary["done"] == NCASES and summary["failed"] == 0,
      summary)

# 2. Resumable: a second run keeps every case.
r = run("study", study_file, "--out", study, "-q")
with open(os.path.join(study, "study_summary.json")) as f:
    again = json.load(f)
check("rerun keeps every case", r.returncode == 0 and again["last_run"]["ran"] == 0 and again["last_run"]["kept"] == NCASES,
      again["last_run"])
# the wall time that computed the cases is the first run's, and a rerun that only kept cases adds none
check("computing wall time survives the rerun",
      again["runs_computing"] == 1 and again["wall_seconds_computing"] == summary["last_run"]["wall_seconds"],
      (again.get("runs_computing"), again.get("wall_seconds_computing"), summary["last_run"]))

# 3. Bad input: one line, exit 2, naming the key.
bad = os.path.join(work, "bad.json")
with open(study_file) as f:
    j = json.load(f)
j["resolution"] = [100]
j["particles"]["set"] = os.path.join(os.path.dirname(os.path.abspath(study_file)), j["particles"]["set"])
with open(bad, "w") as f:
    json.dump(j, f)
r = run("study", bad, "--out", os.path.join(work, "bad"))
check("unknown key exits 2", r.returncode == 2, r.returncode)
check("one line naming the key", r.stderr.count("\n") == 1 and "resolution" in r.stderr and "resolutions" in r.stderr,
      r.stderr)
check("nothing written for bad input", not os.path.exists(os.path.join(work, "bad")))
# refinement.max_contact_factor as the scene key: 0 or at least 1
j.pop("resolution")
j["refinement"]["max_contact_factor"] = 0.5
with open(bad, "w") as f:
    json.dump(j, f)
r = run("study", bad, "--out", os.path.join(work, "bad"))
check("max_contact_factor below 1 exits 2 naming it",
      r.returncode == 2 and r.stderr.count("\n") == 1 and "max_contact_factor" in r.stderr, (r.returncode, r.stderr))
# "reference": "source" or "finest" (issue 28)
j["refinement"].pop("max_contact_factor")
j["reference"] = "particle"
with open(bad, "w") as f:
    json.dump(j, f)
r = run("study", bad, "--out", os.path.join(work, "bad"))
check("a reference other than source or finest exits 2 naming it",
      r.returncode == 2 and r.stderr.count("\n") == 1 and "reference" in r.stderr and "source" in r.stderr,
      (r.returncode, r.stderr))
check("nothing written for a bad reference", not os.path.exists(os.path.join(work, "bad")))

# 4. The report: files, tables, charts, numbers equal to the cases' summary.json.
r = run("report", study, "--out", report)
check("report exits 0", r.returncode == 0, r.stderr)
for name in ["report.md", "report.html", "cases.csv", "references.csv", "classification.csv", "particle_classes.csv", "cpu_fit.csv",
             "candidates.csv", "guidelines.csv", "discretization.csv", "answer.csv", "few_hundred.csv",
             "unreferenced.csv", "cpu_vs_resolution.png", "accuracy_vs_cost.png"]:
    check(f"{name} present", os.path.isfile(os.path.join(report, name)) and os.path.getsize(os.path.join(report, name)) > 0)
tables = {}
for name in os.listdir(report):
    if name.endswith(".csv"):
        with open(os.path.join(report, name), newline="") as f:
            rows = list(csv.DictReader(f))
        # unreferenced.csv is the header alone when every particle has its reference.
        check(f"{name} parses with rows", (len(rows) > 0 or name == "unreferenced.csv") and
              all(None not in r for r in rows))
        tables[name] = rows
pngs = [n for n in os.listdir(report) if n.endswith(".png")]
check("a force chart per particle", sum(n.startswith("force_") for n in pngs) == 2, pngs)
for name in pngs:
    size = png_size(os.path.join(report, name))
    # 200 px: the smallest chart is 6 in at 72-80 dpi; a blank or broken figure comes out tiny
    check(f"{name} is a PNG image", size is not None and size[0] >= 200 and size[1] >= 150, size)
cases = tables.get("cases.csv", [])
check(f"cases.csv: {NCASES} rows", len(cases) == NCASES, len(cases))
keys = {"peak_force": "peak_force", "impulse": "impulse", "contact_duration": "contact_duration",
        "first_contact_time": "first_contact_time", "steps": "steps", "dt": "dt"}
summaries = {}
for row in cases:
    h = f"h{float(row['element_size_rel']):g}-" if row["element_size_rel"] else ""
    folder = f"{row['model']}-{row['resolution']}-{h}{row['placement']}"
    if row["model"] == "sphere-local":
        folder = f"sphere-local-{row['placement']}"
    with open(os.path.join(study, "cases", row["particle"], folder, "summary.json")) as f:
        s = json.load(f)
    summaries[(row["particle"], folder)] = s
    with open(os.path.join(study, "cases", row["particle"], folder, "case.json")) as f:
        record = json.load(f)
    # the study's own facts go to case.json, the runner's summary.json keeps the contract's keys
    check(f"{row['particle']} {folder} summary.json has no study keys",
          "element_size" not in s and "cpu_seconds_thread" not in s, sorted(set(s) & {"element_size", "cpu_seconds_thread"}))
    # the element size: empty for the coarse default, else the value the case ran with (its scene's)
    with open(os.path.join(study, "cases", row["particle"], folder, "scene.json")) as f:
        ran_with = json.load(f)["bodies"][0]["shape"].get("element_size")
    check(f"{row['particle']} {folder} element_size equals case.json and scene.json",
          (row["element_size"] == "" and record["element_size"] is None and ran_with is None) or
          (row["element_size"] != "" and float(row["element_size"]) == record["element_size"] == ran_with),
          (row["element_size"], record.get("element_size"), ran_with))
    check(f"{row['particle']} {folder} cpu_seconds equals case.json", float(row["cpu_seconds"]) == float(record["cpu_seconds"]),
          (row["cpu_seconds"], record["cpu_seconds"]))
    for col, key in keys.items():
        # exact: the table writes the shortest decimal that reads back to the same double
        check(f"{row['particle']} {folder} {col} equals summary.json", float(row[col]) == float(s[key]),
              (row[col], s[key]))
    with open(os.path.join(study, "cases", row["particle"], folder, "scene.json")) as f:
        scene = json.load(f)
    if row["model"] == "fem":  # the study's penalty_alpha reaches the scene: p = 100 x E (50 GPa)
        check(f"{row['particle']} {folder} penalty = 100 E", s["penalty"] == 100 * 5e10, s["penalty"])
        check(f"{row['particle']} {folder} penalty_alpha reported", s["penalty_alpha"] == 100, s["penalty_alpha"])
        # the fem's block is rigid by construction (a fixed block): its material as the study's
        check(f"{folder} block material as given", scene["materials"]["block"]["young"] == 5e10)
    elif row["model"] == "sphere-local":
        # Hertz on a sphere of radius sqrt(R1 R2), the principal radii at the reference mesh's lowest vertex
        # (case.json), carrying the particle's mass (the reference mesh's volume at the study's density), onto a
        # rigid block (E* = E/(1 - nu^2) to 1e-6: the block's E is 1e6 times the particle's)
        with open(os.path.join(study, "cases", row["particle"], folder, "case.json")) as f:
            rec = json.load(f)
        r1, r2 = rec["local_radii"]
        radius = scene["bodies"][0]["shape"]["radius"]
        check(f"{row['particle']} {folder}: radius = sqrt(R1 R2)", abs(radius - (r1 * r2) ** 0.5) <= 1e-12 * radius,
              (radius, r1, r2))
        with open(os.path.join(study, "meshes", row["particle"], "250", "mesh.json")) as f:
            volume = json.load(f)["volume"]
        rho = scene["materials"]["particle-local"]["density"]
        check(f"{row['particle']} {folder}: the particle's mass", abs(rho * 4 / 3 * 3.141592653589793 * radius ** 3 -
                                                                      2650 * volume) <= 1e-9 * 2650 * volume)
        check(f"{folder}: rigid block", scene["materials"]["block"]["young"] == 1e6 * 5e10)
        check(f"{folder}: Hertz law", scene["contact"]["law"] == "hertz")
    else:
        # the rigid polyhedron strikes under the elastic volume law, no penalty, on a rigid block (as the fem)
        check(f"{row['particle']} {folder} rigid under volume-hertz",
              s.get("contact_law") == "volume-hertz" and "penalty" not in s, (s.get("contact_law"), s.get("penalty")))
        check(f"{folder}: rigid block", scene["materials"]["block"]["young"] == 1e6 * 5e10)
    # every case's contact ends well inside the window, so every case stops after separation
    if row["model"] != "sphere-local":  # the sphere's DEM run stops at separation by itself
        check(f"{row['particle']} {folder} ended by separation", s["ended_by"] == "separation", s["ended_by"])
    if row["resolution"] == "250":  # the reference of this study: its own errors are 0
        check(f"{folder} reference error 0", float(row["peak_force_err"]) == 0.0)

# The two axes (issue 12). Each (particle, 250, lowest) fem sequence: coarse, then h = 0.15 R. With one refined level
# there is no extrapolation: the limit is the finest level, its error the last change (docs/study.md, "Guidelines").
limit_errors = []
for p in sorted({r["particle"] for r in cases}):
    seq = [r for r in cases if r["particle"] == p and r["model"] == "fem" and r["resolution"] == "250"
           and r["placement"] == "lowest"]
    coarse = next(r for r in seq if r["element_size"] == "")
    fine = next(r for r in seq if r["element_size"] != "")
    sc = summaries[(p, "fem-250-lowest")]
    sf = summaries[(p, "fem-250-h0.15-lowest")]
    # the answer is the finest level; converged when the last refinement moved the peak < 1 %
    change = abs(sc["peak_force"] - sf["peak_force"]) / abs(sf["peak_force"])
    limit_errors.append(change)
    check(f"{p}: the refined case is the answer", fine["answer"] == "true" and coarse["answer"] == "false",
          (fine["answer"], coarse["answer"]))
    check(f"{p}: converged flag from the summaries", fine["converged"] == ("true" if change < 0.01 else "false")
          and coarse["converged"] == "false", (fine["converged"], change))
    check(f"{p}: convergence_change from the summaries", abs(float(fine["convergence_change"]) - change) <= 1e-12 * change,
          (fine["convergence_change"], change))
    check(f"{p}: one refined level, no extrapolation", fine["extrapolated_peak_force"] == "" and
          fine["extrapolation_error"] == "" and fine["extrapolation_order"] == "", fine)
    # discretization error: coarse against the limit (here the finest level) at the same resolution
    d = (sc["peak_force"] - sf["peak_force"]) / sf["peak_force"]
    check(f"{p}: discretization_error from the summaries", abs(float(coarse["discretization_error"]) - d) <= 1e-12 * abs(d)
          and float(fine["discretization_error"]) == 0.0, (coarse["discretization_error"], d))
    # the refined mesh keeps the geometry: the same volume (mass at one density; TetGen's
    # tetrahedra fill the same closed surface, so to round-off) and the same placement relative
    # to the centroid (the lowest point strikes at the same time: within one coarse step, the
    # resolution of the first-contact interpolation's neighbourhood)
    mc, mf = sc["bodies"][0]["mass"], sf["bodies"][0]["mass"]
    check(f"{p}: refined volume equals coarse", abs(mc - mf) <= 1e-9 * mc, (mc, mf))
    check(f"{p}: refined mesh has more tetrahedra", sf["bodies"][0]["tets"] > sc["bodies"][0]["tets"],
          (sc["bodies"][0]["tets"], sf["bodies"][0]["tets"]))
    # refinement.max_contact_factor reaches the refined case alone (the coarse one keeps the penalty as asked)
    check(f"{p}: the refined case meets the study's contact factor, the coarse none",
          sf["max_contact_factor"] == 2 and sc["max_contact_factor"] == 0,
          (sf["max_contact_factor"], sc["max_contact_factor"]))
    check(f"{p}: refined centroid and strike point equal coarse (same first contact)",
          abs(sc["first_contact_time"] - sf["first_contact_time"]) <= sc["dt"],
          (sc["first_contact_time"], sf["first_contact_time"], sc["dt"]))
# references.csv: the reference of each (particle, lowest) is the limit at 250 (one refined level: its own value), its
# discretization term the last change, no geometry term (100 is not refined), the uncertainty their quadrature sum.
lowest_refs = [r for r in tables.get("references.csv", []) if r["placement"] == "lowest"]
for ref in lowest_refs:
    p = ref["particle"]
    sc, sf = summaries[(p, "fem-250-lowest")], summaries[(p, "fem-250-h0.15-lowest")]
    change = abs(sc["peak_force"] - sf["peak_force"]) / abs(sf["peak_force"])
    check(f"{p}: references.csv peak force is the finest level's", float(ref["peak_force"]) == sf["peak_force"],
          (ref["peak_force"], sf["peak_force"]))
    check(f"{p}: references.csv discretization term is the last change",
          abs(float(ref["peak_force_discretization"]) - change) <= 1e-12 * change and ref["peak_force_geometry"] == ""
          and ref["geometry_from"] == "", ref)
    check(f"{p}: references.csv uncertainty is the quadrature sum",
          abs(float(ref["peak_force_uncertainty"]) - change) <= 1e-12 * change, ref)
check("references.csv: a row per particle at the lowest placement",
      sorted(r["particle"] for r in lowest_refs) == sorted({r["particle"] for r in cases}),
      tables.get("references.csv"))
# The response classes: shifted exactly when the first contact moved by more than 5 % of the reference duration (the
# shift equals cases.csv's first_contact_shift_fem), tail above 1.1 times its duration, short below 0.9.
err_fem = {(r["particle"], r["model"], r["resolution"], r["placement"]): r for r in cases if not r["element_size"]}
for c in tables.get("classification.csv", []):
    labels = c["class"].split("+")
    row = err_fem[(c["particle"], c["model"], c["resolution"], c["placement"])]
    shift, ratio = float(c["first_contact_shift_rel"]), float(c["duration_ratio"])
    check(f"{c['particle']} {c['model']} {c['resolution']} {c['placement']}: shift as cases.csv",
          shift == float(row["first_contact_shift_fem"]), (shift, row["first_contact_shift_fem"]))
    check(f"{c['particle']} {c['model']} {c['resolution']} {c['placement']}: classes from the measures",
          ("shifted" in labels) == (abs(shift) > 0.05) and ("tail" in labels) == (ratio > 1.1)
          and ("short" in labels) == (ratio < 0.9), c)
fits = tables.get("cpu_fit.csv", [])
check("CPU fit for fem and rigid", {f["model"] for f in fits} == {"fem", "rigid"}, fits)
with open(os.path.join(report, "report.md")) as f:
    md = f.read()
for f_ in fits:
    check("report.md shows the fitted exponent", f"{float(f_['exponent']):.3g}" in md)
for g in tables.get("guidelines.csv", []):
    check("guideline model known", g["model"] in ("fem", "rigid", "rigid-penalty", "sphere", "sphere-local"), g)
    check("guideline carries the reference uncertainty", g["reference_uncertainty"] != "", g)
check("guidelines cover the four metrics",
      {g["metric"] for g in tables.get("guidelines.csv", [])} >=
      {"peak_force", "impulse", "contact_duration", "first_contact_time"},
      {g["metric"] for g in tables.get("guidelines.csv", [])})
# What a converged answer costs (report.md, 'Geometry and discretization'): the worst particle's sequence at 250
# triangles (the coarse case and its refined level, lowest placement) is the sum of their cases' CPU.
seq = {}
for c in tables.get("cases.csv", []):
    if c["model"] == "fem" and c["resolution"] == "250" and c["placement"] == "lowest" and c["status"] == "ok":
        seq[c["particle"]] = seq.get(c["particle"], 0.0) + float(c["cpu_seconds"])
worst = max(seq, key=seq.get) if seq else ""
check("report.md: the converged answer's cost is the sequence's CPU",
      re.search(r"\| lowest \| 250 \| 2 \| [^|]+\| [^|]+\| " + re.escape(f"{seq[worst]:.3g}") + r" \(" + worst + r"\) \|",
                md) is not None if seq else False, seq)
# The particles a large study charts (study_report.chart_particles): on 20 particles whose coarse fem is off by
# 1..20 %, 5 charts take the smallest, the median ranks and the largest, in the study's order; 8 or fewer, all.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "report"))
import study_report  # noqa: E402

synthetic = []
for k, e in enumerate([7, 3, 12, 1, 20, 15, 9, 2, 18, 5, 11, 14, 4, 6, 19, 8, 10, 16, 13, 17]):
    p = f"p{k:02d}"
    synthetic += [{"particle": p, "model": "fem", "resolution": "2000", "placement": "lowest", "element_size": "",
                   "answer": "false", "discretization_error": str(e / 100)},
                  {"particle": p, "model": "fem", "resolution": "2000", "placement": "lowest", "element_size": "1e-3",
                   "answer": "true", "discretization_error": "0"}]
picked, rule = study_report.chart_particles(synthetic, 5)
errors = {f"p{k:02d}": e for k, e in enumerate([7, 3, 12, 1, 20, 15, 9, 2, 18, 5, 11, 14, 4, 6, 19, 8, 10, 16, 13, 17])}
check("chart_particles: smallest, evenly spaced ranks and largest, in the study's order",
      sorted(errors[p] for p in picked) == [1, 6, 11, 15, 20] and picked == sorted(picked) and "5 of the 20" in rule,
      (picked, rule))
check("chart_particles: a small study charts every particle",
      study_report.chart_particles(synthetic[:16], 8) == ([f"p{k:02d}" for k in range(8)], ""))
# The reference uncertainty (lowest placement, peak force, median over the 2 particles): the reference is the limit
# at 250 triangles, uncertain by its extrapolation's error; the geometry term (against the limit one resolution down)
# needs a refined sequence there too, and 100 is not refined here, so it is absent (docs/study.md, "Guidelines").
median_u = sum(limit_errors) / 2  # the median of two values
rows = [g for g in tables.get("guidelines.csv", []) if g["placement"] == "lowest" and g["metric"] == "peak_force"
        and g["statistic"] == "median"]
check("peak-force guidelines state the reference uncertainty from the summaries",
      all(abs(float(g["reference_uncertainty"]) - median_u) <= 1e-12 * median_u for g in rows),
      ([g["reference_uncertainty"] for g in rows], median_u))
# A tolerance with no row is one nothing met: no candidate's median peak error (against the limit) is within it.
best = min(float(c["peak_force_err_median"]) for c in tables.get("candidates.csv", []) if c["placement"] == "lowest")
for tol in (0.02, 0.05, 0.1):
    met = [g for g in rows if float(g["tolerance"]) == tol]
    check(f"peak force {tol}: a row exactly when a candidate meets it", bool(met) == (best <= tol), (tol, best, met))

# The answer (answer.csv, docs/study.md "The answer"): every tolerance, metric and statistic has a row under lowest
# placement, the first-contact time left out (0 by construction there); a row is "studied" exactly when a candidate's
# error is within the tolerance, and otherwise names the closest (its error the smallest of the candidates').
answer = [a for a in tables.get("answer.csv", []) if a["placement"] == "lowest"]
check("answer.csv: 4 metrics x 3 tolerances x 2 statistics under lowest, no first-contact row",
      len(answer) == 24 and not any(a["metric"] == "first_contact_time" for a in answer), len(answer))
lowest_candidates = [c for c in tables.get("candidates.csv", []) if c["placement"] == "lowest"]
for a in answer:
    if a["metric"] not in ("peak_force", "impulse", "contact_duration"):
        continue
    errors = [float(c[f"{a['metric']}_err_{a['statistic']}"]) for c in lowest_candidates]
    within = min(errors) <= float(a["tolerance"])
    check(f"answer {a['metric']} {a['tolerance']} {a['statistic']}: studied exactly when a candidate is within",
          (a["answer"] == "studied") == within and (within or float(a["error"]) == min(errors)), (a, min(errors)))
check("few_hundred.csv: a row per metric and statistic",
      len([f for f in tables.get("few_hundred.csv", []) if f["placement"] == "lowest"]) == 8,
      tables.get("few_hundred.csv"))
report_md = open(os.path.join(report, "report.md")).read()
check("the report answers 'a few hundred triangles' and never says unresolved in the answer",
      "Is a few hundred triangles" in report_md and
      "unresolved" not in report_md.split("## The answer")[1].split("\n## ")[0], "")
# Issue 28: a finest-resolution reference whose geometry term no particle measured says so in the answer and beside
# its uncertainty, and never names discretization as the larger term.
finest_refs = [r for r in tables.get("references.csv", []) if r.get("reference", "finest") != "source"]
unmeasured = bool(finest_refs) and not any(r["geometry_from"] for r in finest_refs)
check("geometry_unmeasured: only a finest reference with no geometry term anywhere",
      study_report.geometry_unmeasured([{"reference": "finest", "geometry_from": ""}] * 2) and
      not study_report.geometry_unmeasured([{"reference": "finest", "geometry_from": ""},
                                            {"reference": "finest", "geometry_from": "1000"}]) and
      not study_report.geometry_unmeasured([{"reference": "source", "geometry_from": ""}]), "")
# unreferenced.csv: the header alone when every particle has its reference, and then the report says nothing.
missing_refs = tables.get("unreferenced.csv", [])
check("unreferenced.csv: a row exactly for each particle and placement with no reference",
      len(missing_refs) + len(tables.get("references.csv", [])) == len(
          {(r["particle"], r["placement"]) for r in tables.get("cases.csv", [])}), missing_refs)
check("report.md names the particles with no reference exactly when there are some",
      ("No reference for" in report_md) == bool(missing_refs), "")
check("unreferenced_paragraph: counts, the rest and every reason",
      study_report.unreferenced_paragraph([], 4) is None and
      study_report.unreferenced_paragraph([{"particle": "a-o1", "placement": "lowest", "why": "L3 unstable: x"}], 4) ==
      "No reference for 1 of 4 particle and placement pairs, left out of every error below (each median and p90 is "
      "over the other 3): a-o1 (lowest): L3 unstable: x.", "")
check("report.md says the geometry term is not measured exactly when no coarser resolution was refined",
      (report_md.count("its geometry term is not measured") == 2) == unmeasured and
      report_md.split("## The reference and its uncertainty")[1].count("| unknown: geometry not measured |") ==
      sum(not r["geometry_from"] for r in finest_refs),
      (unmeasured, [r["geometry_from"] for r in finest_refs]))

# 5. recommend: JSON on stdout, a model the study has.
scene = {"name": "new", "gravity": [0, 0, -9.81], "duration": 0.001,
         "materials": {"rock": {"density": 2650, "young": 5e10, "poisson": 0.25}},
         "bodies": [{"name": "p", "material": "rock", "shape": {"type": "sphere", "radius": 0.025},
                     "position": [0, 0, 0.03], "velocity": [0, 0, -2]},
                    {"name": "floor", "material": "rock", "shape": {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}}]}
scene_file = os.path.join(work, "scene.json")
with open(scene_file, "w") as f:
    json.dump(scene, f)
r = run("recommend", scene_file, "--tolerance", "5%", "--study", study, "-q")
check("recommend exits 0", r.returncode == 0, r.stderr)
try:
    rec = json.loads(r.stdout)
    check("recommend names a model", rec["recommendation"]["model"] in ("fem", "rigid", "sphere", "sphere-local"), rec)
    check("recommend states the reference uncertainty", "reference_uncertainty" in rec["recommendation"], rec)
    check("recommend reads the speed", abs(rec["particle"]["speed"] - 2.0) < 1e-12, rec["particle"])
    # the guideline holds at the study's penalty (alpha 100), so the scene change carries it:
    # 100 x the scene particle's E (5e10 Pa)
    if rec["recommendation"]["model"] == "fem":
        check("recommend carries the study's penalty",
              rec["scene_change"].get("contact.penalty_alpha") == 100, rec["scene_change"])
except (json.JSONDecodeError, KeyError) as e:
    check("recommend writes JSON", False, e)
r = run("recommend", scene_file, "--tolerance", "five", "--study", study)
check("bad tolerance exits 2", r.returncode == 2, r.returncode)

# 6. The HTML in headless Chromium: no console errors, a screenshot.
chromium = shutil.which("chromium")
check("chromium installed (deps/debian-packages.txt)", chromium is not None)


def browse(html_file, shot):
    profile = tempfile.mkdtemp()
    try:
        p = subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                            "--disable-component-update", "--disable-sync", "--no-first-run",
                            f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0",
                            "--window-size=1200,2000", f"--screenshot={shot}", "file://" + os.path.abspath(html_file)],
                           capture_output=True, text=True, timeout=120)
    finally:
        shutil.rmtree(profile, ignore_errors=True)
    # Chromium logs a page's console messages as "...:CONSOLE(line)] ..."; errors and uncaught
    # exceptions carry ERROR, or the level in the message for newer builds.
    return [l for l in p.stderr.splitlines() if "CONSOLE" in l and ("ERROR" in l or "error" in l.lower())]


if chromium:
    # The detector itself: a page that logs an error must be caught.
    probe = os.path.join(work, "probe.html")
    with open(probe, "w") as f:
        f.write("<!DOCTYPE html><html><body><script>console.error('probe error'); undefined_call();</script></body></html>")
    check("console error detector catches a bad page", len(browse(probe, os.path.join(work, "probe.png"))) > 0)
    shot = os.path.join(report, "screenshot.png")
    errors = browse(os.path.join(report, "report.html"), shot)
    check("report.html: no console errors", not errors, errors)
    size = png_size(shot) if os.path.exists(shot) else None
    check("screenshot taken", size is not None and size[0] >= 800, size)
    with open(os.path.join(report, "report.html")) as f:
        page = f.read()
    check("HTML self-contained (no external scripts, styles or fonts)",
          not re.search(r"<script|<link|https?://|@import|@font-face", page, re.I))

print(f"{'FAILED' if failures else 'passed'}: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
