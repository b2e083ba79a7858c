#!/usr/bin/env python3
"""FEM reference for Prandtl's strip footing (verification/footing/footing.yaml), by CalculiX.

What is solved
  The scene's half model: a 5 x 5 m block in plane strain (thickness 1 m), E = 100 MPa,
  nu = 0.3, von Mises perfect plasticity with the yield stress sqrt(3) k = 2 c = 200 kPa
  (Drucker-Prager with phi = 0 and c = 100 kPa: sqrt(J2) at yield k = 2 c / sqrt(3)). The
  edges x = 0 and x = 5 on rollers (u_x = 0), the bottom fixed, the top nodes with x <= 1 m
  moved down by 0.05 m (a smooth footing of half-width b = 1 m) in 50 equal increments.
  Prandtl's collapse pressure (2 + pi) k = 593.7 kPa, a reaction of 593.7 kN per metre on
  the half footing.

How
  Structured 8-node quads (gmsh, Transfinite + Recombine, second order, incomplete) of side
  h, CPE8R (reduced integration, which does not lock in isochoric plastic flow), ccx's
  *PLASTIC (von Mises, associated). The footing's reaction is read at every increment
  (*NODE PRINT, TOTALS=ONLY).

Outputs (in this folder): footing.csv, one row per mesh and increment: h_m, settlement_m,
  reaction_N (per metre, on the half footing), over_prandtl.

Usage: python3 verification/fem/footing.py [--keep DIR] [--out DIR]
Needs gmsh and CalculiX (apt-get install gmsh calculix-ccx). Runs single-threaded (~2 min).
"""
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ccx_common as cc
import numpy as np

SIDE, B, SETTLE = 5.0, 1.0, 0.05
E, NU, C = 1e8, 0.3, 1e5
K = 2 * C / math.sqrt(3)
PRANDTL = (2 + math.pi) * K * B
H_LIST = [0.25, 0.125, 0.0625]
INCREMENTS = 50

GEO = """Point(1) = {{0, 0, 0}}; Point(2) = {{{s}, 0, 0}}; Point(3) = {{{s}, {s}, 0}}; Point(4) = {{0, {s}, 0}};
Line(1) = {{1, 2}}; Line(2) = {{2, 3}}; Line(3) = {{3, 4}}; Line(4) = {{4, 1}};
Curve Loop(1) = {{1, 2, 3, 4}}; Plane Surface(1) = {{1}};
Transfinite Curve{{1, 2, 3, 4}} = {n1}; Transfinite Surface{{1}}; Recombine Surface{{1}};
Physical Surface("block") = {{1}};
Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
"""


def solve(h, work):
    n = round(SIDE / h)
    ids, xy, elems = cc.quad8_mesh(cc.gmsh(GEO.format(s=SIDE, n1=n + 1), work, "block"))
    xy = np.round(xy / (h / 2)) * (h / 2)
    tol = 1e-6 * h
    left, right = ids[np.abs(xy[:, 0]) < tol], ids[np.abs(xy[:, 0] - SIDE) < tol]
    bottom = ids[np.abs(xy[:, 1]) < tol]
    foot = ids[(np.abs(xy[:, 1] - SIDE) < tol) & (xy[:, 0] < B + tol)]
    with open(os.path.join(work, "footing.inp"), "w") as f:
        cc.write_mesh(f, f"Prandtl footing, h = {h}", ids, xy, elems, "CPE8R")
        for name, nodes in (("NLEFT", left), ("NRIGHT", right), ("NBOT", bottom), ("NFOOT", foot)):
            cc.write_nset(f, name, nodes)
        f.write(f"*MATERIAL, NAME=M\n*ELASTIC\n{cc.num(E)}, {cc.num(NU)}\n*PLASTIC\n{cc.num(2 * C)}, 0.0\n")
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=M\n1.0\n")
        f.write("*BOUNDARY\nNLEFT, 1, 1, 0.0\nNRIGHT, 1, 1, 0.0\nNBOT, 1, 2, 0.0\n")
        f.write(f"*STEP, NLGEOM=NO, INC=1000\n*STATIC, DIRECT\n{1 / INCREMENTS}, 1.0\n")
        f.write(f"*BOUNDARY\nNFOOT, 2, 2, {cc.num(-SETTLE)}\n")
        f.write("*NODE PRINT, NSET=NFOOT, TOTALS=ONLY\nRF\n*END STEP\n")
    seconds = cc.run_ccx(work, "footing", f"h = {h}")
    rows = []
    time = None
    for line in open(os.path.join(work, "footing.dat")):
        m = re.search(r"total force .* time\s+(\S+)", line)
        if m:
            time = float(m.group(1))
            continue
        t = line.split()
        if time is not None and len(t) >= 2:
            rows.append((time * SETTLE, -float(t[1])))
            time = None
    return rows, seconds


def main():
    a = cc.parse_args(__doc__)
    out = []
    for h in H_LIST:
        rows, seconds = cc.in_work_folder(f"perinom_fem_footing_h{h:g}_", a.keep, f"h{h:g}", lambda w, h=h: solve(h, w))
        print(f"h = {h:g} m ({round(SIDE / h) ** 2} CPE8R, {seconds:.1f} s): reaction / Prandtl at "
              + ", ".join(f"{s * 100:.1f} cm {r / PRANDTL:.3f}" for s, r in rows[4::5]), flush=True)
        out += [f"{h:g},{s:.6g},{r:.7e},{r / PRANDTL:.5f}" for s, r in rows]
    os.makedirs(a.out, exist_ok=True)
    cc.write_csv(os.path.join(a.out, "footing.csv"), "h_m,settlement_m,reaction_N,over_prandtl", out)
    print("wrote footing.csv in", a.out)


if __name__ == "__main__":
    main()
