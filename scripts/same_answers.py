#!/usr/bin/env python3
"""Do two perinom binaries give the same answers? (issue 16: a refactor changes no answer)

Runs every scene of a list with both binaries, one thread each (so the comparison does not
depend on the thread count or the thread governor), and compares every number of
summary.json (wall times and memory excepted) and of every CSV file the runs write. Prints
one line per scene with the largest relative difference, and exits 1 if any exceeds the
tolerance.

  scripts/same_answers.py --old /work/before/perinom --new build/drivers/perinom [--tolerance 1e-12]

A binary whose library is not next to its RUNPATH can be given as LIB:BIN
(e.g. /work/before:/work/before/perinom), and runs with LD_LIBRARY_PATH=LIB.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time

# (scene, --set overrides): every example, the verification scenes at their committed
# resolution, and variants that reach each operator, stabilization storage, formulation and
# solver path.
CASES = [
    ("examples/biaxial_compression.yaml", []),
    ("examples/biaxial_compression.yaml", ["model.kinematics=finite_rotation"]),
    ("examples/lame_cylinder.yaml", []),
    ("examples/plate_with_hole.yaml", []),
    ("examples/thin_plate_clamped.yaml", []),
    ("examples/thin_plate_simply_supported.yaml", []),
    ("examples/uniaxial_compression.yaml", []),
    ("examples/vibrating_bar.yaml", []),
    ("examples/vibrating_bar.yaml", ["model.operator_order=1", "model.formulation=classical"]),
    ("examples/vibrating_bar.yaml", ["model.operator_order=1", "model.formulation=classical",
                                     "model.stabilization_storage=assembled"]),
    ("examples/vibrating_bar.yaml", ["model.operator_order=1", "model.formulation=classical",
                                     "model.stabilization_storage=matrix_free"]),
    ("examples/vibrating_bar.yaml", ["model.operator_order=1", "model.formulation=classical",
                                     "model.weight_precision=single"]),
    ("examples/plate_with_hole.yaml", ["discretization.dx=0.004", "model.formulation=improved"]),
    ("examples/plate_with_hole.yaml", ["discretization.dx=0.004", "model.formulation=strong"]),
    ("examples/plate_with_hole.yaml", ["discretization.dx=0.004", "model.formulation=classical"]),
    ("examples/plate_with_hole.yaml", ["discretization.dx=0.004", "solver.type=newton"]),
    ("verification/formulation/cantilever_2d.yaml", []),
    ("verification/formulation/cantilever_2d.yaml", ["model.formulation=classical"]),
    ("verification/formulation/cantilever_3d.yaml", []),
    ("verification/formulation/plate_hole.yaml", []),
    ("verification/formulation/plate_hole_mesh.yaml", []),
    ("verification/lame/lame.yaml", []),
]

IGNORED = ("wall_time", "memory", "threads", "scene")


def numbers(value, path=""):
    """Flattens a JSON value into {path: number or string}."""
    out = {}
    if isinstance(value, dict):
        for k, v in value.items():
            if k not in IGNORED:
                out.update(numbers(v, f"{path}.{k}"))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            out.update(numbers(v, f"{path}[{i}]"))
    else:
        out[path] = value
    return out


def csv_numbers(path):
    """Every cell of a CSV file but those of its wall-time column (`seconds`)."""
    out = {}
    with open(path) as f:
        rows = list(csv.reader(f))
    timed = {c for c, name in enumerate(rows[0] if rows else []) if name == "seconds"}
    for r, row in enumerate(rows):
        for c, cell in enumerate(row):
            if c not in timed:
                out[f"{os.path.basename(path)}[{r},{c}]"] = cell
    return out


def outputs(folder):
    """Every compared value of a run's output folder."""
    values = {}
    with open(os.path.join(folder, "summary.json")) as f:
        values.update(numbers(json.load(f)))
    for name in sorted(os.listdir(folder)):
        if name.endswith(".csv"):
            values.update(csv_numbers(os.path.join(folder, name)))
    return values


def run(binary, scene, sets, out):
    lib, _, exe = binary.rpartition(":")
    env = dict(os.environ, OMP_NUM_THREADS="1", PERINOM_THREAD_GOVERNOR="off")
    if lib:
        env["LD_LIBRARY_PATH"] = lib
    cmd = [exe, "run", scene, "--out", out] + [a for s in sets for a in ("--set", s)]
    start = time.time()
    p = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    return p.returncode, time.time() - start, p.stderr


def difference(a, b):
    """The largest relative difference between two value maps, and where (inf: not comparable)."""
    worst, where = 0.0, ""
    for key in sorted(set(a) | set(b)):
        if key not in a or key not in b:
            return math.inf, f"{key} only in one run"
        x, y = a[key], b[key]
        try:
            x, y = float(x), float(y)
        except (TypeError, ValueError):
            if x != y:
                return math.inf, f"{key}: {x!r} != {y!r}"
            continue
        if x == y or (math.isnan(x) and math.isnan(y)):
            continue
        d = abs(x - y) / max(abs(x), abs(y), 1e-300)
        if d > worst:
            worst, where = d, key
    return worst, where


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--old", required=True)
    ap.add_argument("--new", required=True)
    ap.add_argument("--tolerance", type=float, default=1e-12)
    args = ap.parse_args()
    failed = 0
    print(f"{'scene':<48} {'overrides':<48} {'max rel diff':>12} {'old s':>7} {'new s':>7}")
    with tempfile.TemporaryDirectory() as tmp:
        for n, (scene, sets) in enumerate(CASES):
            folders = [os.path.join(tmp, f"{n}_{tag}") for tag in ("old", "new")]
            results = [run(b, scene, sets, f) for b, f in zip((args.old, args.new), folders)]
            if any(r[0] != 0 for r in results):  # nothing to compare: a failure either way
                worst, where = math.inf, f"exit codes {results[0][0]} and {results[1][0]}"
            else:
                worst, where = difference(outputs(folders[0]), outputs(folders[1]))
            bad = worst > args.tolerance
            failed += bad
            print(f"{scene:<48} {' '.join(sets):<48} {worst:12.3e} {results[0][1]:7.1f} {results[1][1]:7.1f}"
                  + (f"  DIFFERS at {where}" if bad else ""))
            sys.stdout.flush()
    print(f"{len(CASES) - failed} of {len(CASES)} scenes give the same answers (tolerance {args.tolerance:g})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
