#!/usr/bin/python3
"""The seed's square thin plate (seed 002 sec. 6.2; THEORY sec. 7) against Timoshenko.

Solved: a = 0.5 m square, t = 0.01 m, E = 210 GPa, nu = 0.3, uniform pressure q = 1 kPa,
all four edges simply supported or clamped; D0 = E t^3 / (12 (1 - nu^2)). References: the
centre deflection w_c = alpha q a^4 / D0, alpha = 0.00406 (simply supported) and 0.00126
(clamped) (Timoshenko and Woinowsky-Krieger, tables 8 and 35).

  1. Static: examples/thin_plate_{simply_supported,clamped}.yaml solved by ADR at
     20, 40, 80 cells per side (21, 41, 81 nodes; more with --fine), every other key as in
     the examples; centre deflection, relative error, ADR iterations, wall time and peak
     memory into thin_plate_static.csv and a table on stdout.
  2. Dynamic (the seed's Fig. 6): the same plates at 41 x 41 under the pressure applied at
     t = 0, Velocity Verlet at 0.8 of the stable step for 2000 steps (11 ms); the centre
     deflection every 10 steps (from the snapshots' CSV) into thin_plate_dynamic_{support}.csv, plotted with
     the static answer and the reference in thin_plate_dynamic.png; the period, from the
     upward crossings of the static deflection, against the fundamental mode
     omega = c pi^2 / a^2 sqrt(D0 / (rho t)), c = 2 (simply supported), 3.646 (clamped).

Run from the repository root:  /usr/bin/python3 verification/thin_plate/thin_plate.py
  [--perinom build/drivers/perinom] [--out out/thin_plate] [--docs docs/verification] [--fine]
"""
import argparse
import csv
import glob
import json
import os
import subprocess
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

A, T, E, NU, Q = 0.5, 0.01, 210e9, 0.3, 1000.0
D0 = E * T**3 / (12 * (1 - NU**2))
ALPHA = {"simply_supported": 0.00406, "clamped": 0.00126}


def reference(support):
    return ALPHA[support] * Q * A**4 / D0


def run(perinom, support, out, sets):
    """perinom run on the example with --set overrides; returns (summary, seconds, peak KiB)."""
    scene = f"examples/thin_plate_{support}.yaml"
    cmd = ["/usr/bin/time", "-f", "%M", perinom, "run", scene, "--out", out]
    for s in sets:
        cmd += ["--set", s]
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    seconds = time.time() - t0
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr}")
    peak_kib = int(p.stderr.strip().splitlines()[-1])
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f), seconds, peak_kib


def static_sweep(args, cells):
    rows = []
    for support in ALPHA:
        for n in cells:
            s, sec, kib = run(args.perinom, support, f"{args.out}/static_{support}_{n}",
                              [f"discretization.dx={A / n!r}"])
            w = s["probes"]["center_w"]
            rows.append({"support": support, "nodes_per_side": n + 1, "particles": s["particles"],
                         "center_w": w, "reference": reference(support),
                         "relative_error": w / reference(support) - 1, "iterations": s["solver"]["iterations"],
                         "solve_seconds": s["wall_time"]["solve"], "wall_seconds": sec, "peak_MiB": kib / 1024})
            r = rows[-1]
            print(f"{support:17s} {n + 1:4d}^2  w_c = {w:.5e}  ref {r['reference']:.5e}  error "
                  f"{100 * r['relative_error']:+.2f}%  {r['iterations']} it  {sec:.1f} s  {r['peak_MiB']:.0f} MiB",
                  flush=True)
    with open(os.path.join(args.docs, "thin_plate_static.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return rows


def dynamic(args, support, static_w):
    out = f"{args.out}/dynamic_{support}"
    for old in glob.glob(f"{out}/*.csv"):
        os.remove(old)
    s, sec, _ = run(args.perinom, support, out,
                    ["solver.type=verlet", "solver.steps=2000", "output.vtk_every=10", "output.csv=true"])
    dt = s["solver"]["end_time"] / s["solver"]["iterations"]
    # Snapshots k = 0, 1, ... at steps 10 k; the centre node is the probe's (the middle node).
    history = []
    for k, path in enumerate(sorted(glob.glob(f"{out}/thin_plate_{support}_*.csv"))):
        with open(path) as f:
            for row in csv.DictReader(f):
                if abs(float(row["x"]) - A / 2) < 1e-9 and abs(float(row["y"]) - A / 2) < 1e-9:
                    history.append((10 * (k + 1) * dt, float(row["deflection"])))
    with open(os.path.join(args.docs, f"thin_plate_dynamic_{support}.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time", "center_w"])
        w.writerows(history)
    ups = [t0 + (static_w - w0) / (w1 - w0) * (t1 - t0)
           for (t0, w0), (t1, w1) in zip(history, history[1:]) if w0 < static_w <= w1]
    period = (ups[-1] - ups[0]) / (len(ups) - 1)
    omega = {"simply_supported": 2.0, "clamped": 3.646}[support] * 3.141592653589793**2 / A**2 * (D0 / (7800.0 * T)) ** 0.5
    print(f"{support}: period {1e3 * period:.4f} ms against the fundamental mode's {2e3 * 3.141592653589793 / omega:.4f} ms")
    print(f"{support}: Verlet {s['solver']['iterations']} steps of {dt:.3e} s (stable {s['solver']['stable_time_step']:.3e} s)"
          f" in {sec:.1f} s; peak centre deflection {max(h[1] for h in history):.4e} m", flush=True)
    return history


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--perinom", default="build/drivers/perinom")
    ap.add_argument("--out", default="out/thin_plate")
    ap.add_argument("--docs", default="docs/verification")
    ap.add_argument("--fine", action="store_true", help="also 120 and 160 cells per side (long)")
    args = ap.parse_args()
    rows = static_sweep(args, [10, 20, 40, 80] + ([120, 160] if args.fine else []))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for ax, support in zip(axes, ALPHA):
        static_w = [r["center_w"] for r in rows if r["support"] == support and r["nodes_per_side"] == 41][0]
        h = dynamic(args, support, static_w)
        ax.plot([1e3 * t for t, _ in h], [1e6 * w for _, w in h], label="perinom, Verlet, 41 x 41")
        ax.axhline(1e6 * static_w, color="k", ls="--", lw=0.8, label="perinom, static (ADR)")
        ax.axhline(1e6 * reference(support), color="r", ls=":", lw=0.8, label="Timoshenko, static")
        ax.set_title(f"{support.replace('_', ' ')}: centre deflection, pressure from t = 0")
        ax.set_xlabel("t (ms)")
        ax.set_ylabel("w (um)")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(args.docs, "thin_plate_dynamic.png"), dpi=110)


if __name__ == "__main__":
    main()
