#!/usr/bin/env python3
"""FEM reference for a thick-walled cylinder under internal pressure (Lame, plane strain), by CalculiX.

What is solved
  A long thick-walled cylinder, inner radius a = 0.01 m, outer radius b = 0.02 m, plane
  strain, thickness 1 m, linear elastic isotropic, E = 200e9 Pa, nu = 0.3, internal
  pressure p = 1e6 Pa on r = a, outer surface r = b free. By symmetry a quarter is solved:
  a <= r <= b, 0 <= theta <= 90 deg, with rollers ux = 0 on x = 0 and uy = 0 on y = 0.

  Closed form (Lame, plane strain; c = p a^2/(b^2 - a^2)):
    u_r(r)       = (1 + nu) c/E ((1 - 2 nu) r + b^2/r)
    sigma_r(r)   = c (1 - b^2/r^2),   sigma_r(a) = -p
    sigma_t(r)   = c (1 + b^2/r^2),   sigma_t(a) = p (b^2 + a^2)/(b^2 - a^2)
    sigma_z      = 2 nu c
  Here u_r(a) = 9.5333333e-08 m, u_r(b) = 6.0666667e-08 m, sigma_t(a) = 1.6666667e6 Pa.
  The FEM is mainly for the error-against-time table: every mesh's error against this, with
  its ccx wall time.

How
  A structured (Transfinite + Recombine) grid of 8-node serendipity quads made by gmsh
  (second order, incomplete; the mid-edge nodes on r = a and r = b lie on the circles):
  m elements through the wall (uniform) and n = 2 m around the quarter (about square
  elements; nodes on theta = 45 deg); refinement doubles m and n. Solved by CalculiX ccx with
  CPE8 elements (plane strain, full 3x3 integration); the pressure is a *DLOAD of 1e6 Pa on
  the element faces on r = a (consistent nodal loads, computed by ccx on the isoparametric
  face). Displacements and the total reactions of the rollers come from the .dat file
  (*NODE PRINT, 7 significant digits); stresses are the .frd nodal stresses (*EL FILE, S;
  ccx extrapolates the integration-point stresses to the nodes and averages the elements
  sharing a node; 6 significant digits). In polar components at a node at angle theta:
  sigma_r = sxx c^2 + syy s^2 + 2 sxy s c, sigma_t = sxx s^2 + syy c^2 - 2 sxy s c
  (c = cos theta, s = sin theta). sigma_t(a) is also given from the displacement, as for
  the plate with a hole: at r = a, sigma_r = -p, so in plane strain
  sigma_t = E/(1 - nu^2) eps_t + nu/(1 - nu) sigma_r with eps_t = u_r/a (u_theta = 0).

Outputs (in this folder; work files go to a temporary folder and are deleted)
  lame.csv        one row per mesh: h_m (radial element size (b - a)/m), elements, nodes,
                  ur_a_45_m (u_r at r = a, theta = 45 deg), ur_a_0_m (u_r = ux at (a, 0)),
                  st_a_45_nodal_pa (sigma_t at r = a, 45 deg, .frd nodal stress),
                  st_a_45_disp_pa (sigma_t at r = a, 45 deg, from u_r), err_ur_a_45,
                  err_ur_a_0, err_st_a_45_nodal, err_st_a_45_disp (relative errors against
                  the closed form), seconds (ccx wall time); then a row with h_m = 0 holding
                  the Richardson-extrapolated values (the finest value where the last
                  differences are not monotone or at the printed digits' round-off) and
                  their errors.
  lame_line.csv   r_m, ur_m, ur_exact_m, sr_pa, sr_exact_pa, st_pa, st_exact_pa, sz_pa,
                  sz_exact_pa at the nodes on theta = 45 deg, finest mesh.
  lame_fem.png    error against ccx time, and the line profiles.

Usage: python3 verification/fem/lame.py [--max-seconds S] [--keep DIR] [--out DIR]
Needs gmsh and CalculiX (Debian: apt-get install gmsh calculix-ccx), python3 with numpy
and matplotlib (Debian: python3-numpy python3-matplotlib). Runs single-threaded.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ccx_common as cc   # the shared helpers (it re-runs this under /usr/bin/python3 without numpy)
import numpy as np

# ---- problem data (SI) ------------------------------------------------------------------
A, B = 0.01, 0.02              # inner and outer radius, m
E, NU = 200e9, 0.3             # Pa, -
P = 1e6                        # internal pressure, Pa
M_LIST = [2, 4, 8, 16, 32, 64, 128]   # elements through the wall (n = 2 m around the quarter)
TOL = 1e-9                     # m, for finding nodes on the axes and circles


# ---- closed form (Lame, plane strain) ---------------------------------------------------
C_LAME = P * A ** 2 / (B ** 2 - A ** 2)


def ur_exact(r):
    return (1 + NU) * C_LAME / E * ((1 - 2 * NU) * r + B ** 2 / r)


def sr_exact(r):
    return C_LAME * (1 - B ** 2 / r ** 2)


def st_exact(r):
    return C_LAME * (1 + B ** 2 / r ** 2)


SZ_EXACT = 2 * NU * C_LAME
ST_A = P * (B ** 2 + A ** 2) / (B ** 2 - A ** 2)
assert abs(st_exact(A) / ST_A - 1) < 1e-15 and abs(sr_exact(A) / -P - 1) < 1e-15


# ---- step 1: mesh with gmsh -------------------------------------------------------------
GEO = """// quarter of a thick-walled cylinder, structured 8-node quads
Point(1) = {{0, 0, 0}};
Point(2) = {{{A!r}, 0, 0}}; Point(3) = {{{B!r}, 0, 0}};
Point(4) = {{0, {B!r}, 0}}; Point(5) = {{0, {A!r}, 0}};
Line(1) = {{2, 3}}; Circle(2) = {{3, 1, 4}}; Line(3) = {{4, 5}}; Circle(4) = {{5, 1, 2}};
Curve Loop(1) = {{1, 2, 3, 4}}; Plane Surface(1) = {{1}};
Transfinite Curve{{1, 3}} = {m1}; Transfinite Curve{{2, 4}} = {n1};
Transfinite Surface{{1}}; Recombine Surface{{1}};
Physical Surface("wall") = {{1}};
Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
"""


def mesh(m, work):
    """Returns node ids, coordinates (n x 2) and 8-node elements (k x 8, node ids, ccx order)."""
    n = 2 * m
    ids, xy, elems = cc.quad8_mesh(cc.gmsh(GEO.format(A=A, B=B, m1=m + 1, n1=n + 1), work, "wall"))
    assert len(elems) == n * m, (len(elems), n, m)
    # snap the nodes on the axes exactly (gmsh leaves ~1e-18 m of round-off)
    for col in (0, 1):
        xy[np.abs(xy[:, col]) < TOL, col] = 0.0
    r = np.hypot(xy[:, 0], xy[:, 1])
    assert r.min() > A * (1 - 1e-12) and r.max() < B * (1 + 1e-12)
    return ids, xy, elems


# ---- step 2: CalculiX input -------------------------------------------------------------
def write_inp(path, ids, xy, elems, out_nodes):
    r = np.hypot(xy[:, 0], xy[:, 1])
    left = ids[np.abs(xy[:, 0]) < TOL]
    bottom = ids[np.abs(xy[:, 1]) < TOL]
    dload = cc.faces_on(ids, elems, np.abs(r - A) < TOL)   # the faces on r = a
    with open(path, "w") as f:
        cc.write_mesh(f, "quarter of a thick-walled cylinder, plane strain, CPE8", ids, xy, elems, "CPE8")
        cc.write_nset(f, "NLEFT", left)
        cc.write_nset(f, "NBOT", bottom)
        cc.write_nset(f, "NOUT", out_nodes)
        f.write(f"*MATERIAL, NAME=M\n*ELASTIC\n{cc.num(E)}, {cc.num(NU)}\n")
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=M\n1.0\n")
        f.write("*BOUNDARY\nNLEFT, 1, 1, 0.0\nNBOT, 2, 2, 0.0\n")
        f.write("*STEP\n*STATIC\n*DLOAD\n")
        for eid, face in dload:
            f.write(f"{eid}, P{face}, {cc.num(P)}\n")
        f.write("*NODE PRINT, NSET=NOUT\nU\n")
        f.write("*NODE PRINT, NSET=NLEFT, TOTALS=ONLY\nRF\n")
        f.write("*NODE PRINT, NSET=NBOT, TOTALS=ONLY\nRF\n")
        f.write("*EL FILE\nS\n")
        f.write("*END STEP\n")
    return len(dload)


# ---- step 3: run ccx, read .dat and .frd ------------------------------------------------
def pressure_load(ids, xy, elems, node):
    """The consistent nodal force (fx, fy) of the internal pressure at a node on r = a, as ccx
    computes it on the isoparametric quadratic faces: p times the integral of N_i over the
    face of the normal pointing away from the axis (3-point Gauss, exact for the quadratic
    face). At the corners (a, 0) and (0, a) it has a tangential part (the face is only nearly
    a circle), which ccx counts in the roller's RF there."""
    pos = cc.node_index(ids)
    r = np.hypot(xy[:, 0], xy[:, 1])
    g, w = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]), np.array([5, 8, 5]) / 9
    f = np.zeros(2)
    for e in elems:
        for k in range(4):
            c0, c1, mid = e[k], e[(k + 1) % 4], e[k + 4]
            if node not in (c0, c1, mid) or abs(r[pos[c0]] - A) > TOL or abs(r[pos[c1]] - A) > TOL:
                continue
            x0, xm, x1 = xy[pos[c0]], xy[pos[mid]], xy[pos[c1]]
            for xi, wt in zip(g, w):
                shape = {c0: xi * (xi - 1) / 2, mid: 1 - xi * xi, c1: xi * (xi + 1) / 2}
                t = x0 * (xi - 0.5) + xm * (-2 * xi) + x1 * (xi + 0.5)
                X = x0 * shape[c0] + xm * shape[mid] + x1 * shape[c1]
                nrm = np.array([t[1], -t[0]])
                if nrm @ X < 0:
                    nrm = -nrm
                f += P * wt * shape[node] * nrm
    return f


def polar(x, y, ux, uy, sxx, syy, sxy):
    """u_r, sigma_r, sigma_t at the point (x, y)."""
    t = np.arctan2(y, x)
    c, s = np.cos(t), np.sin(t)
    return (ux * c + uy * s, sxx * c * c + syy * s * s + 2 * sxy * s * c,
            sxx * s * s + syy * c * c - 2 * sxy * s * c)


def solve(work, m):
    ids, xy, elems = mesh(m, work)
    pos = cc.node_index(ids)
    ang = np.arctan2(xy[:, 1], xy[:, 0])
    ray = ids[np.abs(ang - np.pi / 4) < 1e-6]   # theta = 45 deg (gmsh places the arc nodes to ~2e-9 rad)
    a0 = ids[(np.abs(xy[:, 1]) < TOL) & (np.abs(xy[:, 0] - A) < TOL)]
    a90 = ids[(np.abs(xy[:, 0]) < TOL) & (np.abs(xy[:, 1] - A) < TOL)]
    assert len(ray) == 2 * m + 1 and len(a0) == 1
    nload = write_inp(os.path.join(work, "wall.inp"), ids, xy, elems, sorted(set(ray) | set(a0)))
    assert nload == 2 * m
    seconds = cc.run_ccx(work, "wall", f"m = {m}")
    u, totals = cc.parse_dat(os.path.join(work, "wall.dat"))
    st = cc.parse_frd_stress(os.path.join(work, "wall.frd"))
    rows = []
    for nid in ray:
        x, y = xy[pos[nid]]
        sxx, syy, szz, sxy = st[nid]
        ur, sr, sth = polar(x, y, *u[nid], sxx, syy, sxy)
        rows.append((np.hypot(x, y), ur, sr, sth, szz))
    line = np.array(sorted(rows))                     # r ur sr st sz
    assert abs(line[0, 0] - A) < TOL
    ur_a = line[0, 1]
    st_disp = E / (1 - NU ** 2) * ur_a / A + NU / (1 - NU) * (-P)
    return dict(m=m, h=(B - A) / m, elements=len(elems), nodes=len(ids), seconds=seconds,
                reactions=totals, corner_loads=(pressure_load(ids, xy, elems, a90[0])[0],
                                                pressure_load(ids, xy, elems, a0[0])[1]), line=line, ur_a_45=ur_a, ur_a_0=u[a0[0]][0],
                st_a_45_nodal=line[0, 3], st_a_45_disp=st_disp)


KEYS = ["ur_a_45", "ur_a_0", "st_a_45_nodal", "st_a_45_disp"]
EXACT = {"ur_a_45": ur_exact(A), "ur_a_0": ur_exact(A), "st_a_45_nodal": ST_A, "st_a_45_disp": ST_A}
CSV_NAMES = {"ur_a_45": "ur_a_45_m", "ur_a_0": "ur_a_0_m", "st_a_45_nodal": "st_a_45_nodal_pa",
             "st_a_45_disp": "st_a_45_disp_pa"}


# ---- step 4: run the meshes, check, write outputs ---------------------------------------
def main():
    a = cc.parse_args(__doc__, max_seconds=120.0)
    print(f"closed form: u_r(a) = {ur_exact(A):.7e} m, u_r(b) = {ur_exact(B):.7e} m, "
          f"sigma_t(a) = {ST_A:.7e} Pa, sigma_r(a) = {-P:.7e} Pa, sigma_z = {SZ_EXACT:.7e} Pa")

    def report(m, r):
        (lx, ly), (bx, by) = r["reactions"]
        fx90, fy0 = r["corner_loads"]
        print(f"m = {m:3d} (h = {r['h'] * 1e3:.4f} mm): {r['elements']:6d} elements {r['nodes']:7d} nodes  "
              f"ccx {r['seconds']:6.2f} s  reactions: x on x = 0 {lx - fx90:.7e}, y on y = 0 "
              f"{by - fy0:.7e} N/m (RF totals {lx:.7e}, {by:.7e})", flush=True)
        print("   " + "  ".join(f"{k} {r[k]:.7e} ({r[k] / EXACT[k] - 1:+.1e})" for k in KEYS), flush=True)

    results = cc.mesh_series(M_LIST, 6, a.max_seconds, lambda m: f"m = {m}",
                             lambda m: cc.in_work_folder(f"perinom_fem_lame_m{m}_", a.keep, f"m_{m}", solve, m),
                             report)

    # sanity checks: equilibrium and the line profiles. Each roller holds the pressure
    # resultant on the quarter back, -p a; ccx's RF total of the roller x = 0 also counts the
    # applied force at its node (0, a) (RF is the internal force K u at every node), whose x
    # part, tangential, is about 1.2 N on the coarsest mesh and falls like h^4; it is removed.
    for r in results:
        (lx, ly), (bx, by) = r["reactions"]
        fx90, fy0 = r["corner_loads"]
        assert abs(lx - fx90 + P * A) <= 1e-6 * P * A, f"reaction on x = 0: {lx - fx90} != {-P * A}"
        assert abs(by - fy0 + P * A) <= 1e-6 * P * A, f"reaction on y = 0: {by - fy0} != {-P * A}"
    fine = results[-1]
    rr, ur, sr, sth, sz = fine["line"].T
    err_u = np.abs(ur / ur_exact(rr) - 1).max()
    err_s = max(np.abs(sr - sr_exact(rr)).max(), np.abs(sth - st_exact(rr)).max(),
                np.abs(sz - SZ_EXACT).max()) / ST_A
    print(f"theta = 45 deg, finest mesh: max |u_r/exact - 1| = {err_u:.1e}, "
          f"max |stress - exact| / sigma_t(a) = {err_s:.1e}")
    assert err_u < 1e-6 and err_s < 2e-4

    out = {}
    for key in KEYS:
        f = [r[key] for r in results]
        p, lim = cc.richardson_monotone(*f[-3:])
        out[key] = lim
        print(f"{key}: errors {', '.join(f'{v / EXACT[key] - 1:+.2e}' for v in f)}; extrapolated "
              f"{lim:.7e} ({lim / EXACT[key] - 1:+.1e}, order {p:.2f}); exact {EXACT[key]:.7e}")

    os.makedirs(a.out, exist_ok=True)
    cc.write_csv(os.path.join(a.out, "lame.csv"),
                 "h_m,elements,nodes," + ",".join(CSV_NAMES[k] for k in KEYS) + ","
                 + ",".join("err_" + k for k in KEYS) + ",seconds",
                 [cc.mesh_columns(r) + "," + ",".join(f"{r[k]:.7e}" for k in KEYS)
                  + "," + ",".join(f"{r[k] / EXACT[k] - 1:.3e}" for k in KEYS) + f",{r['seconds']:.2f}"
                  for r in results]
                 + ["0,0,0," + ",".join(f"{out[k]:.7e}" for k in KEYS) + ","
                    + ",".join(f"{out[k] / EXACT[k] - 1:.3e}" for k in KEYS) + ",0"])
    cc.write_csv(os.path.join(a.out, "lame_line.csv"),
                 "r_m,ur_m,ur_exact_m,sr_pa,sr_exact_pa,st_pa,st_exact_pa,sz_pa,sz_exact_pa",
                 [f"{r_:.9g},{u_:.7e},{ur_exact(r_):.7e},{s1:.6e},{sr_exact(r_):.6e},"
                  f"{s2:.6e},{st_exact(r_):.6e},{s3:.6e},{SZ_EXACT:.6e}" for r_, u_, s1, s2, s3 in fine["line"]])

    fig, (a1, a2) = cc.figure(2)
    secs = np.array([max(r["seconds"], 1e-3) for r in results])
    for key, lab in (("ur_a_45", "u_r(a), 45 deg"), ("ur_a_0", "u_r(a), 0 deg"),
                     ("st_a_45_nodal", "sigma_t(a), nodal"), ("st_a_45_disp", "sigma_t(a), from u_r")):
        err = np.abs(np.array([r[key] for r in results]) / EXACT[key] - 1)
        ok = err > 0
        a1.loglog(secs[ok], err[ok], "o-", label=lab)
    a1.set(xlabel="ccx wall time (s)", ylabel="|relative error|", title="error against time")
    rs = np.linspace(A, B, 200)
    a2.plot(rs * 1e3, sr_exact(rs) / 1e6, "k-", lw=0.8, label="closed form")
    a2.plot(rs * 1e3, st_exact(rs) / 1e6, "k-", lw=0.8)
    for r, mk in zip(results[:3:2], ("o", "x")):
        c = r["line"]
        a2.plot(c[:, 0] * 1e3, c[:, 2] / 1e6, mk, ms=4, color="C0", label=f"sigma_r, m = {r['m']}")
        a2.plot(c[:, 0] * 1e3, c[:, 3] / 1e6, mk, ms=4, color="C1", label=f"sigma_t, m = {r['m']}")
    a2.set(xlabel="r (mm)", ylabel="stress (MPa)", title="theta = 45 deg")
    cc.save_figure(fig, (a1, a2), os.path.join(a.out, "lame_fem.png"))
    print("wrote lame.csv, lame_line.csv, lame_fem.png in", a.out)


if __name__ == "__main__":
    main()
