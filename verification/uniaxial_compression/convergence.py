#!/usr/bin/env python3
"""Uniaxial compression plate (THEORY sec. 11), the demo scene as it stands (improved
formulation, support at the face; --set options can be appended to the command): top-centre
vertical displacement against the CalculiX value -0.4466475 mm, for several spacings at
horizon ratio 3.015, with run times. Usage: convergence.py PERINOM_BINARY [OUT_DIR] [--set k=v ...]
Writes OUT_DIR/convergence.csv and prints a Markdown table."""
import json, os, subprocess, sys, time

FEM_TOP_CENTER_UY = -0.4466475e-3  # m, CalculiX, verification/fem (Richardson)
HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "..", "examples", "uniaxial_compression.yaml")

def main():
    exe = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else "out/verification/uniaxial_compression"
    extra = sys.argv[3:]
    os.makedirs(out, exist_ok=True)
    rows = []
    for dx in [4e-3, 2e-3, 1e-3, 0.5e-3]:
        run_dir = os.path.join(out, f"dx_{dx*1e3:g}mm")
        t0 = time.time()
        subprocess.run([exe, "run", SCENE, "--out", run_dir, "--set", f"discretization.dx={dx}"] + extra,
                       check=True, stdout=subprocess.DEVNULL)
        wall = time.time() - t0
        s = json.load(open(os.path.join(run_dir, "summary.json")))
        uy = s["probes"]["top_center_uy"]
        rows.append((dx, s["particles"], s["solver"]["iterations"], uy,
                     (uy - FEM_TOP_CENTER_UY) / abs(FEM_TOP_CENTER_UY), s["wall_time"]["solve"], wall))
    with open(os.path.join(out, "convergence.csv"), "w") as f:
        f.write("dx_m,particles,iterations,top_center_uy_m,relative_error,solve_s,wall_s\n")
        for r in rows:
            f.write(",".join(repr(v) for v in r) + "\n")
    print("| dx (mm) | particles | ADR iterations | top-centre u_y (mm) | error vs FEM | solve (s) |")
    print("|---|---|---|---|---|---|")
    for dx, n, it, uy, err, solve, wall in rows:
        print(f"| {dx*1e3:g} | {n} | {it} | {uy*1e3:.5f} | {err*100:+.3f}% | {solve:.2f} |")

if __name__ == "__main__":
    main()
