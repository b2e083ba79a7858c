#!/usr/bin/env python3
"""FEM reference for a square plate with a central circular hole in tension (plane strain), by CalculiX.

What is solved
  A square plate 0.1 m x 0.1 m with a central hole of radius R = 0.005 m, plane strain,
  thickness 1 m, linear elastic isotropic, E = 200e9 Pa, nu = 0.3, pulled by the uniform
  traction 1e6 Pa on its two edges normal to x; the edges normal to y and the hole are free.
  By symmetry a quarter is solved: 0 <= x <= 0.05, 0 <= y <= 0.05 minus the disc
  x^2 + y^2 < R^2, with rollers ux = 0 on x = 0 and uy = 0 on y = 0, the traction (1e6, 0) Pa
  on x = 0.05, and y = 0.05 and the hole free.

How
  The quarter is cut along the diagonal into two four-sided patches, each meshed by gmsh as
  a structured (Transfinite + Recombine) grid of 8-node serendipity quads (second order,
  incomplete; the mid-edge nodes on the hole lie on the circle): n elements along each
  45-degree arc of the hole and along each outer edge, m = 2 n elements from the hole
  outwards, sized in geometric progression (ratio q) so that the elements at the hole are
  about square. Refinement doubles n and m and takes the square root of q, so every mesh
  contains the nodes of the previous one (nested meshes). Solved by CalculiX ccx with CPE8
  elements (plane strain, full 3x3 integration); the traction is a *DLOAD pressure of -1e6 Pa
  on the element faces on x = 0.05 (consistent nodal loads, computed by ccx). Displacements
  and the total reaction of the roller x = 0 come from the .dat file (*NODE PRINT, 7
  significant digits); stresses are the .frd nodal stresses (*EL FILE, S; ccx extrapolates
  the integration-point stresses of each element to its nodes and averages the elements
  sharing a node; 6 significant digits).

  The hole-edge stresses are given three ways:
  - disp (the reference): from the displacements of the hole's nodes. At the free hole edge
    sigma_rr = 0, so in plane strain the hoop stress is E/(1 - nu^2) eps_tt, and eps_tt is
    the tangential derivative of the tangential displacement: d ux/dx at (0, R), d uy/dy at
    (R, 0). It is the slope at the symmetry line of an odd cubic a1 phi + a3 phi^3 (phi the
    angle from the symmetry line; ux, resp. uy, is odd in phi) fitted by least squares to the
    first 4 nodes of the hole (2 elements), divided by R. Nodal displacements of quadratic
    elements are far more accurate than nodal stresses; this estimate is converged to about
    1e-7 on n >= 64 and does not depend on the fit (1 or 3 terms agree to 1e-6);
  - nodal: the .frd stress at the node (0, R) (sigma_xx) or (R, 0) (sigma_yy); that node is a
    corner of a single element, so its value is one element's extrapolation;
  - line: a least-squares cubic in the distance from the hole through the nodal stresses of
    the first 3 elements along the symmetry line (x = 0 for sigma_xx, y = 0 for sigma_yy;
    the 6 nodes after the hole-edge node, which is left out), evaluated at the hole.
  The nodal and line values converge to the disp value within a few 1e-5 on the finest mesh,
  but not monotonically: the nodal stresses zigzag between the mid-edge nodes (one element)
  and the corner nodes (two elements), so their Richardson extrapolation is unreliable at
  that level.

Outputs (in this folder; work files go to a temporary folder and are deleted)
  plate_hole.csv        one row per mesh: h_m (element size along the hole, R (pi/4)/n),
                        elements, nodes, ux_x05_y0_m (ux at (0.05, 0)), ux_x05_y05_m (ux at
                        (0.05, 0.05)), uy_x0_y05_m (uy at (0, 0.05)), sxx_hole_nodal_pa,
                        sxx_hole_line_pa, sxx_hole_disp_pa (sigma_xx at (0, R)),
                        syy_hole_nodal_pa, syy_hole_line_pa, syy_hole_disp_pa (sigma_yy at
                        (R, 0)), seconds (ccx wall time); a last row with h_m = 0 holds the
                        Richardson-extrapolated values (the finest value where the last
                        differences are not monotone or at the printed digits' round-off).
  plate_hole_line.csv   y_m, sxx_pa, syy_pa, sxy_pa, szz_pa, ux_m, uy_m at the corner nodes on
                        x = 0 from y = R to y = 0.05, finest mesh.
  plate_hole_fem.png    sigma_xx along x = 0 and the convergence of the hole-edge stress.

Usage: python3 verification/fem/plate_hole.py [--max-seconds S] [--keep DIR] [--out DIR]
Needs gmsh and CalculiX (Debian: apt-get install gmsh calculix-ccx), python3 with numpy
and matplotlib (Debian: python3-numpy python3-matplotlib). Runs single-threaded.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ccx_common as cc   # the shared helpers (it re-runs this under /usr/bin/python3 without numpy)
import numpy as np

# ---- problem data (SI) ------------------------------------------------------------------
W = 0.05                       # half width of the plate, m
R = 0.005                      # hole radius, m
E, NU = 200e9, 0.3             # Pa, -
S = 1e6                        # applied traction, Pa
N_LIST = [4, 8, 16, 32, 64, 128]   # elements per 45-degree arc (m = 2 n from the hole outwards)
Q0 = 1.48                      # radial growth ratio of the coarsest mesh (n = 4, m = 8)
FIT_NODES = 6                  # nodes (after the hole-edge node) in the line fit: 3 elements
TOL = 1e-9                     # m, for finding nodes on the straight edges


# ---- step 1: mesh with gmsh -------------------------------------------------------------
GEO = """// quarter plate with a hole, two structured patches of 8-node quads
Point(1) = {{0, 0, 0}};
Point(2) = {{{R!r}, 0, 0}}; Point(3) = {{{Rd!r}, {Rd!r}, 0}}; Point(4) = {{0, {R!r}, 0}};
Point(5) = {{{W!r}, 0, 0}}; Point(6) = {{{W!r}, {W!r}, 0}}; Point(7) = {{0, {W!r}, 0}};
Circle(1) = {{2, 1, 3}}; Circle(2) = {{3, 1, 4}};
Line(3) = {{2, 5}}; Line(4) = {{5, 6}}; Line(5) = {{3, 6}}; Line(6) = {{6, 7}}; Line(7) = {{4, 7}};
Curve Loop(1) = {{3, 4, -5, -1}}; Plane Surface(1) = {{1}};
Curve Loop(2) = {{5, 6, -7, -2}}; Plane Surface(2) = {{2}};
Transfinite Curve{{1, 2, 4, 6}} = {n1};
Transfinite Curve{{3, 5, 7}} = {m1} Using Progression {q!r};
Transfinite Surface{{1}}; Transfinite Surface{{2}}; Recombine Surface{{1, 2}};
Physical Surface("plate") = {{1, 2}};
Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
"""


def mesh(n, work):
    """Returns node ids, coordinates (n x 2) and 8-node elements (m x 8, node ids, ccx order)."""
    k = round(np.log2(n / N_LIST[0]))
    m = 2 * n
    q = Q0 ** (1 / 2 ** k)
    ids, xy, elems = cc.quad8_mesh(cc.gmsh(GEO.format(R=R, Rd=R / np.sqrt(2), W=W, n1=n + 1, m1=m + 1, q=q),
                                           work, "plate"))
    assert len(elems) == 2 * n * m, (len(elems), n, m)
    # snap the straight edges exactly (gmsh leaves ~1e-17 m of round-off)
    for col, val in ((0, 0.0), (1, 0.0), (0, W), (1, W)):
        on = np.abs(xy[:, col] - val) < TOL
        xy[on, col] = val
    r = np.hypot(xy[:, 0], xy[:, 1])
    assert r.min() > R * (1 - 1e-12)
    return ids, xy, elems, m


# ---- step 2: CalculiX input -------------------------------------------------------------
def node_at(ids, xy, x, y):
    k = np.nonzero((np.abs(xy[:, 0] - x) < TOL) & (np.abs(xy[:, 1] - y) < TOL))[0]
    assert len(k) == 1, (x, y, k)
    return ids[k[0]]


def write_inp(path, ids, xy, elems):
    left = ids[np.abs(xy[:, 0]) < TOL]
    bottom = ids[np.abs(xy[:, 1]) < TOL]
    points = [node_at(ids, xy, W, 0.0), node_at(ids, xy, W, W), node_at(ids, xy, 0.0, W)]
    hole = ids[np.abs(np.hypot(xy[:, 0], xy[:, 1]) - R) < 1e-9 * R]
    dload = cc.faces_on(ids, elems, np.abs(xy[:, 0] - W) < TOL)   # the faces on x = W
    with open(path, "w") as f:
        cc.write_mesh(f, "quarter plate with a hole, plane strain, CPE8", ids, xy, elems, "CPE8")
        for name, nodes in (("NLEFT", left), ("NBOT", bottom), ("NPTS", points), ("NHOLE", hole)):
            cc.write_nset(f, name, nodes)
        cc.write_rollers_in_tension(f, E, NU, dload, S)
        f.write("*NODE PRINT, NSET=NLEFT\nU\n")
        f.write("*NODE PRINT, NSET=NBOT\nU\n")
        f.write("*NODE PRINT, NSET=NPTS\nU\n")
        f.write("*NODE PRINT, NSET=NHOLE\nU\n")
        f.write("*NODE PRINT, NSET=NLEFT, TOTALS=ONLY\nRF\n")
        f.write("*NODE PRINT, NSET=NBOT, TOTALS=ONLY\nRF\n")
        f.write("*EL FILE\nS\n")
        f.write("*END STEP\n")
    return len(dload)


# ---- step 3: run ccx, read .dat and .frd ------------------------------------------------
def line_fit(d, f):
    """Least-squares cubic through the values f at distances d from the hole (d > 0, the
    first FIT_NODES nodes), evaluated at d = 0."""
    d, f = np.asarray(d[:FIT_NODES]), np.asarray(f[:FIT_NODES])
    scale = d[-1]
    c = np.polyfit(d / scale, f, 3)
    return np.polyval(c, 0.0)


def hoop_fit(phi, u, k):
    """Slope at phi = 0 of an odd polynomial a1 phi + a3 phi^3 + ... (k terms) fitted by least
    squares to u at the angles phi (the first 2 k nodes)."""
    phi, u = np.asarray(phi[:2 * k]), np.asarray(u[:2 * k])
    A = np.array([phi ** (2 * j + 1) for j in range(k)]).T
    return np.linalg.lstsq(A, u, rcond=None)[0][0]


def solve(work, n):
    ids, xy, elems, m = mesh(n, work)
    nload = write_inp(os.path.join(work, "plate.inp"), ids, xy, elems)
    assert nload == n
    seconds = cc.run_ccx(work, "plate", f"n = {n}")
    u, totals = cc.parse_dat(os.path.join(work, "plate.dat"))
    st = cc.parse_frd_stress(os.path.join(work, "plate.frd"))
    pos = cc.node_index(ids)
    # symmetry line x = 0: nodes from the hole (0, R) up to (0, W); the corner nodes are the
    # even ones (n + 1 counted from the hole: 0, 2, 4, ...)
    left = sorted((xy[pos[nid], 1], nid) for nid in ids if abs(xy[pos[nid], 0]) < TOL)
    assert len(left) == 2 * m + 1 and abs(left[0][0] - R) < TOL
    line = np.array([(y, *st[nid], *u[nid]) for y, nid in left])   # y sxx syy szz sxy ux uy
    bottom = sorted((xy[pos[nid], 0], nid) for nid in ids if abs(xy[pos[nid], 1]) < TOL)
    assert len(bottom) == 2 * m + 1 and abs(bottom[0][0] - R) < TOL
    bline = np.array([(x, *st[nid], *u[nid]) for x, nid in bottom])  # x sxx syy szz sxy ux uy
    res = dict(n=n, h=R * np.pi / 4 / n, elements=len(elems), nodes=len(ids), seconds=seconds,
               reactions=totals, line=line, bline=bline)
    res["ux_x05_y0"] = u[node_at(ids, xy, W, 0.0)][0]
    res["ux_x05_y05"] = u[node_at(ids, xy, W, W)][0]
    res["uy_x0_y05"] = u[node_at(ids, xy, 0.0, W)][1]
    res["sxx_nodal"] = line[0, 1]
    res["sxx_line"] = line_fit(line[1:, 0] - R, line[1:, 1])
    res["syy_nodal"] = bline[0, 2]
    res["syy_line"] = line_fit(bline[1:, 0] - R, bline[1:, 2])
    # hoop stress from the displacements of the hole: at a free edge (plane strain)
    # sigma_tt = E/(1 - nu^2) eps_tt; at (0, R) eps_tt = d ux/dx along the hole, at (R, 0) d uy/dy
    hole = [(np.arctan2(xy[pos[nid], 1], xy[pos[nid], 0]), nid) for nid in ids
            if abs(np.hypot(*xy[pos[nid]]) - R) < 1e-9 * R]
    top = sorted((np.pi / 2 - t, u[nid][0]) for t, nid in hole)[1:]   # phi = 90 deg - theta > 0
    bot = sorted((t, u[nid][1]) for t, nid in hole)[1:]
    for k in (1, 2, 3):
        # x = R sin(phi) near the top: d ux/dx = (d ux/d phi)/R at phi = 0; k = 2 (an odd cubic
        # through the first 4 nodes, 2 elements) is the one reported, k = 1 and 3 the check
        key = "disp" if k == 2 else f"disp{k}"
        res[f"sxx_{key}"] = E / (1 - NU ** 2) * hoop_fit(*zip(*top), k) / R
        res[f"syy_{key}"] = E / (1 - NU ** 2) * hoop_fit(*zip(*bot), k) / R
    return res


KEYS = ["ux_x05_y0", "ux_x05_y05", "uy_x0_y05", "sxx_nodal", "sxx_line", "sxx_disp",
        "syy_nodal", "syy_line", "syy_disp"]
UNITS = {"ux_x05_y0": "m", "ux_x05_y05": "m", "uy_x0_y05": "m"}
CSV_NAMES = {"ux_x05_y0": "ux_x05_y0_m", "ux_x05_y05": "ux_x05_y05_m", "uy_x0_y05": "uy_x0_y05_m",
             "sxx_nodal": "sxx_hole_nodal_pa", "sxx_line": "sxx_hole_line_pa", "sxx_disp": "sxx_hole_disp_pa",
             "syy_nodal": "syy_hole_nodal_pa", "syy_line": "syy_hole_line_pa", "syy_disp": "syy_hole_disp_pa"}


# ---- step 4: run the meshes, check, write outputs ---------------------------------------
def main():
    a = cc.parse_args(__doc__, max_seconds=150.0)

    def report(n, r):
        (lx, ly), (bx, by) = r["reactions"]
        print(f"n = {n:3d} (h at the hole {r['h'] * 1e3:.4f} mm): {r['elements']:6d} elements "
              f"{r['nodes']:7d} nodes  ccx {r['seconds']:6.1f} s  reactions: x on x = 0 {lx:.7e}, "
              f"y on y = 0 {by:.1e} N/m; nodal syy at (0, R) (zero in the limit) {r['line'][0, 2]:.1f} Pa",
              flush=True)
        print("   " + "  ".join(f"{k} {r[k]:.7e}" for k in KEYS + ["sxx_disp1", "sxx_disp3"]), flush=True)

    results = cc.mesh_series(N_LIST, 6, a.max_seconds, lambda n: f"n = {n}",
                             lambda n: cc.in_work_folder(f"perinom_fem_hole_n{n}_", a.keep, f"n_{n}", solve, n),
                             report)

    # sanity checks: equilibrium (the roller x = 0 takes the whole load, the roller y = 0
    # nothing in total), plane strain, the far field
    for r in results:
        (lx, ly), (bx, by) = r["reactions"]
        assert abs(lx + S * W) <= 1e-6 * S * W, f"reaction on x = 0: {lx} != {-S * W}"
        assert abs(by) <= 1e-6 * S * W, f"total reaction on y = 0: {by}"
        ln = r["line"]
        assert np.allclose(ln[:, 3], NU * (ln[:, 1] + ln[:, 2]), rtol=0, atol=2e-5 * 3 * S)
    fine = results[-1]
    y, sxx, syy, szz, sxy, ux, uy = fine["line"].T
    assert np.abs(ux).max() < 1e-12 * np.abs(uy).max() + 1e-18, "ux on the roller x = 0"
    assert abs(sxx[-1] / S - 1) < 0.05, "sigma_xx at (0, W) is not about S"
    # the hole-edge stress from the displacements does not depend on the fit (k = 1, 2, 3 terms)
    for v in ("sxx", "syy"):
        for k in (1, 3):
            assert abs(fine[f"{v}_disp{k}"] / fine[f"{v}_disp"] - 1) < 3e-5, (v, k)

    out = {}
    for key in KEYS:
        f = [r[key] for r in results]
        p, lim = cc.richardson_monotone(*f[-3:])
        p_prev, lim_prev = cc.richardson_monotone(*f[-4:-1]) if len(f) >= 4 else (np.nan, np.nan)
        if not np.isfinite(lim):   # no monotone convergence left (e.g. round-off): the finest value
            lim = f[-1]
        out[key] = (p, lim, p_prev, lim_prev, f)
        u = UNITS.get(key, "Pa")
        print(f"{key}: differences {', '.join(f'{d:.3e}' for d in np.diff(f))} {u}")
        print(f"  order {p:.3f} (previous three {p_prev:.3f}), extrapolated {lim:.7e} {u} (previous "
              f"three {lim_prev:.7e}); finest - extrapolated {(f[-1] - lim) / abs(lim):.1e} relative; "
              f"finest two differ by {abs(f[-1] - f[-2]) / abs(lim):.1e} relative")
    print("stress concentration sigma_xx(0, R)/S: " + ", ".join(
        f"{k[4:]} {out[k][1] / S:.6f}" for k in ("sxx_disp", "sxx_nodal", "sxx_line")) +
        " (Kirsch, infinite plate: 3); sigma_yy(R, 0)/S: " + ", ".join(
        f"{k[4:]} {out[k][1] / S:.6f}" for k in ("syy_disp", "syy_nodal", "syy_line")) + " (Kirsch: -1)")

    os.makedirs(a.out, exist_ok=True)
    cc.write_csv(os.path.join(a.out, "plate_hole.csv"),
                 "h_m,elements,nodes," + ",".join(CSV_NAMES[k] for k in KEYS) + ",seconds",
                 [cc.mesh_columns(r) + "," + ",".join(f"{r[k]:.7e}" for k in KEYS) + f",{r['seconds']:.2f}"
                  for r in results]
                 + ["0,0,0," + ",".join(f"{out[k][1]:.7e}" for k in KEYS) + ",0"])   # h -> 0: Richardson
    cc.write_csv(os.path.join(a.out, "plate_hole_line.csv"), "y_m,sxx_pa,syy_pa,sxy_pa,szz_pa,ux_m,uy_m",
                 [f"{yy:.9g},{a_:.6e},{b_:.6e},{d_:.6e},{c_:.6e},{uxx:.7e},{uyy:.7e}"
                  for yy, a_, b_, c_, d_, uxx, uyy in fine["line"][::2]])   # the corner nodes

    fig, (a1, a2) = cc.figure(2)
    yy = np.linspace(R, W, 400)
    a1.plot(yy * 1e3, (1 + R ** 2 / (2 * yy ** 2) + 3 * R ** 4 / (2 * yy ** 4)), "k--", lw=0.8,
            label="Kirsch (infinite plate)")
    for r in results:
        ln = r["line"]
        a1.plot(ln[:, 0] * 1e3, ln[:, 1] / S, lw=1, label=f"n = {r['n']}")
    a1.set(xlabel="y (mm)", ylabel="sigma_xx / S", title="x = 0: sigma_xx", xscale="log")
    hs = np.array([r["h"] for r in results])
    for key in ("sxx_disp", "sxx_nodal", "sxx_line", "syy_disp", "syy_nodal", "syy_line"):
        f = np.array(out[key][4])
        err = np.abs(f - out["sxx_disp" if key[:3] == "sxx" else "syy_disp"][1]) / abs(out[key][1])
        a2.loglog(hs[err > 0] * 1e3, err[err > 0], "o-", label=key)
    a2.set(xlabel="h at the hole (mm)", ylabel="relative difference from extrapolated disp",
           title="hole-edge stress convergence")
    cc.save_figure(fig, (a1, a2), os.path.join(a.out, "plate_hole_fem.png"))
    print("wrote plate_hole.csv, plate_hole_line.csv, plate_hole_fem.png in", a.out)


if __name__ == "__main__":
    main()
