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
W, H = 0.036, 0.072            # plate width and height, m
E, NU = 30e6, 0.25             # Pa, -
P = 200e3                      # top pressure, Pa
XC = W / 2                     # centre line
H_LIST = [4e-3, 2e-3, 1e-3, 0.5e-3, 0.25e-3]   # element sizes, m (W/h: 9, 18, 36, 72, 144)
EXPECTED_TOP_UY = -0.4466e-3   # m, THEORY sec. 11

HERE = os.path.dirname(os.path.abspath(__file__))
ENV = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1",
           CCX_NPROC_RESULTS="1", CCX_NPROC_STIFFNESS="1")


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
    geo = os.path.join(work, "plate.geo")
    msh = os.path.join(work, "plate.msh")
    with open(geo, "w") as f:
        f.write(GEO.format(W=W, H=H, nx1=nx + 1, ny1=ny + 1))
    subprocess.run(["gmsh", "-2", geo, "-o", msh, "-format", "msh22", "-v", "1"],
                   check=True, env=ENV, stdout=subprocess.DEVNULL)
    lines = open(msh).read().split("\n")
    i = lines.index("$Nodes")
    n = int(lines[i + 1])
    ids = np.empty(n, dtype=np.int64)
    xy = np.empty((n, 2))
    for k in range(n):
        t = lines[i + 2 + k].split()
        ids[k] = int(t[0])
        xy[k] = float(t[1]), float(t[2])
    i = lines.index("$Elements")
    m = int(lines[i + 1])
    elems = []
    for k in range(m):
        t = [int(v) for v in lines[i + 2 + k].split()]
        if t[1] == 16:  # 8-node quad; gmsh and ccx both number corners 1-4, then mid-edges 12, 23, 34, 41
            elems.append(t[3 + t[2]:])
    elems = np.array(elems, dtype=np.int64)
    assert len(elems) == nx * ny, (len(elems), nx, ny)
    # ccx wants counter-clockwise elements in the x-y plane
    pos = {nid: k for k, nid in enumerate(ids)}
    c = np.array([[xy[pos[v]] for v in e[:4]] for e in elems])
    area2 = sum(c[:, a, 0] * c[:, (a + 1) % 4, 1] - c[:, (a + 1) % 4, 0] * c[:, a, 1] for a in range(4))
    cw = area2 < 0
    elems[cw] = elems[cw][:, [0, 3, 2, 1, 7, 6, 5, 4]]
    # gmsh leaves round-off of order 1e-14 m on the structured grid; snap to the exact
    # half-element grid (the mesh is structured, so every node lies on it)
    snapped = np.round(xy / (h / 2)) * (h / 2)
    assert np.abs(snapped - xy).max() < 1e-9
    return ids, snapped, elems, nx, ny


# ---- step 2: CalculiX input -------------------------------------------------------------
def write_inp(path, ids, xy, elems, h):
    tol = 1e-6 * h
    pos = {nid: k for k, nid in enumerate(ids)}
    bottom = ids[np.abs(xy[:, 1]) < tol]
    top_center = ids[(np.abs(xy[:, 1] - H) < tol) & (np.abs(xy[:, 0] - XC) < tol)]
    assert len(top_center) == 1
    # top faces: CPE8 face k (P1..P4) joins corners k and k+1
    dload = []
    for eid, e in enumerate(elems, start=1):
        for k in range(4):
            a, b = xy[pos[e[k]]], xy[pos[e[(k + 1) % 4]]]
            if abs(a[1] - H) < tol and abs(b[1] - H) < tol:
                dload.append((eid, k + 1))
    assert len(dload) == round(W / h)
    with open(path, "w") as f:
        f.write("*HEADING\nuniaxial compression plate, plane strain, CPE8\n*NODE, NSET=NALL\n")
        for nid, (x, y) in zip(ids, xy):
            f.write(f"{nid}, {x!r}, {y!r}, 0.0\n")
        f.write("*ELEMENT, TYPE=CPE8, ELSET=EALL\n")
        for eid, e in enumerate(elems, start=1):
            f.write(f"{eid}, " + ", ".join(str(v) for v in e) + "\n")
        f.write("*NSET, NSET=NBOT\n" + "".join(f"{v},\n" for v in bottom))
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
def parse_dat(path):
    """Displacements {node: (ux, uy)} and the total reaction (fx, fy) of NBOT."""
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
            u[int(t[0])] = (float(t[1]), float(t[2]))
        elif mode == "rf":
            total = (float(t[0]), float(t[1]))
            mode = None
    return u, total


def parse_frd_stress(path):
    """Nodal stresses {node: (sxx, syy, szz, sxy)} from the STRESS block of the .frd."""
    s, inside = {}, False
    for line in open(path):
        if line.startswith(" -4"):
            inside = line.split()[1] == "STRESS"
            continue
        if inside and line.startswith(" -3"):
            inside = False
        if inside and line.startswith(" -1"):
            nid = int(line[3:13])
            v = [float(line[13 + 12 * k: 25 + 12 * k]) for k in range(6)]  # SXX SYY SZZ SXY SYZ SZX
            s[nid] = (v[0], v[1], v[2], v[3])
    return s


def solve(h, work):
    ids, xy, elems, nx, ny = mesh(h, work)
    tc = write_inp(os.path.join(work, "plate.inp"), ids, xy, elems, h)
    t0 = time.time()
    r = subprocess.run(["ccx", "-i", "plate"], cwd=work, env=ENV,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    seconds = time.time() - t0
    if r.returncode != 0 or "ERROR" in r.stdout:
        sys.exit(f"ccx failed for h = {h}:\n{r.stdout[-3000:]}")
    u, total = parse_dat(os.path.join(work, "plate.dat"))
    st = parse_frd_stress(os.path.join(work, "plate.frd"))
    # the centre line x = XC (an element edge when nx is even, mid-edge nodes only when odd)
    line = sorted((xy[k, 1], nid) for k, nid in enumerate(ids) if abs(xy[k, 0] - XC) < 1e-6 * h)
    cl = np.array([(y, *u[nid], *st[nid]) for y, nid in line])   # y ux uy sxx syy szz sxy
    return dict(h=h, elements=len(elems), nodes=len(ids), uy=u[tc][1], seconds=seconds,
                reaction=total, centerline=cl, nx=nx)


def von_mises(sxx, syy, szz, sxy):
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3 * sxy ** 2)


def richardson(f1, f2, f3, p=None):
    """Richardson extrapolation of three values on meshes refined by 2 (coarse, medium, fine):
    observed order p (unless given) and the limit."""
    if p is None:
        p = np.log((f1 - f2) / (f2 - f3)) / np.log(2.0)
    return p, f3 + (f3 - f2) / (2 ** p - 1)


def corner_exponent(nu):
    """Williams' exponent lambda (u ~ r^lambda) of a 90-degree corner between a fixed and a free
    edge, plane strain: kappa sin^2(lambda pi/2) = (1 + kappa)^2/4 - lambda^2, kappa = 3 - 4 nu.
    The pollution it causes in a point displacement converges like h^(2 lambda)."""
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
    ap.add_argument("--max-seconds", type=float, default=120.0,
                    help="skip a mesh whose predicted ccx time (6 x the previous one) exceeds this (default 120)")
    ap.add_argument("--keep", help="keep the work files in this folder")
    ap.add_argument("--out", default=HERE, help="output folder (default: this script's)")
    a = ap.parse_args()
    for tool in ("gmsh", "ccx"):
        if shutil.which(tool) is None:
            sys.exit(f"{tool} not found: apt-get install gmsh calculix-ccx")
    results = []
    for h in H_LIST:
        if results and results[-1]["seconds"] * 6 > a.max_seconds:
            print(f"h = {h * 1e3:g} mm skipped: the previous mesh took {results[-1]['seconds']:.1f} s")
            break
        work = tempfile.mkdtemp(prefix=f"perinom_fem_h{h * 1e3:g}mm_")
        try:
            r = solve(h, work)
        finally:
            if a.keep:
                dst = os.path.join(a.keep, f"h_{h * 1e3:g}mm")
                shutil.rmtree(dst, ignore_errors=True)
                shutil.copytree(work, dst)
            shutil.rmtree(work)
        results.append(r)
        fx, fy = r["reaction"]
        cl = r["centerline"]
        mid = np.abs(cl[:, 0] - H / 2) < 0.25 * H   # middle half of the height
        print(f"h = {h * 1e3:5g} mm: {r['elements']:6d} elements {r['nodes']:7d} nodes  "
              f"top-centre uy = {r['uy']:.7e} m  ccx {r['seconds']:6.1f} s  "
              f"reaction ({fx:.6e}, {fy:.9e}) N/m  centre-line syy in [{cl[mid, 4].min():.1f}, "
              f"{cl[mid, 4].max():.1f}] Pa over 0.25H..0.75H")

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
    p, lim = richardson(*uys[-3:])
    p_prev, lim_prev = richardson(*uys[-4:-1]) if len(uys) >= 4 else (np.nan, np.nan)
    lam = corner_exponent(NU)
    _, lim_theory = richardson(*uys[-3:], p=2 * lam)
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
    with open(os.path.join(a.out, "uniaxial_compression_top_center.csv"), "w") as f:
        f.write("h_m,elements,nodes,top_center_uy_m,seconds\n")
        for r in results:
            f.write(f"{r['h']:.6g},{r['elements']},{r['nodes']},{r['uy']:.7e},{r['seconds']:.2f}\n")
        f.write(f"0,0,0,{lim:.7e},0\n")   # h -> 0: Richardson extrapolation of the three finest
    with open(os.path.join(a.out, "uniaxial_compression_centerline.csv"), "w") as f:
        f.write("y_m,ux_m,uy_m,von_mises_pa,sxx_pa,syy_pa,szz_pa,sxy_pa\n")
        for row in cl:
            yy, uxx, uyy, a_, b_, c_, d_ = row
            f.write(f"{yy:.9g},{uxx:.7e},{uyy:.7e},{von_mises(a_, b_, c_, d_):.6e},"
                    f"{a_:.6e},{b_:.6e},{c_:.6e},{d_:.6e}\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(9.6, 3.6), dpi=100)
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
    for ax in (a1, a2, a3):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "uniaxial_compression_fem.png"))
    print("wrote", ", ".join(f"uniaxial_compression_{s}" for s in ("top_center.csv", "centerline.csv", "fem.png")),
          "in", a.out)


if __name__ == "__main__":
    main()
