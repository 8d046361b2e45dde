#!/usr/bin/env python3
"""The peer table: every sphere case in asperity and in each peer, side by side.

    peer_table.py ASPERITY_EXE OUT_DIR [--peers yade,lammps,liggghts] [--yade-table DIR] [--jobs N]
                  [--tables-only [--also-runs DIR]] [CASES...]

Runs `asperity crosscheck CASE --peer P1,P2,... --only-expressible` once per case that a sphere
peer's gate takes (`asperity crosscheck --list`, from validation/peer_policy.json; default:
validation/cases), so every code's CPU time is for
the same scene and step and measured in one run on one machine, then writes OUT_DIR/peers.csv
(one row per case and peer) and OUT_DIR/peers.md: per case and peer the relative differences
(asperity − peer)/peer of peak force, impulse, contact duration and restitution, both CPU times
and their ratio, and for a peer that cannot express the case, its reason; the ratios' median and
spread per peer are the C++'s (spread_table, built beside ASPERITY_EXE). With --yade-table DIR
it also writes the YADE rows alone as DIR/crosscheck.csv and .md (reports/yade/, which the study
report reads). The cost per step on a two-sphere scene and a 10,000-sphere bed is
peer_cost.py's (OUT_DIR/cost.md); the `peers-report` target runs both. --tables-only rewrites the
tables from the comparison.json files an earlier run left in OUT_DIR/runs/ (--also-runs DIR: a
peer a case's comparison lacks is taken from DIR/CASE/comparison.json, another such run's).
"""
import concurrent.futures
import csv
import json
import os
import pathlib
import platform
import subprocess
import sys

from tabular import spread  # beside this file

ROOT = pathlib.Path(__file__).resolve().parents[2]


def sphere_cases(exe):
    """The case files some sphere peer's gate runs or refuses (not YADE's polyhedra gates):
    `asperity crosscheck --list`, which applies validation/peer_policy.json (the one place that
    says which cases the peers take)."""
    out = subprocess.run([exe, "crosscheck", "--list", "--peer", "yade,lammps,liggghts"], check=True,
                         capture_output=True, text=True).stdout
    return {pathlib.Path(line.split("\t")[2]).resolve() for line in out.splitlines()
            if line.startswith(("run\t", "refused\t"))}


def parse_args(argv):
    """The command line (the module's doc) as a dict; None: print the usage."""
    if len(argv) < 2:
        return None
    a = {"exe": argv[0], "out": pathlib.Path(argv[1]), "peers": ["yade", "lammps", "liggghts"], "jobs": 1,
         "also_runs": [], "yade_table": None}
    rest = argv[2:]
    if "--peers" in rest:
        i = rest.index("--peers")
        a["peers"] = rest[i + 1].split(",")
        rest = rest[:i] + rest[i + 2:]
    a["tables_only"] = "--tables-only" in rest
    if a["tables_only"]:
        rest.remove("--tables-only")
    if "--jobs" in rest:
        i = rest.index("--jobs")
        a["jobs"] = int(rest[i + 1])
        rest = rest[:i] + rest[i + 2:]
    while "--also-runs" in rest:
        i = rest.index("--also-runs")
        a["also_runs"].append(pathlib.Path(rest[i + 1]))
        rest = rest[:i] + rest[i + 2:]
    if "--yade-table" in rest:
        i = rest.index("--yade-table")
        a["yade_table"] = pathlib.Path(rest[i + 1])
        rest = rest[:i] + rest[i + 2:]
    a["targets"] = [pathlib.Path(p) for p in rest] or [ROOT / "validation" / "cases"]
    return a


def with_other_runs(c, name, peers, also_runs):
    """The case's comparison with each peer this run left out taken from another run's
    (--also-runs); also whether any was taken."""
    extra = {}
    for d in also_runs:
        other = d / name / "comparison.json"
        if other.exists():
            oc = json.loads(other.read_text())
            for peer in oc.get("peers", []):
                extra.setdefault(peer, oc)
    merged = False
    for peer in peers:
        if peer not in c.get("peers", []) and peer not in c.get("not_run", {}) and peer in extra:
            c = dict(c)
            oc = extra[peer]
            merged = True
            for q in ("peak_force", "impulse", "contact_duration"):
                c[q] = {"rel_diff": {**c[q]["rel_diff"], peer: oc[q]["rel_diff"].get(peer)}}
            c["other"] = dict(c["other"])
            c["other"]["restitution"] = {"rel_diff": {
                **c["other"].get("restitution", {}).get("rel_diff", {}),
                peer: oc["other"].get("restitution", {}).get("rel_diff", {}).get(peer)}}
            c["status"] = {**c["status"], peer: oc["status"].get(peer, "")}
            c["cpu_seconds"] = {**c["cpu_seconds"], peer: oc["cpu_seconds"].get(peer),
                                "ratio_asperity_over": {**c["cpu_seconds"]["ratio_asperity_over"],
                                                        peer: oc["cpu_seconds"]["ratio_asperity_over"].get(peer)}}
    return c, merged


def case_rows(c, name, peers):
    """The table's rows of one case's comparison, one per peer measured in it."""
    rows = []
    for peer in peers:
        if peer not in c["status"] and peer not in c.get("not_run", {}):
            continue  # not measured in this run (a partial --tables-only)
        row = {"case": name, "law": c["contact_law"], "recorded_body": c.get("recorded_body", ""),
               "steps": c["steps"], "peer": peer, "status": c["status"].get(peer, "")}
        why = c.get("not_run", {}).get(peer)
        if why:
            row["status"] = "not run"
            row["reason"] = why.split(": ", 1)[-1]
        for q in ("peak_force", "impulse", "contact_duration"):
            row[q + "_rel_diff"] = c[q]["rel_diff"].get(peer)
        row["restitution_rel_diff"] = c["other"].get("restitution", {}).get("rel_diff", {}).get(peer)
        row["cpu_asperity_s"] = c["cpu_seconds"]["asperity"]
        row["cpu_peer_s"] = c["cpu_seconds"].get(peer)
        row["ratio_asperity_over_peer"] = c["cpu_seconds"]["ratio_asperity_over"].get(peer)
        rows.append(row)
    return rows


def run_cases(a, files):
    """Each case's crosscheck (or, --tables-only, an earlier run's comparison): the table's rows,
    the cases not measured as (name, exit, message), and the cases with a peer from --also-runs."""
    exe, out, peers, tables_only, also_runs = a["exe"], a["out"], a["peers"], a["tables_only"], a["also_runs"]
    rows, failed = [], []
    merged = set()  # cases with a peer from --also-runs

    def crosscheck(f):
        run_dir = out / "runs" / json.loads(f.read_text())["case"]
        if tables_only:
            return subprocess.CompletedProcess([], 0 if (run_dir / "comparison.json").exists() else 2, "",
                                               "no comparison.json from an earlier run")
        return subprocess.run([exe, "crosscheck", str(f), "--out", str(run_dir), "--peer", ",".join(peers),
                               "--only-expressible", "--quiet"], capture_output=True, text=True)

    # Cases in parallel (--jobs): each case's codes still run one after the other, and the CPU
    # times are CPU, not wall; the order of the table is the files' order.
    with concurrent.futures.ThreadPoolExecutor(max_workers=a["jobs"]) as pool:
        done = list(pool.map(crosscheck, files))
    for k, (f, p) in enumerate(zip(files, done)):
        name = json.loads(f.read_text())["case"]
        run_dir = out / "runs" / name
        cmp_file = run_dir / "comparison.json"
        if tables_only and not cmp_file.exists():
            cmp_file = next((d / name / "comparison.json" for d in also_runs
                             if (d / name / "comparison.json").exists()), cmp_file)
            p = subprocess.CompletedProcess([], 0 if cmp_file.exists() else 2, "", p.stderr)
        if p.returncode not in (0, 1) or not cmp_file.exists():
            failed.append((name, p.returncode, p.stderr.strip()))
            print(f"[{k + 1}/{len(files)}] {name}: FAILED ({p.returncode}) {p.stderr.strip()}", file=sys.stderr)
            continue
        # --also-runs: a peer this run left out of the case comes from another run's comparison.
        c, took = with_other_runs(json.loads(cmp_file.read_text()), name, peers, also_runs)
        if took:
            merged.add(name)
        rows += case_rows(c, name, peers)
        print(f"[{k + 1}/{len(files)}] {name}: done", file=sys.stderr)
    return rows, failed, merged


def write_peers_csv(out, rows):
    out.mkdir(parents=True, exist_ok=True)
    fields = ["case", "law", "recorded_body", "steps", "peer", "status", "peak_force_rel_diff", "impulse_rel_diff",
              "contact_duration_rel_diff", "restitution_rel_diff", "cpu_asperity_s", "cpu_peer_s",
              "ratio_asperity_over_peer", "reason"]
    with open(out / "peers.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)


def fmt(x, spec):
    return "" if x is None or x == "" else format(x, spec)


def peer_summaries(peers, rows, program):
    """A paragraph per peer: its cases run, not expressible and refused, the CPU ratio's median
    and spread (spread_table's, program) and its largest differences."""
    def measured(peer):
        return [r for r in rows if r["peer"] == peer and r["status"] not in ("not run",)
                and not str(r["status"]).startswith("failed") and r["cpu_peer_s"] is not None]

    ratio_spread = spread((((peer,), r["ratio_asperity_over_peer"]) for peer in peers for r in measured(peer)
                           if r["ratio_asperity_over_peer"]), program)
    lines = []
    for peer in peers:
        rs = measured(peer)
        nr = [r for r in rows if r["peer"] == peer and r["status"] == "not run"]
        ratio = ratio_spread.get((peer,))
        worst = {q: max((abs(r[q + "_rel_diff"]) for r in rs if r[q + "_rel_diff"] is not None), default=None)
                 for q in ("peak_force", "impulse", "contact_duration")}
        fl = [r for r in rows if r["peer"] == peer and str(r["status"]).startswith("failed")]
        lines.append(f"**{peer}**: {len(rs)} cases run, {len(nr)} not expressible, {len(fl)} refused by the peer "
                     "as it ran (reasons in the table). "
                     + (f"CPU ratio asperity/{peer}: median {ratio[1]:.3f}, "
                        f"min {ratio[2]:.3f}, max {ratio[3]:.3f}. " if ratio else "")
                     + "Largest |difference|: " + ", ".join(f"{q} {fmt(v, '.2e')}" for q, v in worst.items()) + ".")
        lines.append("")
    return lines


def table_lines(rows, failed):
    """The table: a row per case and peer, then the cases not measured."""
    lines = ["| case | law | recorded | steps | peer | Δ peak force | Δ impulse | Δ duration | Δ restitution | "
             "asperity CPU s | peer CPU s | asperity/peer |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if str(r["status"]).startswith("failed"):
            why = str(r["status"]).split(": ", 1)[-1].split(" [log:")[0].replace("|", "/")
            lines.append(f"| {r['case']} | {r['law']} | {r['recorded_body']} | {r['steps']} | {r['peer']} | "
                         f"failed: {why} | | | | | | |")
            continue
        if r["status"] == "not run":
            lines.append(f"| {r['case']} | {r['law']} | {r['recorded_body']} | {r['steps']} | {r['peer']} | "
                         f"not run: {r['reason']} | | | | | | |")
            continue
        lines.append(f"| {r['case']} | {r['law']} | {r['recorded_body']} | {r['steps']} | {r['peer']} | "
                     f"{fmt(r['peak_force_rel_diff'], '.2e')} | {fmt(r['impulse_rel_diff'], '.2e')} | "
                     f"{fmt(r['contact_duration_rel_diff'], '.2e')} | {fmt(r['restitution_rel_diff'], '.2e')} | "
                     f"{fmt(r['cpu_asperity_s'], '.5f')} | {fmt(r['cpu_peer_s'], '.5f')} | "
                     f"{fmt(r['ratio_asperity_over_peer'], '.3f')} |")
    for name, code, err in failed:
        lines.append(f"| {name} | failed (exit {code}) | {err} | | | | | | | | | |")
    return lines


def write_peers_md(out, peers, rows, failed, merged, program):
    lines = [
        "# asperity against YADE, LAMMPS and LIGGGHTS: agreement and cost, case by case",
        "",
        f"Machine: {platform.machine()}, {os.cpu_count()} CPUs, {platform.platform()}. Each case is one "
        "`asperity crosscheck --peer " + ",".join(peers) + "` run (tools/report/peer_table.py): every code "
        "single-threaded, same scene, same dt, same step count, run one after the other. A peer's CPU time is "
        "its loop without any per-step recorder or dump (LIGGGHTS prints its loop's wall time only, so its "
        "figure is that wall time); asperity's includes its per-step recording, which dominates these short "
        "runs (a few hundred to a few thousand steps): the like-for-like cost per step is cost.md's. "
        "Differences are (asperity − peer)/peer. docs/crosscheck.md explains every mapping and systematic "
        "difference.",
        "",
    ]
    if merged:
        lines += [f"{len(merged)} cases take some peers' columns from a second such run on the same machine "
                  "(`--also-runs`; such a row's asperity CPU is this run's, its ratio that run's).", ""]
    if failed:
        lines += [f"{len(failed)} cases were not measured in this run; they are listed at the end of the table.", ""]
    lines += peer_summaries(peers, rows, program)
    lines += table_lines(rows, failed)
    lines += ["", "Cost per step on a two-sphere scene and a 10,000-sphere bed: [cost.md](cost.md) "
              "(tools/report/peer_cost.py)."]
    (out / "peers.md").write_text("\n".join(lines) + "\n")


def main(argv):
    a = parse_args(argv)
    if a is None:
        print(__doc__)
        return 2
    exe, out, peers = a["exe"], a["out"], a["peers"]
    files = []
    for t in a["targets"]:
        files += sorted(t.rglob("*.json")) if t.is_dir() else [t]
    listed = sphere_cases(exe)
    files = [f for f in files if f.resolve() in listed]
    rows, failed, merged = run_cases(a, files)
    write_peers_csv(out, rows)
    program = pathlib.Path(exe).resolve().parent / "spread_table"
    write_peers_md(out, peers, rows, failed, merged, program)
    if a["yade_table"] and "yade" in peers:
        write_yade_table(a["yade_table"], [r for r in rows if r["peer"] == "yade" and r["status"] != "not run"
                                           and r["cpu_peer_s"] is not None], program)
    print(f"{len(files)} cases -> {out / 'peers.md'}", file=sys.stderr)
    return 1 if failed else 0


def write_yade_table(out, rows, program):
    """The YADE rows alone, in the columns of the earlier YADE-only table (study_report.py reads
    crosscheck.csv); the ratios' median and spread are spread_table's (program)."""
    out.mkdir(parents=True, exist_ok=True)
    fields = ["case", "law", "steps", "peak_force_rel_diff", "impulse_rel_diff", "contact_duration_rel_diff",
              "cpu_asperity_s", "cpu_yade_s", "ratio"]
    table = [{"case": r["case"], "law": r["law"], "steps": r["steps"],
              "peak_force_rel_diff": r["peak_force_rel_diff"], "impulse_rel_diff": r["impulse_rel_diff"],
              "contact_duration_rel_diff": r["contact_duration_rel_diff"], "cpu_asperity_s": r["cpu_asperity_s"],
              "cpu_yade_s": r["cpu_peer_s"], "ratio": r["ratio_asperity_over_peer"]} for r in rows]
    with open(out / "crosscheck.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=fields)
        w.writeheader()
        w.writerows(table)
    ratio = spread(((("yade",), r["ratio"]) for r in table if r["ratio"]), program).get(("yade",))
    cpu_a = sum(r["cpu_asperity_s"] or 0 for r in table)
    cpu_y = sum(r["cpu_yade_s"] or 0 for r in table)
    lines = ["# asperity against YADE: agreement and cost, case by case", "",
             f"Machine: {platform.machine()}, {os.cpu_count()} CPUs, {platform.platform()}; both codes single-threaded, "
             "same scene, same dt, same step count, run one after the other by `asperity crosscheck` "
             "(tools/report/peer_table.py --yade-table, the YADE rows of reports/peers/peers.md). YADE's CPU time "
             "is its engine loop alone (no Python in the loop); asperity's includes its per-step recording. Relative "
             "differences are (asperity − YADE)/YADE. docs/crosscheck.md explains every systematic difference.", "",
             f"{len(table)} cases cross-checked. CPU in all: asperity {cpu_a:.3f} s, YADE {cpu_y:.3f} s"
             + (f" (ratio {cpu_a / cpu_y:.3f})" if cpu_y else "") + "."
             + (f" Ratio asperity/YADE per case: median {ratio[1]:.3f}, min {ratio[2]:.3f}, "
                f"max {ratio[3]:.3f}." if ratio else ""), "",
             "| case | law | steps | Δ peak force | Δ impulse | Δ duration | asperity CPU s | YADE CPU s | asperity/YADE |",
             "|---|---|---|---|---|---|---|---|---|"]

    def fmt(x, spec):
        return "" if x is None or x == "" else format(x, spec)

    for r in table:
        lines.append(f"| {r['case']} | {r['law']} | {r['steps']} | {fmt(r['peak_force_rel_diff'], '.2e')} | "
                     f"{fmt(r['impulse_rel_diff'], '.2e')} | {fmt(r['contact_duration_rel_diff'], '.2e')} | "
                     f"{fmt(r['cpu_asperity_s'], '.5f')} | {fmt(r['cpu_yade_s'], '.5f')} | {fmt(r['ratio'], '.3f')} |")
    (out / "crosscheck.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
