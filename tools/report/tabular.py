"""Reading the tables the C++ writes and formatting their cells: the one reader and the one number
format every report writer in this folder uses (study_report.py, geometry_table.py, ...), so a
cell prints the same in every report. Python reads and draws; the numbers are the tables'. A
writer that repeats a measurement hands its samples to the C++ for their median and spread
(`spread`, app/spread_table)."""
import csv
import math
import pathlib
import subprocess
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]


def read_csv(path):
    """The rows of a CSV table as dicts keyed by its header."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(x):
    """A cell as a float; an empty or non-numeric cell is NaN."""
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def fmt(x, digits=4):
    """A number to `digits` significant digits; a cell that is not a number as it was."""
    v = num(x)
    if math.isnan(v):
        return "" if x in (None, "") else str(x)
    return f"{v:.{digits}g}"


def pct(x, digits=2):
    """A fraction as a percentage with `digits` decimals; empty when it is not a finite number."""
    v = num(x)
    return "" if not math.isfinite(v) else f"{100 * v:.{digits}f} %"


def spread(samples, program=ROOT / "build" / "bin" / "spread_table"):
    """The median and spread of repeated measurements by group, computed by the C++ that owns the
    median (app/spread_table, solver/core/quantile.hpp): samples are (key, value) pairs, key a
    tuple of plain strings (no comma, quote or line end), value a number. Returns {key: (count,
    median, min, max)} in the order the groups first show; program: a build's spread_table (default
    the source tree's build/)."""
    samples = list(samples)
    if not samples:
        return {}
    width = len(samples[0][0])
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        with open(tmp / "samples.csv", "w", newline="") as fh:
            w = csv.writer(fh, lineterminator="\n")
            w.writerow([f"key{i}" for i in range(width)] + ["value"])
            for key, value in samples:
                if len(key) != width or any(set(str(k)) & set(',"\r\n') for k in key):
                    raise ValueError(f"spread: a key must be {width} plain fields: {key!r}")
                w.writerow(list(key) + [repr(float(value))])
        p = subprocess.run([str(program), str(tmp / "samples.csv"), str(tmp / "spread.csv")],
                           capture_output=True, text=True)
        if p.returncode != 0:
            raise RuntimeError(f"{program}: exit {p.returncode}: {p.stderr.strip()}")
        return {tuple(r[f"key{i}"] for i in range(width)):
                (int(r["count"]), float(r["median"]), float(r["min"]), float(r["max"]))
                for r in read_csv(tmp / "spread.csv")}
