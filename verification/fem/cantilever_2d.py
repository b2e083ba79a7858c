#!/usr/bin/env python3
"""FEM reference for a 2-D (plane stress) cantilever under a tip shear load, by CalculiX.

What is solved
  A rectangle 0 <= x <= 0.1, 0 <= y <= 0.01 (m), plane stress, thickness 1 m, linear
  elastic isotropic, E = 200e9 Pa, nu = 0.3. The edge x = 0 is fully fixed (ux = uy = 0 at
  every node of it). The edge x = 0.1 carries the uniform traction (0, -1e6) Pa, a total
  force of -1e4 N (per metre of thickness). The edges y = 0 and y = 0.01 are free. The two
  corners of the fixed edge carry stress singularities; the tip displacement converges all
  the same.

How
  Structured meshes of square 8-node serendipity quads made by gmsh (Transfinite +
  Recombine, second order, incomplete), solved by CalculiX ccx with CPE8 elements (plane
  strain, full 3x3 integration) and the equivalent plane-strain constants
  E* = E (1 + 2 nu)/(1 + nu)^2, nu* = nu/(1 + nu): plane strain with (E*, nu*) has exactly the
  in-plane equations of plane stress with (E, nu), so the in-plane displacements and stresses
  are those of plane stress. Why not ccx's CPS8: ccx expands a plane-stress element into one
  layer of C3D20 elements of the given thickness with nothing holding the faces, i.e. it
  solves a 3-D slab; with a thickness of 1 m, 100 times the depth of this beam, that slab is
  close to plane strain in bending (the tip deflection comes out about 9% stiffer than plane
  stress). CPS8 gives plane stress only for a section thin against the in-plane sizes;
  the script checks that CPS8 with a thickness of 0.1 mm (and the loads scaled with it)
  agrees with the CPE8 (E*, nu*) model to 5e-5 on the meshes h = 2.5 and 1.25 mm, and prints
  the 1 m slab for information. The tip traction is applied as consistent nodal forces
  (*CLOAD), computed here: a uniform traction t on a straight 3-node element edge of
  length l gives t l/6 at each end and 2 t l/3 at the middle node. The script checks that
  they sum to -1e4 N and that the reaction of the fixed edge balances them. Displacements
  and reactions are read from the .dat file (*NODE PRINT, 7 significant digits).

Outputs (in this folder; work files go to a temporary folder and are deleted)
  cantilever_2d.csv             one row per mesh: h_m, elements, nodes, tip_center_uy_m,
                                tip_edge_mean_uy_m, seconds (ccx wall time); a last row with
                                h_m = 0 holds the Richardson-extrapolated values.
                                tip_center_uy_m: uy at the node (0.1, 0.005);
                                tip_edge_mean_uy_m: the mean of the interpolated uy over the
                                edge x = 0.1 (= the work-conjugate of the uniform load).
  cantilever_2d_centerline.csv  x_m, ux_m, uy_m at the nodes on y = 0.005 of the finest mesh,
                                every 0.3125 mm (every 4th node of that mesh).
  cantilever_2d_fem.png         the centre-line deflection and the convergence.

Usage: python3 verification/fem/cantilever_2d.py [--max-seconds S] [--keep DIR] [--out DIR]
Needs gmsh and CalculiX (Debian: apt-get install gmsh calculix-ccx), python3 with numpy
and matplotlib (Debian: python3-numpy python3-matplotlib). Runs single-threaded.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ccx_common as cc   # the shared helpers (it re-runs this under /usr/bin/python3 without numpy)
import numpy as np

# ---- problem data (SI) ------------------------------------------------------------------
L, H = 0.1, 0.01               # length (x) and depth (y), m; thickness 1 m
E, NU = 200e9, 0.3             # Pa, -
E_PS = E * (1 + 2 * NU) / (1 + NU) ** 2   # plane-strain constants that give plane stress (E, NU)
NU_PS = NU / (1 + NU)
TY = -1e6                      # tip traction, y component, Pa
PY = TY * H                    # total tip force, N per m of thickness (-1e4)
YC = H / 2                     # centre line
H_LIST = [5e-3, 2.5e-3, 1.25e-3, 0.625e-3, 0.3125e-3, 0.15625e-3]   # element sides, m (H/h: 2 ... 64)
LINE_STEP = 0.3125e-3          # spacing of the centre-line output, m

# beam theory, for comparison (plane stress: the beam modulus is E)
I_SEC = H ** 3 / 12                           # second moment of area per m of thickness, m^4/m
G = E / (2 * (1 + NU))
EB_TIP = PY * L ** 3 / (3 * E * I_SEC)        # Euler-Bernoulli
K_SHEAR = 5 / 6                               # rectangle, plane stress (Cowper's 2-D value)
TIMO_TIP = EB_TIP + PY * L / (K_SHEAR * G * H)


# ---- step 1: mesh with gmsh -------------------------------------------------------------
GEO = """// cantilever, structured 8-node quads
Point(1) = {{0, 0, 0}}; Point(2) = {{{L!r}, 0, 0}};
Point(3) = {{{L!r}, {H!r}, 0}}; Point(4) = {{0, {H!r}, 0}};
Line(1) = {{1, 2}}; Line(2) = {{2, 3}}; Line(3) = {{3, 4}}; Line(4) = {{4, 1}};
Curve Loop(1) = {{1, 2, 3, 4}}; Plane Surface(1) = {{1}};
Transfinite Curve{{1, 3}} = {nx1}; Transfinite Curve{{2, 4}} = {ny1};
Transfinite Surface{{1}}; Recombine Surface{{1}};
Physical Surface("beam") = {{1}};
Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
"""


def mesh(h, work):
    """Returns node ids, coordinates (n x 2) and 8-node elements (m x 8, node ids, ccx order)."""
    nx, ny = round(L / h), round(H / h)
    assert ny % 2 == 0, "an even count across, so that the centre line has corner nodes"
    ids, xy, elems = cc.quad8_mesh(cc.gmsh(GEO.format(L=L, H=H, nx1=nx + 1, ny1=ny + 1), work, "beam"))
    assert len(elems) == nx * ny, (len(elems), nx, ny)
    # gmsh leaves round-off of order 1e-14 m on the structured grid; snap to the exact
    # half-element grid (the mesh is structured, so every node lies on it)
    snapped = np.round(xy / (h / 2)) * (h / 2)
    assert np.abs(snapped - xy).max() < 1e-9
    return ids, snapped, elems


# ---- step 2: CalculiX input -------------------------------------------------------------
def tip_weights(ids, xy, elems, h):
    """Consistent nodal weights {node: w} of a unit uniform traction on the edge x = L
    (sum w = edge length): l/6 at the ends and 2 l/3 at the middle of each element edge."""
    tol = 1e-6 * h
    pos = cc.node_index(ids)
    w = {}
    nedge = 0
    for e in elems:
        for k in range(4):   # CPS8 edge k joins corners k, k+1 through mid-edge node k+4
            a, b, mid = e[k], e[(k + 1) % 4], e[k + 4]
            if abs(xy[pos[a], 0] - L) < tol and abs(xy[pos[b], 0] - L) < tol:
                nedge += 1
                l = abs(xy[pos[b], 1] - xy[pos[a], 1])
                for nid, c in ((a, l / 6), (b, l / 6), (mid, 2 * l / 3)):
                    w[nid] = w.get(nid, 0.0) + c
    assert nedge == round(H / h)
    assert abs(sum(w.values()) - H) < 1e-12 * H
    return w


def write_inp(path, ids, xy, elems, h, w, etype="CPE8", thickness=1.0):
    """etype CPE8: plane strain with (E_PS, NU_PS), i.e. plane stress with (E, NU), thickness 1;
    etype CPS8: ccx's plane-stress element, with (E, NU) and the given thickness (the loads are
    scaled with it)."""
    tol = 1e-6 * h
    fixed = ids[np.abs(xy[:, 0]) < tol]
    center_line = ids[np.abs(xy[:, 1] - YC) < tol]
    tip = sorted(w)
    loads = {nid: TY * w[nid] * thickness for nid in tip}
    assert abs(sum(loads.values()) - PY * thickness) < 1e-9 * abs(PY * thickness)
    e_mod, nu = (E_PS, NU_PS) if etype == "CPE8" else (E, NU)
    with open(path, "w") as f:
        cc.write_mesh(f, f"cantilever, tip shear, plane stress, {etype}", ids, xy, elems, etype)
        cc.write_nset(f, "NFIX", fixed)
        cc.write_nset(f, "NOUT", sorted(set(tip) | set(center_line)))
        f.write(f"*MATERIAL, NAME=M\n*ELASTIC\n{cc.num(e_mod)}, {cc.num(nu)}\n")
        f.write(f"*SOLID SECTION, ELSET=EALL, MATERIAL=M\n{cc.num(thickness)}\n")
        f.write("*BOUNDARY\nNFIX, 1, 2, 0.0\n")
        f.write("*STEP\n*STATIC\n*CLOAD\n")
        for nid in tip:
            f.write(f"{nid}, 2, {cc.num(loads[nid])}\n")
        f.write("*NODE PRINT, NSET=NOUT\nU\n")
        f.write("*NODE PRINT, NSET=NFIX, TOTALS=ONLY\nRF\n")
        f.write("*END STEP\n")
    return center_line


# ---- step 3: run ccx, read .dat ---------------------------------------------------------
def solve(h, work, etype="CPE8", thickness=1.0):
    ids, xy, elems = mesh(h, work)
    w = tip_weights(ids, xy, elems, h)
    center_line = write_inp(os.path.join(work, "beam.inp"), ids, xy, elems, h, w, etype, thickness)
    seconds = cc.run_ccx(work, "beam", f"h = {h}")
    u, (total,) = cc.parse_dat(os.path.join(work, "beam.dat"))
    pos = cc.node_index(ids)
    tc = [nid for nid in center_line if abs(xy[pos[nid], 0] - L) < 1e-6 * h]
    assert len(tc) == 1
    mean = sum(w[nid] * u[nid][1] for nid in w) / H
    cl = np.array(sorted((xy[pos[nid], 0], *u[nid]) for nid in center_line))   # x ux uy
    total = (total[0] / thickness, total[1] / thickness)   # per m of thickness
    return dict(h=h, elements=len(elems), nodes=len(ids), uy=u[tc[0]][1], mean=mean,
                seconds=seconds, reaction=total, centerline=cl)


# ---- step 4: run the meshes, check, write outputs ---------------------------------------
def main():
    a = cc.parse_args(__doc__, max_seconds=120.0)

    def run(h, etype="CPE8", thickness=1.0):
        name = f"h_{h * 1e3:g}mm" + ("" if etype == "CPE8" else f"_{etype}_t{thickness:g}")
        return cc.in_work_folder(f"perinom_fem_cant2d_h{h * 1e3:g}mm_", a.keep, name,
                                 lambda work: solve(h, work, etype, thickness))

    def report(h, r):
        fx, fy = r["reaction"]
        print(f"h = {h * 1e3:8g} mm: {r['elements']:6d} elements {r['nodes']:7d} nodes  "
              f"tip-centre uy = {r['uy']:.7e} m  tip-edge mean uy = {r['mean']:.7e} m  "
              f"ccx {r['seconds']:6.1f} s  reaction ({fx:.3e}, {fy:.7e}) N/m", flush=True)

    results = cc.mesh_series(H_LIST, 6, a.max_seconds, lambda h: f"h = {h * 1e3:g} mm", run, report)

    # sanity checks: equilibrium; the centre line (the neutral axis) does not stretch much
    for r in results:
        fx, fy = r["reaction"]
        assert abs(fy + PY) <= 1e-6 * abs(PY), f"reaction {fy} != {-PY}"
        assert abs(fx) <= 1e-6 * abs(PY), f"horizontal reaction {fx}"
        cl = r["centerline"]
        assert np.abs(cl[:, 1]).max() <= 1e-3 * np.abs(cl[:, 2]).max(), "ux on the centre line"

    # the plane-stress model: ccx's CPS8 with a thin section (H/100 = 0.1 mm) agrees with CPE8
    # (E*, nu*) to a few 1e-5 (the thin slab still has a 3-D boundary layer at the fixed edge,
    # and much thinner sections make ccx's expanded elements ill-conditioned); with the 1 m
    # section CPS8 is a thick slab, nearer plane strain
    for r in results[1:3]:
        h = r["h"]
        for t in (H / 100, 1.0):
            rs = run(h, "CPS8", t)
            d = rs["uy"] / r["uy"] - 1
            print(f"h = {h * 1e3:g} mm, CPS8 with thickness {t:g} m: tip-centre uy = {rs['uy']:.7e} m, "
                  f"{d:+.2e} relative to CPE8 (E*, nu*)")
            if t < 1.0:
                assert abs(d) < 5e-5, "CPS8 with a thin section is not the plane-stress CPE8 model"

    out = {}
    lam = cc.corner_exponent((3 - NU) / (1 + NU))   # plane stress
    for key in ("uy", "mean"):
        f = [r[key] for r in results]
        p, lim = cc.richardson(*f[-3:])
        p_prev, lim_prev = cc.richardson(*f[-4:-1]) if len(f) >= 4 else (np.nan, np.nan)
        _, lim_theory = cc.richardson(*f[-3:], p=2 * lam)
        out[key] = (p, lim, p_prev, lim_prev, f)
        name = {"uy": "tip-centre uy", "mean": "tip-edge mean uy"}[key]
        print(f"{name}: successive differences {', '.join(f'{d:.4e}' for d in np.diff(f))} m")
        print(f"  observed order {p:.3f} (previous three meshes: {p_prev:.3f}), extrapolated "
              f"{lim:.7e} m (previous three: {lim_prev:.7e}; with the corner order 2 lambda = "
              f"{2 * lam:.3f}: {lim_theory:.7e})")
        print(f"  finest mesh - extrapolated {f[-1] - lim:.2e} m ({(f[-1] - lim) / abs(lim):.1e} "
              f"relative); finest two differ by {abs(f[-1] - f[-2]) / abs(lim):.1e} relative")
    lim = out["uy"][1]
    print(f"beam theory: Euler-Bernoulli {EB_TIP:.6e} m, Timoshenko (k = 5/6) {TIMO_TIP:.6e} m; "
          f"FEM tip centre / Timoshenko = {lim / TIMO_TIP:.5f}, / Euler-Bernoulli = {lim / EB_TIP:.5f}")

    os.makedirs(a.out, exist_ok=True)
    cc.write_csv(os.path.join(a.out, "cantilever_2d.csv"),
                 "h_m,elements,nodes,tip_center_uy_m,tip_edge_mean_uy_m,seconds",
                 [f"{cc.mesh_columns(r)},{r['uy']:.7e},{r['mean']:.7e},{r['seconds']:.2f}" for r in results]
                 + [f"0,0,0,{out['uy'][1]:.7e},{out['mean'][1]:.7e},0"])   # h -> 0: Richardson
    cl = results[-1]["centerline"]
    step = max(1, round(LINE_STEP / (results[-1]["h"] / 2)))
    cc.write_csv(os.path.join(a.out, "cantilever_2d_centerline.csv"), "x_m,ux_m,uy_m",
                 [f"{x:.9g},{ux:.7e},{uy:.7e}" for x, ux, uy in cl[::step]])

    fig, (a1, a2) = cc.figure(2)
    xs = np.linspace(0, L, 201)
    eb = lambda x: PY * x ** 2 * (3 * L - x) / (6 * E * I_SEC)   # Euler-Bernoulli deflection
    a1.plot(xs * 1e3, 0 * xs, "k--", lw=0.8, label="Euler-Bernoulli")
    a1.plot(xs * 1e3, PY * xs / (K_SHEAR * G * H) * 1e6, "k:", lw=0.8, label="Timoshenko")
    for r in results:
        c = r["centerline"]
        a1.plot(c[:, 0] * 1e3, (c[:, 2] - eb(c[:, 0])) * 1e6, lw=1, label=f"h = {r['h'] * 1e3:g} mm")
    a1.set(xlabel="x (mm)", ylabel="u_y - Euler-Bernoulli (um)", title="centre line y = 5 mm: u_y minus Euler-Bernoulli")
    hs = np.array([r["h"] for r in results])
    for key, lab in (("uy", "tip centre"), ("mean", "tip-edge mean")):
        f = np.array(out[key][4])
        a2.loglog(hs * 1e3, np.abs(f - out[key][1]) * 1e3, "o-", label=f"|u_y(h) - extrapolated|, {lab}")
    a2.set(xlabel="h (mm)", ylabel="error (mm)", title="tip u_y convergence")
    a2.set_xticks(hs * 1e3, [f"{v * 1e3:g}" for v in hs])
    a2.minorticks_off()
    cc.save_figure(fig, (a1, a2), os.path.join(a.out, "cantilever_2d_fem.png"))
    print("wrote cantilever_2d.csv, cantilever_2d_centerline.csv, cantilever_2d_fem.png in", a.out)


if __name__ == "__main__":
    main()
