#!/usr/bin/env python3
"""FEM reference for the 2-D cantilever in plane strain as nu approaches 1/2, by CalculiX.

What is solved
  cantilever_2d.py's beam (0.1 x 0.01 m, E = 200e9 Pa, the edge x = 0 fully fixed, the
  uniform traction (0, -1e6) Pa on x = 0.1), here in plane strain (thickness 1 m) with
  nu = 0.3, 0.45, 0.49, 0.499, 0.4999: the range where a discretization can lock (its
  volumetric constraint pointwise too stiff for the nearly isochoric bending field).

How
  cantilever_2d.py's structured 8-node quads and consistent tip loads, solved by ccx with
  CPE8R (plane strain, reduced 2 x 2 integration, which does not lock) and, for comparison,
  CPE8 (full 3 x 3 integration, which locks as nu -> 1/2 on coarse meshes). The reference is
  the CPE8R tip-centre u_y Richardson-extrapolated from h = 1.25, 0.625, 0.3125 mm.

Outputs (in this folder): cantilever_2d_incompressible.csv, one row per nu and element:
  nu, element, h_m, tip_center_uy_m (h_m = 0: the extrapolated value); and the Timoshenko
  beam (plane strain: E / (1 - nu^2) in bending, k = 5/6) for reading.

Usage: python3 verification/fem/cantilever_2d_incompressible.py [--keep DIR] [--out DIR]
Needs gmsh and CalculiX (apt-get install gmsh calculix-ccx). Runs single-threaded (~1 min).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ccx_common as cc
import cantilever_2d as cb
import numpy as np

NUS = [0.3, 0.45, 0.49, 0.499, 0.4999]
H_LIST = [1.25e-3, 0.625e-3, 0.3125e-3]


def solve(h, nu, etype, work):
    ids, xy, elems = cb.mesh(h, work)
    w = cb.tip_weights(ids, xy, elems, h)
    tol = 1e-6 * h
    fixed = ids[np.abs(xy[:, 0]) < tol]
    pos = cc.node_index(ids)
    tip_centre = [nid for nid in ids if abs(xy[pos[nid], 0] - cb.L) < tol and abs(xy[pos[nid], 1] - cb.YC) < tol]
    assert len(tip_centre) == 1
    with open(os.path.join(work, "beam.inp"), "w") as f:
        cc.write_mesh(f, f"cantilever, tip shear, plane strain, nu {nu}, {etype}", ids, xy, elems, etype)
        cc.write_nset(f, "NFIX", fixed)
        cc.write_nset(f, "NOUT", tip_centre)
        f.write(f"*MATERIAL, NAME=M\n*ELASTIC\n{cc.num(cb.E)}, {cc.num(nu)}\n")
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=M\n1.0\n")
        f.write("*BOUNDARY\nNFIX, 1, 2, 0.0\n*STEP\n*STATIC\n*CLOAD\n")
        for nid in sorted(w):
            f.write(f"{nid}, 2, {cc.num(cb.TY * w[nid])}\n")
        f.write("*NODE PRINT, NSET=NOUT\nU\n*NODE PRINT, NSET=NFIX, TOTALS=ONLY\nRF\n*END STEP\n")
    cc.run_ccx(work, "beam", f"nu = {nu}, h = {h}, {etype}")
    u, (total,) = cc.parse_dat(os.path.join(work, "beam.dat"))
    assert abs(total[1] + cb.PY) <= 5e-6 * abs(cb.PY), total   # the .dat holds 7 digits
    return u[tip_centre[0]][1]


def timoshenko(nu):
    e_beam = cb.E / (1 - nu ** 2)
    g = cb.E / (2 * (1 + nu))
    return cb.PY * cb.L ** 3 / (3 * e_beam * cb.I_SEC) + cb.PY * cb.L / (cb.K_SHEAR * g * cb.H)


def main():
    a = cc.parse_args(__doc__)
    rows = []
    for nu in NUS:
        for etype in ("CPE8R", "CPE8"):
            f = [cc.in_work_folder(f"perinom_fem_cant2d_nu{nu}_", a.keep, f"nu{nu}_{etype}_h{h * 1e3:g}mm",
                                   lambda work, h=h: solve(h, nu, etype, work)) for h in H_LIST]
            p, lim = cc.richardson(*f)
            rows += [f"{nu},{etype},{h:.6g},{uy:.7e}" for h, uy in zip(H_LIST, f)] + [f"{nu},{etype},0,{lim:.7e}"]
            print(f"nu = {nu}, {etype}: tip-centre u_y {', '.join(f'{x:.6e}' for x in f)} m; order {p:.2f}, "
                  f"extrapolated {lim:.7e} m; Timoshenko {timoshenko(nu):.6e} m", flush=True)
    os.makedirs(a.out, exist_ok=True)
    cc.write_csv(os.path.join(a.out, "cantilever_2d_incompressible.csv"), "nu,element,h_m,tip_center_uy_m", rows)
    print("wrote cantilever_2d_incompressible.csv in", a.out)


if __name__ == "__main__":
    main()
