"""Reading the tables the C++ writes and formatting their cells: the one reader and the one number
format every report writer in this folder uses (study_report.py, geometry_table.py, ...), so a
cell prints the same in every report. Python reads and draws; the numbers are the tables'."""
import csv
import math


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
