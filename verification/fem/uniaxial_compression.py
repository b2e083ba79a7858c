#!/usr/bin/env python3
"""FEM reference for the uniaxial compression plate (THEORY sec. 11), by CalculiX.

What is solved
  A plate 0.036 m wide (0 <= x <= 0.036) by 0.072 m tall (0 <= y <= 0.072), plane strain,
  linear elastic isotropic, E = 30e6 Pa, nu = 0.25, thickness 1 m. Bottom edge (y = 0) fixed
  in x and y; uniform pressure 200e3 Pa on the top edge (traction (0, -200e3)); left and
  right edges free. The bottom corners carry stress singularities (fixed edge meeting a free
  edge); the displacement far from them converges all the same.

How
  Structured meshes of square 8-node serendipity quads made by gmsh (Transfinite + Recombine,
  second order, incomplete), solved by CalculiX ccx with CPE8 elements (plane strain, full
  3x3 integration), the pressure applied as *DLOAD on the top element faces (consistent
  nodal loads, computed by ccx). Displacements and the total bottom reaction are read from
  the .dat file (*NODE PRINT); stresses are the .frd nodal stresses (*EL FILE, S): ccx
  extrapolates the integration-point stresses of each element to its nodes and averages
  the contributions of the elements sharing a node.

Outputs (in this folder; work files go to a temporary folder and are deleted)
  uniaxial_compression_top_center.csv  one row per mesh: h_m, elements, nodes,
                                       top_center_uy_m, seconds (ccx wall time); a last row
                                       with h_m = 0 holds the Richardson-extrapolated value.
  uniaxial_compression_centerline.csv  y_m, ux_m, uy_m, von_mises_pa, sxx_pa, syy_pa,
                                       szz_pa, sxy_pa at the nodes on x = 0.018, finest mesh.
  uniaxial_compression_fem.png         uy and von Mises along the centre line, every mesh.

Usage: python3 verification/fem/uniaxial_compression.py [--max-seconds S] [--keep DIR] [--out DIR]
Needs gmsh and CalculiX (Debian: apt-get install gmsh calculix-ccx), python3 with numpy
and matplotlib (Debian: python3-numpy python3-matplotlib). Runs single-threaded.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ccx_common as cc   # the shared helpers (it re-runs this under /usr/bin/python3 without numpy)
import numpy as np

# ---- problem data (SI) ------------------------------------------------------------------
W, H = 0.036, 0.072            # plate width and height, m
E, NU = 30e6, 0.25             # Pa, -
P = 200e3                      # top pressure, Pa
XC = W / 2                     # centre line
H_LIST = [4e-3, 2e-3, 1e-3, 0.5e-3, 0.25e-3]   # element sizes, m (W/h: 9, 18, 36, 72, 144)
EXPECTED_TOP_UY = -0.4466e-3   # m, THEORY sec. 11


# ---- step 1: mesh with gmsh -------------------------------------------------------------
GEO = """// uniaxial compression plate, structured 8-node quads
Point(1) = {{0, 0, 0}}; Point(2) = {{{W!r}, 0, 0}};
Point(3) = {{{W!r}, {H!r}, 0}}; Point(4) = {{0, {H!r}, 0}};
Line(1) = {{1, 2}}; Line(2) = {{2, 3}}; Line(3) = {{3, 4}}; Line(4) = {{4, 1}};
Curve Loop(1) = {{1, 2, 3, 4}}; Plane Surface(1) = {{1}};
Transfinite Curve{{1, 3}} = {nx1}; Transfinite Curve{{2, 4}} = {ny1};
Transfinite Surface{{1}}; Recombine Surface{{1}};
Physical Surface("plate") = {{1}};
Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
"""


def mesh(h, work):
    """Returns node ids, coordinates (n x 2) and 8-node elements (m x 8, node ids, ccx order)."""
    nx, ny = round(W / h), round(H / h)
    ids, xy, elems = cc.quad8_mesh(cc.gmsh(GEO.format(W=W, H=H, nx1=nx + 1, ny1=ny + 1), work, "plate"))
    assert len(elems) == nx * ny, (len(elems), nx, ny)
    # gmsh leaves round-off of order 1e-14 m on the structured grid; snap to the exact
    # half-element grid (the mesh is structured, so every node lies on it)
    snapped = np.round(xy / (h / 2)) * (h / 2)
    assert np.abs(snapped - xy).max() < 1e-9
    return ids, snapped, elems, nx, ny


# ---- step 2: CalculiX input -------------------------------------------------------------
def write_inp(path, ids, xy, elems, h):
    tol = 1e-6 * h
    bottom = ids[np.abs(xy[:, 1]) < tol]
    top_center = ids[(np.abs(xy[:, 1] - H) < tol) & (np.abs(xy[:, 0] - XC) < tol)]
    assert len(top_center) == 1
    dload = cc.faces_on(ids, elems, np.abs(xy[:, 1] - H) < tol)   # the top faces
    assert len(dload) == round(W / h)
    with open(path, "w") as f:
        cc.write_mesh(f, "uniaxial compression plate, plane strain, CPE8", ids, xy, elems, "CPE8", fmt=repr)
        cc.write_nset(f, "NBOT", bottom)
        f.write(f"*NSET, NSET=NTOPC\n{top_center[0]},\n")
        f.write(f"*MATERIAL, NAME=M\n*ELASTIC\n{E!r}, {NU!r}\n")
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=M\n1.0\n")
        f.write("*BOUNDARY\nNBOT, 1, 2, 0.0\n")
        f.write("*STEP\n*STATIC\n*DLOAD\n")
        for eid, face in dload:
            f.write(f"{eid}, P{face}, {P!r}\n")
        f.write("*NODE PRINT, NSET=NALL\nU\n")
        f.write("*NODE PRINT, NSET=NBOT, TOTALS=ONLY\nRF\n")
        f.write("*EL FILE\nS\n")
        f.write("*END STEP\n")
    return top_center[0]


# ---- step 3: run ccx, read .dat and .frd ------------------------------------------------
def solve(work, h):
    ids, xy, elems, nx, ny = mesh(h, work)
    tc = write_inp(os.path.join(work, "plate.inp"), ids, xy, elems, h)
    seconds = cc.run_ccx(work, "plate", f"h = {h}")
    u, (total,) = cc.parse_dat(os.path.join(work, "plate.dat"))
    st = cc.parse_frd_stress(os.path.join(work, "plate.frd"))
    # the centre line x = XC (an element edge when nx is even, mid-edge nodes only when odd)
    line = sorted((xy[k, 1], nid) for k, nid in enumerate(ids) if abs(xy[k, 0] - XC) < 1e-6 * h)
    cl = np.array([(y, *u[nid], *st[nid]) for y, nid in line])   # y ux uy sxx syy szz sxy
    return dict(h=h, elements=len(elems), nodes=len(ids), uy=u[tc][1], seconds=seconds,
                reaction=total, centerline=cl, nx=nx)


def von_mises(sxx, syy, szz, sxy):
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3 * sxy ** 2)


# ---- step 4: run the meshes, check, write outputs ---------------------------------------
def main():
    a = cc.parse_args(__doc__, max_seconds=120.0)

    def report(h, r):
        fx, fy = r["reaction"]
        cl = r["centerline"]
        mid = np.abs(cl[:, 0] - H / 2) < 0.25 * H   # middle half of the height
        print(f"h = {h * 1e3:5g} mm: {r['elements']:6d} elements {r['nodes']:7d} nodes  "
              f"top-centre uy = {r['uy']:.7e} m  ccx {r['seconds']:6.1f} s  "
              f"reaction ({fx:.6e}, {fy:.9e}) N/m  centre-line syy in [{cl[mid, 4].min():.1f}, "
              f"{cl[mid, 4].max():.1f}] Pa over 0.25H..0.75H")

    results = cc.mesh_series(H_LIST, 6, a.max_seconds, lambda h: f"h = {h * 1e3:g} mm",
                             lambda h: cc.in_work_folder(f"perinom_fem_h{h * 1e3:g}mm_", a.keep, f"h_{h * 1e3:g}mm",
                                                         solve, h),
                             report)

    # sanity checks
    for r in results:
        fx, fy = r["reaction"]
        assert abs(fy - P * W) <= 1e-6 * P * W, f"vertical reaction {fy} != {P * W}"
        assert abs(fx) <= 1e-6 * P * W, f"horizontal reaction {fx}"
    fine = results[-1]
    cl = fine["centerline"]
    y, ux, uy, sxx, syy, szz, sxy = cl.T
    assert np.allclose(szz, NU * (sxx + syy), rtol=0, atol=1e-3 * P), "szz != nu (sxx + syy)"
    mid = np.abs(y - H / 2) < 0.25 * H
    assert np.allclose(syy[mid], -P, rtol=0.05), "syy far from the ends is not about -P"

    # mesh convergence: Richardson on the three finest meshes; its spread against the
    # previous three and against the theoretical order 2 lambda estimates its own error
    uys = [r["uy"] for r in results]
    p, lim = cc.richardson(*uys[-3:])
    p_prev, lim_prev = cc.richardson(*uys[-4:-1]) if len(uys) >= 4 else (np.nan, np.nan)
    lam = cc.corner_exponent(3 - 4 * NU)   # plane strain
    _, lim_theory = cc.richardson(*uys[-3:], p=2 * lam)
    err_fine = abs(lim - uys[-1])
    # the .dat prints 7 significant digits: half a unit of the last one, carried through the
    # extrapolation lim = (1 + c) f3 - c f2, c = 1/(2^p - 1), bounds what the data can resolve
    c = 1 / (2 ** p - 1)
    err_round = 0.5 * 10.0 ** (np.floor(np.log10(abs(uys[-1]))) - 6) * (1 + 2 * c)
    err_lim = np.nanmax([abs(lim - lim_prev), abs(lim - lim_theory), err_round])
    print(f"Richardson, three finest meshes: observed order {p:.3f}, "
          f"extrapolated top-centre uy = {lim:.7e} m")
    print(f"  previous three meshes: order {p_prev:.3f}, limit {lim_prev:.7e} m; with the corner "
          f"order 2 lambda = {2 * lam:.3f}: limit {lim_theory:.7e} m")
    print(f"  discretization error of the finest mesh ~ {err_fine:.2e} m ({err_fine / abs(lim):.1e} "
          f"relative); of the extrapolated value ~ {err_lim:.1e} m")
    print(f"  vs the expected {EXPECTED_TOP_UY:.4e} m: {100 * (lim / EXPECTED_TOP_UY - 1):+.3f}%")
    print(f"centre line, finest mesh: syy in [{syy[mid].min():.0f}, {syy[mid].max():.0f}] Pa over "
          f"0.25H..0.75H, max |szz - nu (sxx + syy)| = {np.abs(szz - NU * (sxx + syy)).max():.2g} Pa")

    os.makedirs(a.out, exist_ok=True)
    cc.write_csv(os.path.join(a.out, "uniaxial_compression_top_center.csv"),
                 "h_m,elements,nodes,top_center_uy_m,seconds",
                 [f"{cc.mesh_columns(r)},{r['uy']:.7e},{r['seconds']:.2f}" for r in results]
                 + [f"0,0,0,{lim:.7e},0"])   # h -> 0: Richardson extrapolation of the three finest
    cc.write_csv(os.path.join(a.out, "uniaxial_compression_centerline.csv"),
                 "y_m,ux_m,uy_m,von_mises_pa,sxx_pa,syy_pa,szz_pa,sxy_pa",
                 [f"{yy:.9g},{uxx:.7e},{uyy:.7e},{von_mises(a_, b_, c_, d_):.6e},"
                  f"{a_:.6e},{b_:.6e},{c_:.6e},{d_:.6e}" for yy, uxx, uyy, a_, b_, c_, d_ in cl])

    fig, (a1, a2, a3) = cc.figure(3)
    for r in results:
        c = r["centerline"]
        lab = f"h = {r['h'] * 1e3:g} mm"
        a1.plot(c[:, 0] * 1e3, c[:, 2] * 1e3, lw=1, label=lab)
        a2.plot(c[:, 0] * 1e3, von_mises(*c[:, 3:7].T) * 1e-3, lw=1, label=lab)
    a1.set(xlabel="y (mm)", ylabel="u_y (mm)", title="centre line x = 18 mm: u_y")
    a2.set(xlabel="y (mm)", ylabel="von Mises (kPa)", title="centre line: von Mises (with s_zz)")
    hs = np.array([r["h"] for r in results])
    a3.loglog(hs * 1e3, np.abs(np.array(uys) - lim) * 1e3, "o-", label="|u_y(h) - extrapolated|")
    a3.loglog(hs * 1e3, err_fine * 1e3 * (hs / hs[-1]) ** (2 * lam), "k--", lw=0.8,
              label=f"h^{2 * lam:.2f} (corner)")
    a3.set(xlabel="h (mm)", ylabel="error (mm)", title="top-centre u_y convergence")
    a3.set_xticks(hs * 1e3, [f"{v * 1e3:g}" for v in hs])
    a3.minorticks_off()
    cc.save_figure(fig, (a1, a2, a3), os.path.join(a.out, "uniaxial_compression_fem.png"))
    print("wrote", ", ".join(f"uniaxial_compression_{s}" for s in ("top_center.csv", "centerline.csv", "fem.png")),
          "in", a.out)


if __name__ == "__main__":
    main()
