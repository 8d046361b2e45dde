"""The peers' scripts' one way to write an output file (scene_to_yade.py, yade_polyhedra.py,
scene_to_calculix.py): through PATH.partial and a rename, so that asperity, which reads raw.csv and
raw.json once the peer exits, never takes a file a failed or killed run left half written.
Runs under YADE's Python and Debian's python3 alike (standard library only)."""
import json
import os


def write_atomically(path, write):
    """Calls write(fh) on PATH.partial, then renames it to PATH."""
    partial = path + ".partial"
    with open(partial, "w") as fh:
        write(fh)
    os.replace(partial, path)


def write_json(path, value):
    """VALUE as indented JSON at PATH, atomically."""
    write_atomically(path, lambda fh: json.dump(value, fh, indent=2))
