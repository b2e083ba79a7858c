#!/usr/bin/env python3
"""FEM reference for a 3-D cantilever under a tip shear load, by CalculiX.

What is solved
  A box 0 <= x <= 0.1, 0 <= y <= 0.01, 0 <= z <= 0.01 (m), linear elastic isotropic,
  E = 200e9 Pa, nu = 0.3. The face x = 0 is fully fixed (ux = uy = uz = 0 at every node of
  it). The face x = 0.1 carries the uniform traction (0, 0, -1e6) Pa, a total force of
  -100 N in z. The other faces are free. The edges of the fixed face carry (weak)
  singularities; the tip displacement converges all the same.

How
  Structured meshes of cubic 20-node serendipity hexahedra made by gmsh (Extrude with Layers
  + Recombine, second order, incomplete), solved by CalculiX ccx with C3D20R elements
  (reduced 2x2x2 integration). The problem is symmetric about the plane y = 0.005 and
  antisymmetric about z = 0.005 (the reflection z -> 0.01 - z turns the load into its
  opposite), so a quarter, 0 <= y <= 0.005, 0 <= z <= 0.005, is solved, with uy = 0 on
  y = 0.005 (symmetry) and ux = uy = 0 on z = 0.005 (antisymmetry: uz is even, ux and uy
  odd about that plane). On a mesh that is the quarter of a symmetric full mesh this gives
  the full mesh's solution exactly; the script checks it by also solving the two coarsest
  full meshes. The quarter makes the finest mesh (16 x 16 elements across the full section)
  affordable: ccx's direct solver (SPOOLES, the only one in the Debian build besides a slow
  iterative one) costs about N b^2 for N unknowns and a front b of about one cross-section,
  and the quarter divides that by about 16.
  The tip traction is applied as consistent nodal forces (*CLOAD), computed here: for a
  uniform traction t on a flat rectangular 8-node face of area A the consistent forces are
  -t A/12 at each corner and t A/3 at each mid-edge node. The script checks that they sum
  to the force on the loaded face (-25 N on the quarter, -100 N on the full face) and that
  the reaction of the fixed face balances it. Displacements and reactions are read from the
  .dat file (*NODE PRINT, 7 significant digits).
  The edge singularities make the uniform family converge slowly (order about 1.3-1.5, so
  its Richardson extrapolation is uncertain by about 1e-5); a second family, graded toward
  the fixed face and its edges, converges faster and checks the extrapolated value.

Outputs (in this folder; work files go to a temporary folder and are deleted)
  cantilever_3d.csv             one row per mesh: h_m, elements, nodes, tip_center_uz_m,
                                tip_face_mean_uz_m, seconds (ccx wall time); a last row with
                                h_m = 0 holds the Richardson-extrapolated values. h_m is the
                                element side (cubic elements); elements and nodes are those
                                of the quarter model that was solved (the full mesh has 4x
                                the elements).
                                tip_center_uz_m: uz at the node (0.1, 0.005, 0.005);
                                tip_face_mean_uz_m: the area average of uz over the face
                                x = 0.1 (the integral of the interpolated uz over the face,
                                divided by its area; it is also the work-conjugate of the
                                uniform load: -(load work)/(100 N)). By symmetry the mean
                                over the quarter face is the mean over the full face.
  cantilever_3d_graded.csv      the check: level, nx, n_across_half, ratio_x, ratio_yz,
                                elements, nodes, tip_center_uz_m, tip_face_mean_uz_m, seconds
                                for a second, graded family of quarter meshes (geometric
                                progressions toward the fixed face and its edges, nested, 10 2^k
                                elements along x and 2^k across each half-side, k = 0..3); a
                                last row (level inf) holds its Richardson extrapolation, which
                                the script requires to agree with the uniform family's to 3e-5.
  cantilever_3d_centerline.csv  x_m, ux_m, uy_m, uz_m at the nodes on y = z = 0.005, finest
                                mesh.
  cantilever_3d_fem.png         the centre-line deflection minus Euler-Bernoulli, and the
                                convergence.

Usage: python3 verification/fem/cantilever_3d.py [--max-seconds S] [--keep DIR] [--out DIR]
Needs gmsh and CalculiX (Debian: apt-get install gmsh calculix-ccx), python3 with numpy
and matplotlib (Debian: python3-numpy python3-matplotlib). Runs single-threaded.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ccx_common as cc   # the shared helpers (it re-runs this under /usr/bin/python3 without numpy)
import numpy as np

# ---- problem data (SI) ------------------------------------------------------------------
L, B, T = 0.1, 0.01, 0.01      # length (x), width (y), depth (z), m
E, NU = 200e9, 0.3             # Pa, -
TZ = -1e6                      # tip traction, z component, Pa
PZ = TZ * B * T                # total tip force, N (-100)
YC, ZC = B / 2, T / 2          # centre line
H_LIST = [5e-3, 2.5e-3, 1.25e-3, 0.625e-3]   # element sides, m (across the section: 2, 4, 8, 16)

# beam theory, for comparison
I_SEC = B * T ** 3 / 12                       # second moment of area about y, m^4
G = E / (2 * (1 + NU))
EB_TIP = PZ * L ** 3 / (3 * E * I_SEC)        # Euler-Bernoulli
K_COWPER = 10 * (1 + NU) / (12 + 11 * NU)     # Cowper's shear coefficient, rectangle
TIMO_TIP = EB_TIP + PZ * L / (K_COWPER * G * B * T)


# ---- step 1: mesh with gmsh -------------------------------------------------------------
GEO = """// cantilever, structured 20-node hexahedra
Point(1) = {{0, 0, 0}};
l[] = Extrude{{0, {by!r}, 0}}{{ Point{{1}}; Layers{{ {{{ny}}}, {{{fy}}} }}; }};
s[] = Extrude{{0, 0, {tz!r}}}{{ Line{{l[1]}}; Layers{{ {{{nz}}}, {{{fz}}} }}; Recombine; }};
v[] = Extrude{{{L!r}, 0, 0}}{{ Surface{{s[1]}}; Layers{{ {{{nx}}}, {{{fx}}} }}; Recombine; }};
Physical Volume("beam") = {{v[1]}};
Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
"""
# C3D20 node order: corners 1-8 (1-4 one face, 5-8 the opposite one), then the mid-edge
# nodes of edges 12 23 34 41, 56 67 78 85, 15 26 37 48
EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
         (0, 4), (1, 5), (2, 6), (3, 7)]
TOL = 1e-9   # m, for finding nodes on planes (the smallest element side is 6e-5 m)

# the graded cross-check family (quarter model): level k = 0..3 has 10 2^k elements along x
# and 2^k across each half-side, in geometric progression toward the fixed face (x = 0) and
# toward the free faces y = 0 and z = 0 (where the edges of the fixed face are); at level 3
# the last element is GRADE_X = 100 times the first along x and GRADE_YZ = 20 times across.
# Each level's ratio is the square of the next one's, so the meshes are nested.
GRADE_X, GRADE_YZ = 100.0, 20.0


def graded_level(k):
    """(nx, n across each half-side, ratio along x, ratio across) of the graded level k."""
    nx, ny = 10 * 2 ** k, 2 ** k
    return nx, ny, GRADE_X ** (2 ** (3 - k) / 79), GRADE_YZ ** (2 ** (3 - k) / 7)


def fractions(n, q):
    """Cumulative fractions of n layers in geometric progression of ratio q (gmsh Layers)."""
    w = q ** np.arange(n)
    c = np.cumsum(w / w.sum())
    c[-1] = 1.0
    return c


def mesh(h, work, full, graded=None):
    """The box 0 <= x <= L, 0 <= y <= by, 0 <= z <= tz (by, tz = B, T for the full model,
    B/2, T/2 for the quarter), in cubes of side h, or (graded = k) the graded level k of the
    quarter. Returns node ids, coordinates (n x 3) and 20-node elements (m x 20, node ids, in
    ccx order)."""
    by, tz = (B, T) if full else (B / 2, T / 2)
    if graded is None:
        nx, ny, nz = round(L / h), round(by / h), round(tz / h)
        qx = qy = 1.0
    else:
        assert not full
        nx, ny, qx, qy = graded_level(graded)
        nz = ny
    fx, fy = fractions(nx, qx), fractions(ny, qy)
    ones = lambda n: ", ".join(["1"] * n)
    lines = cc.gmsh(GEO.format(L=L, by=by, tz=tz, nx=ones(nx), ny=ones(ny), nz=ones(nz),
                               fx=", ".join(repr(v) for v in fx), fy=", ".join(repr(v) for v in fy),
                               fz=", ".join(repr(v) for v in fy)), work, "beam", dim=3)
    ids, xyz = cc.msh_nodes(lines, 3)
    if graded is None:
        # gmsh leaves round-off on the uniform grid; snap to the exact half-element grid
        grid = np.round(xyz / (h / 2))
        assert np.abs(grid * (h / 2) - xyz).max() < 1e-9
        xyz = grid * (h / 2)
    key = lambda p: tuple(np.round(p / TOL).astype(np.int64))
    at = {key(p): nid for p, nid in zip(xyz, ids)}
    pos = cc.node_index(ids)
    elems = []
    for e in cc.msh_elements(lines, 17):   # 20-node hexahedra
        c = e[:8]   # gmsh and ccx share the corner order
        g = np.array([xyz[pos[v]] for v in c])
        # ccx wants a positive volume: corner 5 on the side the normal of 1-2-3-4 points to
        if np.dot(np.cross(g[1] - g[0], g[3] - g[0]), g[4] - g[0]) < 0:
            c = [c[0], c[3], c[2], c[1], c[4], c[7], c[6], c[5]]
            g = np.array([xyz[pos[v]] for v in c])
        # the mid-edge nodes found by position (robust to gmsh's own mid-edge order)
        mids = [at[key((g[a] + g[b]) / 2)] for a, b in EDGES]
        elems.append(c + mids)
    elems = np.array(elems, dtype=np.int64)
    assert len(elems) == nx * ny * nz, (len(elems), nx, ny, nz)
    return ids, xyz, elems


# ---- step 2: CalculiX input -------------------------------------------------------------
def tip_weights(ids, xyz, elems, full):
    """Consistent nodal weights {node: w} of a unit uniform traction on the face x = L
    (sum w = face area): -A/12 at the corners and A/3 at the mid-edge nodes of each
    rectangular element face of area A."""
    area = B * T if full else B * T / 4
    pos = cc.node_index(ids)
    w = {}
    total = 0.0
    for e in elems:
        p = np.array([xyz[pos[v]] for v in e])
        on = np.abs(p[:, 0] - L) < TOL
        if on[:8].sum() == 4:
            assert on.sum() == 8
            c = p[:8][on[:8]]
            a = np.ptp(c[:, 1]) * np.ptp(c[:, 2])
            total += a
            for k in np.nonzero(on)[0]:
                w[e[k]] = w.get(e[k], 0.0) + (a / 3 if k >= 8 else -a / 12)
    assert abs(total - area) < 1e-9 * area
    assert abs(sum(w.values()) - area) < 1e-12 * area
    return w


def write_inp(path, ids, xyz, elems, w, full):
    tol = TOL
    fixed = ids[np.abs(xyz[:, 0]) < tol]
    center_line = ids[(np.abs(xyz[:, 1] - YC) < tol) & (np.abs(xyz[:, 2] - ZC) < tol)]
    sym_y = ids[np.abs(xyz[:, 1] - YC) < tol]     # symmetry plane y = B/2: uy = 0
    anti_z = ids[np.abs(xyz[:, 2] - ZC) < tol]    # antisymmetry plane z = T/2: ux = uy = 0
    tip = sorted(w)
    loads = {nid: TZ * w[nid] for nid in tip}
    force = PZ if full else PZ / 4
    assert abs(sum(loads.values()) - force) < 1e-9 * abs(force)
    with open(path, "w") as f:
        cc.write_mesh(f, "cantilever, tip shear, C3D20R", ids, xyz, elems, "C3D20R")
        cc.write_nset(f, "NFIX", fixed)
        cc.write_nset(f, "NOUT", sorted(set(tip) | set(center_line)))
        f.write(f"*MATERIAL, NAME=M\n*ELASTIC\n{cc.num(E)}, {cc.num(NU)}\n")
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=M\n")
        f.write("*BOUNDARY\nNFIX, 1, 3, 0.0\n")
        if not full:
            f.write("".join(f"{v}, 2, 2, 0.0\n" for v in sym_y))
            f.write("".join(f"{v}, 1, 2, 0.0\n" for v in anti_z))
        f.write("*STEP\n*STATIC\n*CLOAD\n")
        for nid in tip:
            f.write(f"{nid}, 3, {cc.num(loads[nid])}\n")
        f.write("*NODE PRINT, NSET=NOUT\nU\n")
        f.write("*NODE PRINT, NSET=NFIX, TOTALS=ONLY\nRF\n")
        f.write("*END STEP\n")
    return center_line


# ---- step 3: run ccx, read .dat ---------------------------------------------------------
def solve(h, work, full=False, graded=None):
    ids, xyz, elems = mesh(h, work, full, graded)
    w = tip_weights(ids, xyz, elems, full)
    center_line = write_inp(os.path.join(work, "beam.inp"), ids, xyz, elems, w, full)
    seconds = cc.run_ccx(work, "beam", f"h = {h}")
    u, (total,) = cc.parse_dat(os.path.join(work, "beam.dat"), 3)
    pos = cc.node_index(ids)
    tc = [nid for nid in center_line if abs(xyz[pos[nid], 0] - L) < TOL]
    assert len(tc) == 1
    mean = sum(w[nid] * u[nid][2] for nid in w) / sum(w.values())
    cl = np.array(sorted((xyz[pos[nid], 0], *u[nid]) for nid in center_line))   # x ux uy uz
    return dict(h=h, elements=len(elems), nodes=len(ids), uz=u[tc[0]][2], mean=mean,
                seconds=seconds, reaction=total, centerline=cl, full=full, graded=graded)


# ---- step 4: run the meshes, check, write outputs ---------------------------------------
def main():
    a = cc.parse_args(__doc__, max_seconds=200.0, factor=12)

    def run(h, full, graded=None):
        name = f"h_{h * 1e3:g}mm" + ("_full" if full else "") if graded is None else f"graded_{graded}"
        return cc.in_work_folder(f"perinom_fem_cant3d_h{h * 1e3:g}mm_", a.keep, name,
                                 lambda work: solve(h, work, full, graded))

    def show(r):
        fx, fy, fz = r["reaction"]
        name = f"h = {r['h'] * 1e3:6g} mm" if r["graded"] is None else f"graded level {r['graded']}"
        print(f"{name} {'full   ' if r['full'] else 'quarter'}: {r['elements']:6d} "
              f"elements {r['nodes']:7d} nodes  tip-centre uz = {r['uz']:.7e} m  tip-face mean uz = "
              f"{r['mean']:.7e} m  ccx {r['seconds']:6.1f} s  reaction ({fx:.3e}, {fy:.3e}, {fz:.7e}) N",
              flush=True)

    def check(r):
        # equilibrium: the fixed face carries the whole tip force (a quarter of it on the quarter;
        # there its x and y resultants are not zero: the other half of the bending couple, and
        # of the Poisson stresses, is on the antisymmetry and symmetry planes)
        force = PZ if r["full"] else PZ / 4
        fx, fy, fz = r["reaction"]
        assert abs(fz + force) <= 1e-6 * abs(force), f"reaction {fz} != {-force}"
        if r["full"]:
            assert abs(fx) <= 1e-6 * abs(force) and abs(fy) <= 1e-6 * abs(force)
        cl = r["centerline"]   # the centre line bends in z only, without stretching
        assert np.abs(cl[:, 1:3]).max() <= 1e-6 * np.abs(cl[:, 3]).max(), "ux or uy on the centre line"

    def report(h, r):
        show(r)
        check(r)

    results = cc.mesh_series(H_LIST, 12, a.max_seconds, lambda h: f"h = {h * 1e3:g} mm",
                             lambda h: run(h, False), report)
    # the quarter model against the full one, on the two coarsest meshes: same solution to the
    # 7 digits of the .dat file
    for r in results[:2]:
        rf = run(r["h"], True)
        show(rf)
        check(rf)
        for key in ("uz", "mean"):
            assert abs(rf[key] - r[key]) <= 2e-7 * abs(r[key]), (key, rf[key], r[key])
        assert np.allclose(rf["centerline"], r["centerline"], rtol=0, atol=2e-7 * abs(r["uz"]))
    print("quarter model = full model on the two coarsest meshes (tip centre, face mean, centre line)")
    # the graded family, a check of the extrapolated values
    graded = []
    for k in range(4):
        graded.append(run(L / graded_level(k)[0], False, k))
        show(graded[-1])
        check(graded[-1])

    out = {}
    lam = cc.corner_exponent(3 - 4 * NU)   # plane strain, along the edges of the fixed face
    for key in ("uz", "mean"):
        f = [r[key] for r in results]
        p, lim = cc.richardson(*f[-3:])
        p_prev, lim_prev = cc.richardson(*f[-4:-1]) if len(f) >= 4 else (np.nan, np.nan)
        _, lim_theory = cc.richardson(*f[-3:], p=2 * lam)
        _, lim_one = cc.richardson(*f[-3:], p=1.0)
        out[key] = (p, lim, p_prev, lim_prev, f)
        name = {"uz": "tip-centre uz", "mean": "tip-face mean uz"}[key]
        print(f"{name}: successive differences {', '.join(f'{d:.4e}' for d in np.diff(f))} m")
        print(f"  observed order {p:.3f} (previous three meshes: {p_prev:.3f}), extrapolated "
              f"{lim:.7e} m (previous three: {lim_prev:.7e}; with the edge order 2 lambda = "
              f"{2 * lam:.3f}: {lim_theory:.7e}; with order 1: {lim_one:.7e})")
        print(f"  finest mesh - extrapolated {f[-1] - lim:.2e} m ({(f[-1] - lim) / abs(lim):.1e} "
              f"relative); finest two differ by {abs(f[-1] - f[-2]) / abs(lim):.1e} relative")
    for key in ("uz", "mean"):
        f = [r[key] for r in graded]
        p, lim = cc.richardson(*f[-3:])
        out["graded_" + key] = (p, lim, f)
        name = {"uz": "tip-centre uz", "mean": "tip-face mean uz"}[key]
        print(f"graded family, {name}: successive differences {', '.join(f'{d:.4e}' for d in np.diff(f))} m, "
              f"observed order {p:.3f}, extrapolated {lim:.7e} m; against the uniform family's "
              f"{out[key][1]:.7e} m: {lim / out[key][1] - 1:+.1e}")
        assert abs(lim / out[key][1] - 1) < 3e-5, "the graded and uniform families disagree"
    lim = out["uz"][1]
    print(f"beam theory: Euler-Bernoulli {EB_TIP:.6e} m, Timoshenko (k = {K_COWPER:.4f}) {TIMO_TIP:.6e} m; "
          f"FEM tip centre / Timoshenko = {lim / TIMO_TIP:.5f}")

    os.makedirs(a.out, exist_ok=True)
    cc.write_csv(os.path.join(a.out, "cantilever_3d.csv"),
                 "h_m,elements,nodes,tip_center_uz_m,tip_face_mean_uz_m,seconds",
                 [f"{cc.mesh_columns(r)},{r['uz']:.7e},{r['mean']:.7e},{r['seconds']:.2f}" for r in results]
                 + [f"0,0,0,{out['uz'][1]:.7e},{out['mean'][1]:.7e},0"])   # h -> 0: Richardson
    with open(os.path.join(a.out, "cantilever_3d_graded.csv"), "w") as f:
        f.write("level,nx,n_across_half,ratio_x,ratio_yz,elements,nodes,tip_center_uz_m,"
                "tip_face_mean_uz_m,seconds\n")
        for r in graded:
            nx, ny, qx, qy = graded_level(r["graded"])
            f.write(f"{r['graded']},{nx},{ny},{qx:.6f},{qy:.6f},{r['elements']},{r['nodes']},"
                    f"{r['uz']:.7e},{r['mean']:.7e},{r['seconds']:.2f}\n")
        f.write(f"inf,0,0,0,0,0,0,{out['graded_uz'][1]:.7e},{out['graded_mean'][1]:.7e},0\n")
    cl = results[-1]["centerline"]
    cc.write_csv(os.path.join(a.out, "cantilever_3d_centerline.csv"), "x_m,ux_m,uy_m,uz_m",
                 [f"{x:.9g},{ux:.7e},{uy:.7e},{uz:.7e}" for x, ux, uy, uz in cl])

    fig, (a1, a2) = cc.figure(2)
    xs = np.linspace(0, L, 201)
    eb = lambda x: PZ * x ** 2 * (3 * L - x) / (6 * E * I_SEC)   # Euler-Bernoulli deflection
    a1.plot(xs * 1e3, 0 * xs, "k--", lw=0.8, label="Euler-Bernoulli")
    a1.plot(xs * 1e3, PZ * xs / (K_COWPER * G * B * T) * 1e6, "k:", lw=0.8, label="Timoshenko")
    for r in results:
        c = r["centerline"]
        a1.plot(c[:, 0] * 1e3, (c[:, 3] - eb(c[:, 0])) * 1e6, lw=1, label=f"h = {r['h'] * 1e3:g} mm")
    a1.set(xlabel="x (mm)", ylabel="u_z - Euler-Bernoulli (um)", title="centre line y = z = 5 mm: u_z minus Euler-Bernoulli")
    hs = np.array([r["h"] for r in results])
    for key, lab in (("uz", "tip centre"), ("mean", "tip-face mean")):
        f = np.array(out[key][4])
        a2.loglog(hs * 1e3, np.abs(f - out[key][1]) * 1e3, "o-", label=f"|u_z(h) - extrapolated|, {lab}")
    fg = np.array(out["graded_uz"][2])
    a2.loglog(hs * 1e3, np.abs(fg - out["uz"][1]) * 1e3, "s--",
              label="graded family (same counts across, half along x), tip centre")
    a2.set(xlabel="h (mm)", ylabel="error (mm)", title="tip u_z convergence")
    a2.set_xticks(hs * 1e3, [f"{v * 1e3:g}" for v in hs])
    a2.minorticks_off()
    cc.save_figure(fig, (a1, a2), os.path.join(a.out, "cantilever_3d_fem.png"))
    print("wrote cantilever_3d.csv, cantilever_3d_graded.csv, cantilever_3d_centerline.csv, "
          "cantilever_3d_fem.png in", a.out)


if __name__ == "__main__":
    main()
