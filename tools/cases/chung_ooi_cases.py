#!/usr/bin/env python3
"""Writes the Chung & Ooi (2011) benchmark tests 1-8 as validation cases.

Reads data/chung_ooi/reference.json (inputs and reference numbers, each with its source) and writes
validation/cases/chung_ooi/*.json, one case per material and per angle/speed/spin. Expected values
are either resolved by asperity from the scene ("hertz", "target_restitution") or closed forms
evaluated here (rigid-body impulse with Coulomb friction for gross sliding; unchanged spin for
test 7), or digitised reference curves where no closed form exists. Run it again after editing the
data; the generated JSON is committed.

    python3 tools/cases/chung_ooi_cases.py [--check]   # --check: fail if the files differ
"""
import json
import math
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "data" / "chung_ooi" / "reference.json"
OUT = ROOT / "validation" / "cases" / "chung_ooi"

# Tolerances, each with its reason. Chung & Ooi (2011) report that the codes they compared agree
# with the analytic Hertz peaks and with each other to about 1-2.5 %; we gate at the tight end.
HERTZ_TOL = (0.01, "Chung & Ooi's published codes reach the Hertz solution within ~1 %; at dt = 0.01 "
                   "of the critical step our time-discretisation error is ~1e-4")
PAPER_TOL = (0.015, "digitised paper curve: 1 % code band plus ~0.5 % digitisation error of the figure")
REST_TOL = (0.01, "the damping is inverted exactly for the target restitution (restitution_damping.hpp); "
                  "1 % is the tight end of the published codes' 1-2.5 % band")
SLIDE_TOL = (0.01, "gross sliding has the closed rigid-body solution; compliance changes it only near the "
                   "stick limit, so away from it 1 % (published codes reach 1-2.5 %)")
SPIN_TOL = (0.025, "gross-sliding spin: closed form; 2.5 %, the published codes' band, covers the "
                   "contact-point arm (r - delta/2 against r in the closed form) and the onset of sliding")
ANGLE_ABS = (0.5, "contact-point recoil angle, closed form in gross sliding; 0.5 deg absolute because the "
                  "angle passes through 0 near the stick limit where a relative tolerance is meaningless")
CURVE_TOL_ET = (0.03, "micro-slip regime, no closed form: against the digitised Hertz-Mindlin reference "
                      "curve (KRATOS), whose digitisation and stiffness model (k_t/k_n = 2(1-nu)/(2-nu)) "
                      "we share; 3 % = the codes' 2.5 % band plus reading the curve")


def hertz(m_eff, r_eff, e_eff, v):
    d = (15 * m_eff * v * v / (16 * e_eff * math.sqrt(r_eff))) ** 0.4
    return {"max_overlap": d, "peak_force": 4 / 3 * e_eff * math.sqrt(r_eff) * d ** 1.5,
            "contact_duration": 2.9432751843 * d / v}


def e_star(a, b):
    return 1 / ((1 - a["poisson"] ** 2) / a["young"] + (1 - b["poisson"] ** 2) / b["young"])


def mass(mat, r):
    return mat["density"] * 4 / 3 * math.pi * r ** 3


def material(m, **extra):
    out = {k: m[k] for k in ("density", "young", "poisson")}
    out.update(extra)
    return out


def exp_hertz():
    return {"reference": "hertz", "rel_tol": HERTZ_TOL[0], "why": HERTZ_TOL[1] + " (analytic: Johnson 1985 eqs. 11.23-11.24)"}


def exp_target_restitution():
    return {"reference": "target_restitution", "rel_tol": REST_TOL[0], "why": REST_TOL[1]}


def mindlin(mu, en):
    """The contact of every test: Hertz-Mindlin with the test's friction and restitution."""
    return {"law": "hertz-mindlin", "friction": mu, "restitution": en}


def add_case(out, name, number, t, src, tags, what, scene, ex, closed_form=False):
    """Case NAME of test NUMBER (its data t): the description, tags and sources every case states
    the same way; `what` the case's own part of the description; the closed form's source when an
    expected value is one."""
    source = f"{src['CO2011']} Inputs: {t['source']}."
    if closed_form:
        source += f" Closed form: {src['ANALYTIC']}"
    out[name] = {
        "description": f"Chung & Ooi test {number} ({t['title']}), {what}",
        "tags": ["chung-ooi", f"test{number}", *tags],
        "source": source,
        "scene": scene, "expected": ex}


def exp_value(v, tol, why, abs_tol=None):
    e = {"value": v, "why": why}
    if tol is not None:
        e["rel_tol"] = tol
    if abs_tol is not None:
        e["abs_tol"] = abs_tol
    return e


# Rigid-plane scenes give dt explicitly, a thousandth of the Hertz contact time: asperity's "auto"
# predictor (dem/time_step.cpp) takes the stiffest material pair in the scene, which here is the
# rigid wall against itself (E = 1e20 Pa) although walls never touch each other, and would predict
# a step ~1e5 times too small. 1000 steps per contact keep the time error of the peak below 1e-5.
STEPS_PER_CONTACT = 1000


def wall_scene(name, mats, sphere_mat, r, v, duration, contact, rigid, tc, w=(0, 0, 0), gap=None):
    """A sphere above the rigid plane z = 0 moving with velocity v (vz < 0)."""
    return {
        "name": name,
        "duration": duration,
        "dt": tc / STEPS_PER_CONTACT,
        "allow_unsafe_dt": True,
        "materials": {sphere_mat: material(mats[sphere_mat]), "rigid": rigid},
        "bodies": [
            {"name": "sphere", "material": sphere_mat, "shape": {"type": "sphere", "radius": r},
             "position": [0, 0, r + gap], "velocity": list(v), "angular_velocity": list(w)},
            {"name": "plane", "material": "rigid", "shape": {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}},
        ],
        "contact": contact,
        "record": {"force_on": "sphere"},
    }


def timing(vn, tc):
    """Start gap: a tenth of a contact time of travel; run to 1.5 contact times after the touch."""
    gap = 0.1 * vn * tc
    return gap, gap / vn + 1.5 * tc


def elastic_hertz_expected(t, m):
    """Tests 1 and 2: Hertz peak force, overlap and duration, e = 1; the paper's peak force for the
    material whose force curve it gives."""
    ex = {"status": "ok", "peak_force": exp_hertz(), "max_overlap": exp_hertz(), "contact_duration": exp_hertz(),
          "restitution": exp_value(1.0, None, "elastic: e = 1 exactly; 1e-3 absolute covers the time-step error of the rebound speed", abs_tol=1e-3)}
    if m == t["paper_curve"]["material"]:
        pc = t["paper_curve"]
        ex["peak_force"] = exp_value(pc["peak_force"], PAPER_TOL[0], PAPER_TOL[1] + "; " + pc["source"])
    return ex


def test1_sphere_sphere(d, mats, rigid, src, out):
    """Test 1: two identical spheres, elastic, normal."""
    t = d["test1"]
    for m in t["materials"]:
        r, v = t["radius"], t["speed_each"]
        mat = mats[m]
        h = hertz(mass(mat, r) / 2, r / 2, e_star(mat, mat), 2 * v)
        gap, dur = timing(2 * v, h["contact_duration"])
        scene = {
            "name": f"chung-ooi-t1-{m}", "duration": dur, "dt": "auto",
            "materials": {m: material(mat)},
            "bodies": [
                {"name": "a", "material": m, "shape": {"type": "sphere", "radius": r}, "position": [-(r + gap / 2), 0, 0], "velocity": [v, 0, 0]},
                {"name": "b", "material": m, "shape": {"type": "sphere", "radius": r}, "position": [r + gap / 2, 0, 0], "velocity": [-v, 0, 0]},
            ],
            "contact": mindlin(0.35, 1.0),
            "record": {"force_on": "a"},
        }
        ex = elastic_hertz_expected(t, m)
        add_case(out, scene["name"], 1, t, src, ["hertz", "sphere-sphere"],
                 f"{m}: r = {r} m, each sphere at {v} m/s. Hertz peak force, overlap and duration.",
                 scene, ex)


def test2_sphere_plane(d, mats, rigid, src, out):
    """Test 2: sphere on a rigid plane, elastic, normal."""
    t = d["test2"]
    for m in t["materials"]:
        r, v = t["radius"], t["speed"]
        mat = mats[m]
        h = hertz(mass(mat, r), r, e_star(mat, rigid), v)
        gap, dur = timing(v, h["contact_duration"])
        scene = wall_scene(f"chung-ooi-t2-{m}", mats, m, r, (0, 0, -v), dur, mindlin(0.0, 1.0), rigid, h["contact_duration"], gap=gap)
        ex = elastic_hertz_expected(t, m)
        add_case(out, scene["name"], 2, t, src, ["hertz", "sphere-plane"],
                 f"{m}: r = {r} m at {v} m/s onto a rigid plane (E* = E/(1-nu^2), R* = r).",
                 scene, ex)


def test3_restitution(d, mats, rigid, src, out):
    """Test 3: restitution."""
    t = d["test3"]
    for m in t["materials"]:
        for e in t["restitution"]:
            r, v = t["radius"], t["speed"]
            mat = mats[m]
            h = hertz(mass(mat, r), r, e_star(mat, rigid), v)
            gap, dur = timing(v, h["contact_duration"] * (1.3 if e < 1 else 1.0))
            name = f"chung-ooi-t3-{m}-e{e:.1f}"
            scene = wall_scene(name, mats, m, r, (0, 0, -v), dur, mindlin(0.0, e), rigid, h["contact_duration"], gap=gap)
            ex = {"status": "ok", "restitution": exp_target_restitution()}
            if e == 1.0:
                ex["peak_force"] = exp_hertz()
            add_case(out, name, 3, t, src, ["restitution", "sphere-plane"],
                     f"{m}, input restitution {e}: the measured restitution must equal the input.",
                     scene, ex)


def test4_oblique_angle(d, mats, rigid, src, out):
    """Test 4: oblique impact, constant speed, varying angle."""
    t = d["test4"]
    mu, en = t["friction"], t["restitution"]
    theta_c = math.degrees(math.atan(3.5 * mu * (1 + en)))
    curve = t["reference_curve"]
    for m in t["materials"]:
        for a in t["angles_deg"]:
            r, v = t["radius"], t["speed"]
            mat = mats[m]
            th = math.radians(a)
            vn, vt = v * math.cos(th), v * math.sin(th)
            h = hertz(mass(mat, r), r, e_star(mat, rigid), vn)
            gap, dur = timing(vn, h["contact_duration"] * 1.1)
            name = f"chung-ooi-t4-{m}-{a:02d}deg"
            scene = wall_scene(name, mats, m, r, (vt, 0, -vn), dur, mindlin(mu, en), rigid, h["contact_duration"], gap=gap)
            ex = {"status": "ok", "restitution": exp_target_restitution()}
            regime = "micro-slip (no closed form)"
            if a >= theta_c + 7:
                regime = "gross sliding (closed form)"
                et = 1 - mu * (1 + en) / math.tan(th)
                spin = 5 * mu * (1 + en) * vn / (2 * r)
                rebound = math.degrees(math.atan((math.tan(th) - 3.5 * mu * (1 + en)) / en))
                ex["tangential_restitution"] = exp_value(et, SLIDE_TOL[0], SLIDE_TOL[1] + ": e_t = 1 - mu(1+e_n)/tan(theta)")
                ex["spin_out"] = exp_value(spin, SPIN_TOL[0], SPIN_TOL[1] + ": w' = 5 mu (1+e_n) v cos(theta) / (2r)")
                ex["rebound_angle_deg"] = exp_value(rebound, None, ANGLE_ABS[1] + ": tan(theta') = (tan(theta) - 3.5 mu (1+e_n))/e_n", abs_tol=ANGLE_ABS[0])
            elif m == curve["material"] and a >= 15 and a in [round(x) for x in curve["angle_deg"]]:
                # Below 15 deg e_t falls from ~1 to 0.69 within 10 deg: a 0.2 deg reading error of the
                # curve alone is 0.01, and the value hinges on the tangential stiffness and damping
                # model; 5 and 10 deg are compared in docs/crosscheck.md and against YADE, not gated.
                k = [round(x) for x in curve["angle_deg"]].index(a)
                ex["tangential_restitution"] = exp_value(curve["value"][k], CURVE_TOL_ET[0],
                                                         CURVE_TOL_ET[1] + f"; curve point ({curve['angle_deg'][k]} deg, {curve['value'][k]}) from {curve['source']}")
            add_case(out, name, 4, t, src, ["oblique", "sphere-plane", "sliding" if "gross" in regime else "micro-slip"],
                     f"{m}, incidence {a} deg from the normal at {v} m/s, mu = {mu}, e_n = {en}; {regime} (stick limit {theta_c:.1f} deg for a rigid sphere).",
                     scene, ex, closed_form=True)


def test5_tangential_speed(d, mats, rigid, src, out):
    """Test 5: constant normal speed, varying tangential speed (elastic)."""
    t = d["test5"]
    mu, en = t["friction"], t["restitution"]
    for m in t["materials"]:
        for psi in t["psi1"]:
            r, vn = t["radius"], t["normal_speed"]
            mat = mats[m]
            vt = psi * mu * vn
            h = hertz(mass(mat, r), r, e_star(mat, rigid), vn)
            gap, dur = timing(vn, h["contact_duration"] * 1.1)
            name = f"chung-ooi-t5-{m}-psi{psi:04.1f}"
            scene = wall_scene(name, mats, m, r, (vt, 0, -vn), dur, mindlin(mu, en), rigid, h["contact_duration"], gap=gap)
            ex = {"status": "ok", "restitution": exp_value(1.0, None, "elastic: e = 1; 1e-3 absolute covers the time-step error", abs_tol=1e-3)}
            # Rigid stick limit: Psi1 = 3.5 (1+e) = 7; gate the closed form from Psi1 = 8.
            if psi >= 3.5 * (1 + en) + 1:
                spin = 2.5 * (1 + en) * mu * vn / r
                ex["spin_out"] = exp_value(spin, SPIN_TOL[0], SPIN_TOL[1] + ": r w'/(mu Vn) = 5/2 (1+e) = 5 (Chung & Ooi digitised plateau: 5.00 steel, 4.96 polyethylene)")
                change = 3.5 * (1 + en) * mu * vn
                ex["slip_velocity_out"] = exp_value((psi - 3.5 * (1 + en)) * mu * vn, None,
                                                    "gross sliding, closed form Psi2 = Psi1 - 7 (e = 1); 1 % of the slip change 3.5 mu (1+e) Vn "
                                                    "(the published codes' band) because the closed form takes the rigid torque arm r while "
                                                    "the compressed arm is r - delta/2 (delta/r = 3.7 % for polyethylene at 5 m/s)", abs_tol=0.01 * change)
            else:
                ex["spin_out"] = {"max": 2.5 * (1 + en) * mu * vn / r * (1 + SPIN_TOL[0]),
                                  "why": "micro-slip regime, no closed form: the spin cannot exceed its gross-sliding value 5 mu Vn / r (friction impulse <= mu times the normal impulse)"}
            add_case(out, name, 5, t, src, ["oblique", "sphere-plane"],
                     f"{m}: Vn = {vn} m/s, Psi1 = Vt/(mu Vn) = {psi}, mu = {mu}, elastic.",
                     scene, ex, closed_form=True)


def test6_spin(d, mats, rigid, src, out):
    """Test 6: constant normal speed, zero centre tangential speed, varying spin."""
    t = d["test6"]
    mu, en = t["friction"], t["restitution"]
    curve = t["reference_curve"]
    for m in t["materials"]:
        for chi, beta in zip(curve["chi"], curve["beta"]):
            r, vn = t["radius"], t["normal_speed"]
            mat = mats[m]
            vst = 3.5 * mu * (1 + en) * vn / chi
            h = hertz(mass(mat, r), r, e_star(mat, rigid), vn)
            gap, dur = timing(vn, h["contact_duration"] * 1.3)
            name = f"chung-ooi-t6-{m}-chi{chi:06.3f}"
            scene = wall_scene(name, mats, m, r, (0, 0, -vn), dur, mindlin(mu, en), rigid,
                               h["contact_duration"], w=(0, -vst / r, 0), gap=gap)
            ex = {"status": "ok", "restitution": exp_target_restitution()}
            if chi <= 0.6:
                ex["slip_ratio"] = exp_value(1 - chi, SLIDE_TOL[0], SLIDE_TOL[1] + ": beta = -slip_ratio = chi - 1")
            # chi > 0.6: micro-slip, no closed form. beta there hinges on the tangential damping, which
            # the benchmark leaves to the code; compared with the digitised curve in docs/crosscheck.md
            # and gated against YADE (same Mindlin model and damping), not against the curve.
            add_case(out, name, 6, t, src, ["oblique", "sphere-plane"],
                     f"{m}: Vn = {vn} m/s, contact-point slip {vst:.4g} m/s from spin alone (chi = {chi}).",
                     scene, ex, closed_form=True)


def test7_opposite_spin(d, mats, rigid, src, out):
    """Test 7: two identical spheres, equal and opposite spin: no slip, spin unchanged."""
    t = d["test7"]
    mu, en = t["friction"], t["restitution"]
    for m in t["materials"]:
        for w in t["spin"]:
            r, v = t["radius"], t["speed_each"]
            mat = mats[m]
            h = hertz(mass(mat, r) / 2, r / 2, e_star(mat, mat), 2 * v)
            gap, dur = timing(2 * v, h["contact_duration"] * 1.3)
            name = f"chung-ooi-t7-{m}-w{w:07.4f}"
            scene = {
                "name": name, "duration": dur, "dt": "auto",
                "materials": {m: material(mat)},
                "bodies": [
                    {"name": "a", "material": m, "shape": {"type": "sphere", "radius": r}, "position": [-(r + gap / 2), 0, 0], "velocity": [v, 0, 0], "angular_velocity": [0, w, 0]},
                    {"name": "b", "material": m, "shape": {"type": "sphere", "radius": r}, "position": [r + gap / 2, 0, 0], "velocity": [-v, 0, 0], "angular_velocity": [0, -w, 0]},
                ],
                "contact": mindlin(mu, en),
                "record": {"force_on": "a"},
            }
            ex = {"status": "ok",
                  "restitution": exp_target_restitution(),
                  "angular_velocity_change": {"max": 1e-9 * w, "why": "the two contact points move together (no slip), so no tangential force acts and the spin is unchanged (Chung & Ooi test 7: final = initial spin); 1e-9 relative allows round-off only"},
                  "tangential_speed_out": {"max": 1e-9 * v, "why": "no tangential force: the centres keep zero tangential velocity; 1e-9 of the speed allows round-off only"}}
            add_case(out, name, 7, t, src, ["spin", "sphere-sphere"],
                     f"{m}: +-{v} m/s, spins +-{w} rad/s about the same axis.",
                     scene, ex)


def test8_large_sphere(d, mats, rigid, src, out):
    """Test 8: small sphere with spin against a large, effectively immobile sphere."""
    t = d["test8"]
    mu, en = t["friction"], t["restitution"]
    curve = t["reference_curve"]
    for m in t["materials"]:
        for chi, beta in zip(curve["chi"], curve["beta"]):
            r, big, vn = t["radius"], t["large_radius"], t["normal_speed"]
            mat = mats[m]
            heavy = dict(material(mat))
            heavy["density"] = mat["density"] * t["large_density_factor"]
            vst = 3.5 * mu * (1 + en) * vn / chi
            h = hertz(mass(mat, r), r * big / (r + big), e_star(mat, mat), vn)
            gap, dur = timing(vn, h["contact_duration"] * 1.3)
            name = f"chung-ooi-t8-{m}-chi{chi:06.3f}"
            scene = {
                "name": name, "duration": dur, "dt": "auto",
                "materials": {m: material(mat), m + "_heavy": heavy},
                "bodies": [
                    {"name": "small", "material": m, "shape": {"type": "sphere", "radius": r}, "position": [-(r + big + gap), 0, 0],
                     "velocity": [vn, 0, 0], "angular_velocity": [0, -vst / r, 0]},
                    {"name": "large", "material": m + "_heavy", "shape": {"type": "sphere", "radius": big}, "position": [0, 0, 0]},
                ],
                "contact": mindlin(mu, en),
                "record": {"force_on": "small"},
            }
            ex = {"status": "ok", "restitution": exp_target_restitution()}
            if chi <= 0.6:
                ex["slip_ratio"] = exp_value(1 - chi, SLIDE_TOL[0], SLIDE_TOL[1] + ": beta = chi - 1 (the large sphere is 125000 times heavier)")
            # chi > 0.6: micro-slip, as in test 6 (docs/crosscheck.md; gated against YADE).
            add_case(out, name, 8, t, src, ["oblique", "sphere-sphere"],
                     f"{m}: r = {r} m at {vn} m/s with contact-point slip {vst:.4g} m/s (chi = {chi}) against a {big} m sphere {t['large_density_factor']}x denser.",
                     scene, ex, closed_form=True)


def cases(d):
    """Every case of tests 1-8, by name, in the order of the tests."""
    mats = d["materials"]
    rigid = material(d["rigid_wall"])
    src = d["sources"]
    out = {}

    test1_sphere_sphere(d, mats, rigid, src, out)
    test2_sphere_plane(d, mats, rigid, src, out)
    test3_restitution(d, mats, rigid, src, out)
    test4_oblique_angle(d, mats, rigid, src, out)
    test5_tangential_speed(d, mats, rigid, src, out)
    test6_spin(d, mats, rigid, src, out)
    test7_opposite_spin(d, mats, rigid, src, out)
    test8_large_sphere(d, mats, rigid, src, out)
    return out


def main():
    d = json.loads(DATA.read_text())
    generated = cases(d)
    check_only = "--check" in sys.argv
    OUT.mkdir(parents=True, exist_ok=True)
    stale = []
    for name, c in generated.items():
        text = json.dumps({"case": name, **c}, indent=2) + "\n"
        f = OUT / f"{name}.json"
        if check_only:
            if not f.exists() or f.read_text() != text:
                stale.append(f.name)
        else:
            f.write_text(text)
    extra = sorted(p.name for p in OUT.glob("*.json") if p.stem not in generated)
    if check_only and (stale or extra):
        print("stale or extra case files:", stale + extra)
        return 1
    for name in extra:
        (OUT / name).unlink()
    print(f"{len(generated)} cases in {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
