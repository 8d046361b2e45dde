#!/usr/bin/env python3
"""An example external solver for `asperity validate --solver-cmd` (docs/crosscheck.md, "Gating any
solver"): a deliberately small, independent DEM code that honours the contract.

    hertz_solver.py SCENE.json OUT_DIR [--force-scale S]

It reads a contract scene (docs/contract.md) of one free sphere striking a second sphere or a
plane with the elastic "hertz" law, integrates it with velocity Verlet at 1/2000 of the analytic
Hertz contact time, and writes OUT_DIR/force.csv (t,fx,fy,fz,f) and OUT_DIR/summary.json (status,
peak_force, impulse, contact_duration, first_contact_time, max_overlap, restitution, energy_drift,
dt, steps, cpu_seconds, wall_seconds). Anything else is refused with one line on stderr and exit
status 2.

--force-scale multiplies the contact force (default 1): 1.05 is the deliberately wrong copy that
the gate must catch.
"""
import json
import math
import os
import sys
import time


def fail(msg):
    sys.stderr.write(f"hertz_solver: {msg}\n")
    sys.exit(2)


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    scale = 1.0
    if "--force-scale" in argv:
        scale = float(argv[argv.index("--force-scale") + 1])
        args.remove(argv[argv.index("--force-scale") + 1])
    if len(args) != 2:
        fail("usage: hertz_solver.py SCENE.json OUT_DIR [--force-scale S]")
    scene_file, out = args
    with open(scene_file) as fh:
        s = json.load(fh)
    if s.get("contact", {}).get("law") != "hertz":
        fail(f"{scene_file}: contact.law: only \"hertz\" is implemented")
    mats, bodies = s["materials"], s["bodies"]
    if len(bodies) != 2 or bodies[0]["shape"]["type"] != "sphere":
        fail(f"{scene_file}: bodies: one sphere against one sphere or plane is implemented")
    if any(g != 0 for g in s.get("gravity", [0, 0, 0])):
        fail(f"{scene_file}: gravity: not implemented")
    a, b = bodies
    if a.get("fixed", False):
        fail(f"{scene_file}: bodies[0].fixed: the first body must move")

    def mass(body):
        r = body["shape"]["radius"]
        return mats[body["material"]]["density"] * 4 / 3 * math.pi * r ** 3

    ma, ra = mass(a), a["shape"]["radius"]
    plane = b["shape"]["type"] == "plane"
    if not plane and b["shape"]["type"] != "sphere":
        fail(f"{scene_file}: bodies[1].shape: sphere or plane")
    mb = math.inf if plane or b.get("fixed", False) else mass(b)
    rb = math.inf if plane else b["shape"]["radius"]
    m_eff = ma if mb == math.inf else ma * mb / (ma + mb)
    r_eff = ra if rb == math.inf else ra * rb / (ra + rb)
    e_star = 1 / sum((1 - mats[x["material"]]["poisson"] ** 2) / mats[x["material"]]["young"] for x in (a, b))
    k = 4 / 3 * e_star * math.sqrt(r_eff) * scale  # F = k δ^{3/2}

    # Positions along the line of centres (or the plane normal): a 1-D problem.
    xa, va = a["position"], a.get("velocity", [0, 0, 0])
    if plane:
        n = b["shape"]["normal"]
        nn = math.sqrt(sum(c * c for c in n))
        n = [c / nn for c in n]
        gap0 = sum((xa[i] - b["shape"]["point"][i]) * n[i] for i in range(3)) - ra
        vb = [0, 0, 0]
    else:
        d = [xa[i] - b["position"][i] for i in range(3)]
        dist = math.sqrt(sum(c * c for c in d))
        n = [c / dist for c in d]
        gap0 = dist - ra - rb
        vb = b.get("velocity", [0, 0, 0]) if mb != math.inf else [0, 0, 0]
    v_rel = sum((va[i] - vb[i]) * n[i] for i in range(3))  # < 0: approaching
    if v_rel >= 0:
        fail(f"{scene_file}: bodies: the sphere does not approach its partner")
    # Hertz contact time (Johnson 1985 §11.4): t_c = 2.87 (m*^2 / (R* E*^2 v))^{1/5}.
    t_c = 2.868 * (m_eff ** 2 / (r_eff * (e_star * scale) ** 2 * -v_rel)) ** 0.2
    dt = t_c / 2000
    steps = int(math.ceil(s["duration"] / dt - 1e-9))

    t0, w0 = time.process_time(), time.perf_counter()
    # Relative coordinate: gap g (> 0 apart), relative velocity u = dg/dt; m_eff g'' = F(−g).
    g, u = gap0, v_rel
    force = lambda gap: k * (-gap) ** 1.5 if gap < 0 else 0.0
    f = force(g)
    e0 = 0.5 * m_eff * u * u + (0.4 * k * (-g) ** 2.5 if g < 0 else 0.0)
    rows = [(0.0, f)]
    peak, impulse, duration, first, max_overlap, drift = f, 0.0, 0.0, None, 0.0, 0.0
    start, touching = None, g < 0
    approach, separation = -u if touching else None, None
    for step in range(1, steps + 1):
        u += 0.5 * dt * f / m_eff
        g_prev = g
        g += dt * u
        f_prev, f = f, force(g)
        u += 0.5 * dt * f / m_eff
        t = step * dt
        impulse += 0.5 * (f + f_prev) * dt
        peak = max(peak, f)
        max_overlap = max(max_overlap, -g)
        if not touching and g < 0:  # contact starts: interpolate the crossing
            start = t - dt + dt * g_prev / (g_prev - g)
            first = start if first is None else first
            approach = approach if approach is not None else -u
            touching = True
        elif touching and g >= 0:
            end = t - dt + dt * g_prev / (g_prev - g) if g != g_prev else t
            duration += end - (start if start is not None else 0.0)
            separation = separation if separation is not None else u
            touching = False
        e = 0.5 * m_eff * u * u + (0.4 * k * (-g) ** 2.5 if g < 0 else 0.0)
        drift = max(drift, abs(e - e0) / e0)
        rows.append((t, f))
    if touching:
        duration += steps * dt - (start if start is not None else 0.0)
    cpu, wall = time.process_time() - t0, time.perf_counter() - w0

    os.makedirs(out, exist_ok=True)
    every = int(s.get("record", {}).get("every", 1))
    sign = 1.0 if s.get("record", {}).get("force_on", a["name"]) == a["name"] else -1.0
    with open(os.path.join(out, "force.csv"), "w") as fh:
        fh.write("t,fx,fy,fz,f\n")
        for i, (t, fm) in enumerate(rows):
            if i % every == 0 or i == len(rows) - 1:
                fh.write(f"{t!r},{sign * fm * n[0]!r},{sign * fm * n[1]!r},{sign * fm * n[2]!r},{fm!r}\n")
    summary = {
        "status": "ok" if first is not None else "no_contact",
        "solver": "peers/example_solver/hertz_solver.py" + (f" --force-scale {scale}" if scale != 1 else ""),
        "peak_force": peak,
        "impulse": impulse,
        "contact_duration": duration,
        "first_contact_time": first,
        "max_overlap": max_overlap,
        "restitution": separation / approach if separation is not None and approach else None,
        "energy_drift": drift,
        "dt": dt,
        "steps": steps,
        "cpu_seconds": cpu,
        "wall_seconds": wall,
    }
    tmp = os.path.join(out, "summary.json.partial")
    with open(tmp, "w") as fh:
        json.dump(summary, fh, indent=2)
    os.replace(tmp, os.path.join(out, "summary.json"))  # last, as the contract asks
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
