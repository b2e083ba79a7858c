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

try:
    import numpy as np
except ImportError:  # e.g. a pyenv python3 first on PATH: fall back to Debian's, which has numpy
    if os.path.exists("/usr/bin/python3") and os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    raise

import argparse
import shutil
import subprocess
import tempfile
import time

# ---- problem data (SI) ------------------------------------------------------------------
L, B, T = 0.1, 0.01, 0.01      # length (x), width (y), depth (z), m
E, NU = 200e9, 0.3             # Pa, -
TZ = -1e6                      # tip traction, z component, Pa
PZ = TZ * B * T                # total tip force, N (-100)
YC, ZC = B / 2, T / 2          # centre line
H_LIST = [5e-3, 2.5e-3, 1.25e-3, 0.625e-3]   # element sides, m (across the section: 2, 4, 8, 16)

HERE = os.path.dirname(os.path.abspath(__file__))
ENV = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1",
           CCX_NPROC_RESULTS="1", CCX_NPROC_STIFFNESS="1")

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
    geo = os.path.join(work, "beam.geo")
    msh = os.path.join(work, "beam.msh")
    ones = lambda n: ", ".join(["1"] * n)
    with open(geo, "w") as f:
        f.write(GEO.format(L=L, by=by, tz=tz, nx=ones(nx), ny=ones(ny), nz=ones(nz),
                           fx=", ".join(repr(v) for v in fx), fy=", ".join(repr(v) for v in fy),
                           fz=", ".join(repr(v) for v in fy)))
    subprocess.run(["gmsh", "-3", geo, "-o", msh, "-format", "msh22", "-v", "1"],
                   check=True, env=ENV, stdout=subprocess.DEVNULL)
    lines = open(msh).read().split("\n")
    i = lines.index("$Nodes")
    n = int(lines[i + 1])
    ids = np.empty(n, dtype=np.int64)
    xyz = np.empty((n, 3))
    for k in range(n):
        t = lines[i + 2 + k].split()
        ids[k] = int(t[0])
        xyz[k] = float(t[1]), float(t[2]), float(t[3])
    if graded is None:
        # gmsh leaves round-off on the uniform grid; snap to the exact half-element grid
        grid = np.round(xyz / (h / 2))
        assert np.abs(grid * (h / 2) - xyz).max() < 1e-9
        xyz = grid * (h / 2)
    key = lambda p: tuple(np.round(p / TOL).astype(np.int64))
    at = {key(p): nid for p, nid in zip(xyz, ids)}
    pos = {nid: k for k, nid in enumerate(ids)}
    i = lines.index("$Elements")
    m = int(lines[i + 1])
    elems = []
    for k in range(m):
        t = [int(v) for v in lines[i + 2 + k].split()]
        if t[1] != 17:   # 20-node hexahedron
            continue
        c = t[3 + t[2]:][:8]   # gmsh and ccx share the corner order
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
def num(v):
    """A number for the ccx input. ccx reads a number from its first 20 characters (Fortran
    f20.0): a longer one whose first 20 characters still read as a number is silently cut.
    Python's shortest repr can be longer (a node at y = 6.135769156722633e-05 m was read as
    6.1357 m), so write 14 significant digits, which fit in 20 characters with the sign."""
    return f"{v:.13e}"


def tip_weights(ids, xyz, elems, full):
    """Consistent nodal weights {node: w} of a unit uniform traction on the face x = L
    (sum w = face area): -A/12 at the corners and A/3 at the mid-edge nodes of each
    rectangular element face of area A."""
    area = B * T if full else B * T / 4
    pos = {nid: k for k, nid in enumerate(ids)}
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
        f.write("*HEADING\ncantilever, tip shear, C3D20R\n*NODE, NSET=NALL\n")
        for nid, (x, y, z) in zip(ids, xyz):
            f.write(f"{nid}, {num(x)}, {num(y)}, {num(z)}\n")
        f.write("*ELEMENT, TYPE=C3D20R, ELSET=EALL\n")
        for eid, e in enumerate(elems, start=1):
            s = [str(v) for v in e]   # ccx: at most 16 entries on the first line
            f.write(f"{eid}, " + ", ".join(s[:15]) + ",\n" + ", ".join(s[15:]) + "\n")
        f.write("*NSET, NSET=NFIX\n" + "".join(f"{v},\n" for v in fixed))
        f.write("*NSET, NSET=NOUT\n" + "".join(f"{v},\n" for v in sorted(set(tip) | set(center_line))))
        f.write(f"*MATERIAL, NAME=M\n*ELASTIC\n{num(E)}, {num(NU)}\n")
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=M\n")
        f.write("*BOUNDARY\nNFIX, 1, 3, 0.0\n")
        if not full:
            f.write("".join(f"{v}, 2, 2, 0.0\n" for v in sym_y))
            f.write("".join(f"{v}, 1, 2, 0.0\n" for v in anti_z))
        f.write("*STEP\n*STATIC\n*CLOAD\n")
        for nid in tip:
            f.write(f"{nid}, 3, {num(loads[nid])}\n")
        f.write("*NODE PRINT, NSET=NOUT\nU\n")
        f.write("*NODE PRINT, NSET=NFIX, TOTALS=ONLY\nRF\n")
        f.write("*END STEP\n")
    return center_line


# ---- step 3: run ccx, read .dat ---------------------------------------------------------
def parse_dat(path):
    """Displacements {node: (ux, uy, uz)} and the total reaction (fx, fy, fz) of NFIX."""
    u, total = {}, None
    mode = None
    for line in open(path):
        s = line.strip()
        if not s:
            continue
        if s.startswith("displacements"):
            mode = "u"
            continue
        if s.startswith("total force"):
            mode = "rf"
            continue
        if s[0].isalpha():
            mode = None
            continue
        t = s.split()
        if mode == "u":
            u[int(t[0])] = tuple(float(v) for v in t[1:4])
        elif mode == "rf":
            total = tuple(float(v) for v in t[:3])
            mode = None
    return u, total


def solve(h, work, full=False, graded=None):
    ids, xyz, elems = mesh(h, work, full, graded)
    w = tip_weights(ids, xyz, elems, full)
    center_line = write_inp(os.path.join(work, "beam.inp"), ids, xyz, elems, w, full)
    t0 = time.time()
    r = subprocess.run(["ccx", "-i", "beam"], cwd=work, env=ENV,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    seconds = time.time() - t0
    if r.returncode != 0 or "ERROR" in r.stdout:
        sys.exit(f"ccx failed for h = {h}:\n{r.stdout[-3000:]}")
    u, total = parse_dat(os.path.join(work, "beam.dat"))
    pos = {nid: k for k, nid in enumerate(ids)}
    tc = [nid for nid in center_line if abs(xyz[pos[nid], 0] - L) < TOL]
    assert len(tc) == 1
    mean = sum(w[nid] * u[nid][2] for nid in w) / sum(w.values())
    cl = np.array(sorted((xyz[pos[nid], 0], *u[nid]) for nid in center_line))   # x ux uy uz
    return dict(h=h, elements=len(elems), nodes=len(ids), uz=u[tc[0]][2], mean=mean,
                seconds=seconds, reaction=total, centerline=cl, full=full, graded=graded)


def richardson(f1, f2, f3, p=None):
    """Richardson extrapolation of three values on meshes refined by 2 (coarse, medium, fine):
    observed order p (unless given) and the limit."""
    if p is None:
        p = np.log((f1 - f2) / (f2 - f3)) / np.log(2.0)
    return p, f3 + (f3 - f2) / (2 ** p - 1)


def corner_exponent(nu):
    """Williams' exponent lambda (u ~ r^lambda) of a 90-degree corner between a fixed and a free
    edge, plane strain: kappa sin^2(lambda pi/2) = (1 + kappa)^2/4 - lambda^2, kappa = 3 - 4 nu.
    Along the edges of the fixed face (fixed face meeting a free face) the 3-D field has this
    plane-strain singularity; the pollution it causes in a point displacement goes like
    h^(2 lambda)."""
    k = 3 - 4 * nu
    f = lambda l: k * np.sin(l * np.pi / 2) ** 2 - (1 + k) ** 2 / 4 + l ** 2
    a, b = 0.5, 0.99
    for _ in range(60):
        m = (a + b) / 2
        a, b = (a, m) if f(a) * f(m) <= 0 else (m, b)
    return m


# ---- step 4: run the meshes, check, write outputs ---------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--max-seconds", type=float, default=200.0,
                    help="skip a mesh whose predicted ccx time (12 x the previous one) exceeds this (default 200)")
    ap.add_argument("--keep", help="keep the work files in this folder")
    ap.add_argument("--out", default=HERE, help="output folder (default: this script's)")
    a = ap.parse_args()
    for tool in ("gmsh", "ccx"):
        if shutil.which(tool) is None:
            sys.exit(f"{tool} not found: apt-get install gmsh calculix-ccx")
    def run(h, full, graded=None):
        work = tempfile.mkdtemp(prefix=f"perinom_fem_cant3d_h{h * 1e3:g}mm_")
        try:
            return solve(h, work, full, graded)
        finally:
            if a.keep:
                dst = os.path.join(a.keep, f"h_{h * 1e3:g}mm" + ("_full" if full else "")
                                   if graded is None else f"graded_{graded}")
                shutil.rmtree(dst, ignore_errors=True)
                shutil.copytree(work, dst)
            shutil.rmtree(work)

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

    results = []
    for h in H_LIST:
        if results and results[-1]["seconds"] * 12 > a.max_seconds:
            print(f"h = {h * 1e3:g} mm skipped: the previous mesh took {results[-1]['seconds']:.1f} s")
            break
        results.append(run(h, False))
        show(results[-1])
        check(results[-1])
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
    lam = corner_exponent(NU)
    for key in ("uz", "mean"):
        f = [r[key] for r in results]
        p, lim = richardson(*f[-3:])
        p_prev, lim_prev = richardson(*f[-4:-1]) if len(f) >= 4 else (np.nan, np.nan)
        _, lim_theory = richardson(*f[-3:], p=2 * lam)
        _, lim_one = richardson(*f[-3:], p=1.0)
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
        p, lim = richardson(*f[-3:])
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
    with open(os.path.join(a.out, "cantilever_3d.csv"), "w") as f:
        f.write("h_m,elements,nodes,tip_center_uz_m,tip_face_mean_uz_m,seconds\n")
        for r in results:
            f.write(f"{r['h']:.6g},{r['elements']},{r['nodes']},{r['uz']:.7e},{r['mean']:.7e},"
                    f"{r['seconds']:.2f}\n")
        f.write(f"0,0,0,{out['uz'][1]:.7e},{out['mean'][1]:.7e},0\n")   # h -> 0: Richardson
    with open(os.path.join(a.out, "cantilever_3d_graded.csv"), "w") as f:
        f.write("level,nx,n_across_half,ratio_x,ratio_yz,elements,nodes,tip_center_uz_m,"
                "tip_face_mean_uz_m,seconds\n")
        for r in graded:
            nx, ny, qx, qy = graded_level(r["graded"])
            f.write(f"{r['graded']},{nx},{ny},{qx:.6f},{qy:.6f},{r['elements']},{r['nodes']},"
                    f"{r['uz']:.7e},{r['mean']:.7e},{r['seconds']:.2f}\n")
        f.write(f"inf,0,0,0,0,0,0,{out['graded_uz'][1]:.7e},{out['graded_mean'][1]:.7e},0\n")
    cl = results[-1]["centerline"]
    with open(os.path.join(a.out, "cantilever_3d_centerline.csv"), "w") as f:
        f.write("x_m,ux_m,uy_m,uz_m\n")
        for x, ux, uy, uz in cl:
            f.write(f"{x:.9g},{ux:.7e},{uy:.7e},{uz:.7e}\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9.6, 3.6), dpi=100)
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
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "cantilever_3d_fem.png"))
    print("wrote cantilever_3d.csv, cantilever_3d_graded.csv, cantilever_3d_centerline.csv, "
          "cantilever_3d_fem.png in", a.out)


if __name__ == "__main__":
    main()
