#!/usr/bin/env python3
"""The cost of the bench_fem collision over the particle set (issue 11, item 6), from the console
output of `bench_fem --benchmark_filter=CollisionSet --set-particles=all > LOG` (read line by
line, so a run stopped part-way still gives the particles it finished): per resolution the
median and worst CPU seconds, and per particle the exponent log(cpu_1000 / cpu_100) / log(10)
and the least-squares slope of log cpu against log N over every resolution it ran (100, 250,
500, 1000). Prints a Markdown table; with --csv OUT also writes one row per run.
Usage: collision_cost_table.py LOG [--csv OUT]"""
import math
import re
import statistics
import sys


def slope(points):
    """Least-squares slope of log y against log x."""
    xs = [math.log(x) for x, _ in points]
    ys = [math.log(y) for _, y in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main(path, csv_path=None):
    runs = {}
    units = {"": 1, "G": 1e9, "M": 1e6, "k": 1e3, "m": 1e-3, "u": 1e-6, "n": 1e-9, "p": 1e-12,
             "f": 1e-15}
    for line in open(path):
        m = re.match(r"BM_CollisionSet/(\S+)/(\d+)/\S+\s.*?((?:\w+=\S+ ?)+)$", line.strip())
        if not m:
            continue
        counters = {}
        for kv in m.group(3).split():
            k, v = kv.split("=")
            scale = units.get(v[-1], None)
            counters[k] = float(v[:-1]) * scale if scale and v[-1].isalpha() else float(v)
        runs.setdefault(m.group(1), {})[int(m.group(2))] = counters
    faces = sorted({n for r in runs.values() for n in r})
    print(f"{len(runs)} particles.\n")
    print("| N faces | particles | CPU median (s) | CPU worst (s) | worst particle | steps median | dt median (s) | tets median |")
    print("| ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: |")
    for n in faces:
        rows = [(p, r[n]) for p, r in runs.items() if n in r]
        cpu = [b["cpu_s"] for _, b in rows]
        worst = max(rows, key=lambda x: x[1]["cpu_s"])
        print(f"| {n} | {len(rows)} | {statistics.median(cpu):.3g} | {worst[1]['cpu_s']:.3g} | "
              f"{worst[0]} | {statistics.median([b['steps'] for _, b in rows]):.0f} | "
              f"{statistics.median([b['dt'] for _, b in rows]):.3g} | "
              f"{statistics.median([b['tets'] for _, b in rows]):.0f} |")
    if 100 in faces and 1000 in faces:
        k = [(p, math.log(r[1000]["cpu_s"] / r[100]["cpu_s"]) / math.log(10))
             for p, r in runs.items() if 100 in r and 1000 in r]
        e = [x for _, x in k]
        hi = max(k, key=lambda x: x[1])
        print(f"\nExponent 100 → 1000 over {len(k)} particles: median {statistics.median(e):.2f}, "
              f"min {min(e):.2f}, max {hi[1]:.2f} ({hi[0]}).")
        fits = [(p, slope([(n, r[n]["cpu_s"]) for n in sorted(r)])) for p, r in runs.items()
                if len(r) >= 3]
        if fits:
            f = [x for _, x in fits]
            hi = max(fits, key=lambda x: x[1])
            print(f"Least-squares exponent over {', '.join(map(str, faces))} faces, "
                  f"{len(fits)} particles: median {statistics.median(f):.2f}, min {min(f):.2f}, "
                  f"max {hi[1]:.2f} ({hi[0]}); {sum(x > 1.4 for x in f)} above 1.4.")
        over = [p for p, r in runs.items() if 1000 in r and r[1000]["cpu_s"] > 2]
        print(f"Over 2 s at 1000 faces: {len(over)} ({', '.join(sorted(over)) or 'none'}).")
        bins = {}
        for x in e:
            b = math.floor(x * 10 + 1e-9)
            bins[b] = bins.get(b, 0) + 1
        print("\nExponents 100 → 1000: " + ", ".join(
            f"{n} in [{b / 10:.1f}, {(b + 1) / 10:.1f})" for b, n in sorted(bins.items())) + ".")
        # Why a particle's exponent is high: the cost is steps × work per step, so the exponent
        # splits into the steps' (log of the step-count ratio) and the work per step's; dt/dt_element
        # at 1000 faces says whether the contact (< 0.5: the step below half the elements' own
        # limit, at the benchmark's 0.5 × the predicted step) or the elements set the step.
        high = sorted(((x, p) for p, x in k if x > 1.4), reverse=True)
        if high:
            print("\n| particle | exponent | steps exponent | work/step exponent | tets 100 → 1000 | "
                  "dt/dt_element at 100 | at 1000 | least penalty factor at 1000 |")
            print("| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: |")
            for x, p in high:
                a, b = runs[p][100], runs[p][1000]
                se = math.log(b["steps"] / a["steps"]) / math.log(10)
                print(f"| {p} | {x:.2f} | {se:.2f} | {x - se:.2f} | {a['tets']:.0f} → "
                      f"{b['tets']:.0f} | {a['dt'] / a['dt_element']:.2f} | "
                      f"{b['dt'] / b['dt_element']:.2f} | {b.get('penalty_scale_min', 1):.3g} |")


    if csv_path:
        keys = ["cpu_s", "setup_cpu_s", "steps", "dt", "dt_element", "dt_contact", "tets", "peak_N",
                "penalty_scale_min"]
        with open(csv_path, "w") as out:
            out.write("particle,faces," + ",".join(keys) + "\n")
            for p in sorted(runs):
                for n in sorted(runs[p]):
                    out.write(f"{p},{n}," + ",".join(f"{runs[p][n].get(k, float('nan')):.6g}"
                                                     for k in keys) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[sys.argv.index("--csv") + 1] if "--csv" in sys.argv else None)
