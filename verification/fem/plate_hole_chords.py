#!/usr/bin/env python3
"""FEM reference for the plate with a hole as perinom's body-fitted particles see it: a polygonal hole, by CalculiX.

Why
  perinom's plate_hole_mesh.yaml (verification/formulation) puts its particles at the
  centroids of the quadrangles of plate_hole_h2.msh, plate_hole_h1.msh, plate_hole_h05.msh
  (plate_hole.geo, h = 2, 1, 0.5 mm), with their exact areas, and takes the mesh's boundary
  edges as its boundary facets. The hole it sees is therefore the polygon of the mesh's hole
  nodes (chords of the circle), not the circle of plate_hole.py. This script measures how
  much that polygon alone changes ux at (0.05, 0), so that perinom's error against the
  circle's reference can be split into a geometric part and perinom's own part.

What is solved
  The quarter plate of plate_hole.py: 0 <= x <= 0.05, 0 <= y <= 0.05 (m), plane strain,
  thickness 1 m, E = 200e9 Pa, nu = 0.3, rollers ux = 0 on x = 0 and uy = 0 on y = 0, the
  traction (1e6, 0) Pa on x = 0.05, y = 0.05 and the hole free. The hole is, in turn,
  - for each of the three .msh files, the polygon of its hole nodes: the nodes of the
    physical curve "hole" (read with the gmsh Python API), chained along the mesh's hole
    edges from (R, 0) to (0, R), joined by straight segments (R = 0.005 m; 5, 9 and 17
    nodes, all on the circle);
  - the circle of radius R itself, as the check of the meshing against plate_hole.csv.
  Reported: ux at (0.05, 0), and the area of the quarter disc minus that of the quarter
  polygon (the material the polygon adds).

How
  gmsh (the .geo is written here, meshed by the gmsh command) meshes the plate with
  unstructured second-order serendipity quads (8 nodes; Frontal-Delaunay triangles,
  recombined into quads by the full-quad algorithm, which splits every element, so there
  is no triangle left; Mesh.Algorithm = 8 crashes Debian's gmsh 4.8.4). The element size
  is H_HOLE / 2^k on the hole and grows linearly with the distance from the hole up to
  H_FAR / 2^k at D_GROW (0.4 mm, 4 mm, 20 mm, halved by the full-quad split); the levels
  k = 0, 1, 2, 3 give about 500, 1,600, 6,000, 24,000 elements. CalculiX ccx solves it with
  CPE8 elements (plane strain, full integration), the traction as a *DLOAD pressure of -1e6 Pa
  on the faces on x = 0.05, and prints ux at (0.05, 0) and the total reactions of the rollers
  (checked: -5e4 N/m on x = 0, 0 on y = 0) in the .dat file (7 significant digits, so one
  unit of the last digit is 4.2e-7 relative). The reported values are the finest level's;
  the script stops unless the last two levels agree to 1e-5 relative and the circle
  reproduces plate_hole.csv (2.3927310e-7 m) to 1e-5.

Measured (levels 0-3, about 1 minute in all; ccx single-threaded, 10 s on level 3)
  ux at (0.05, 0), m, on levels 0, 1, 2, 3 (and 4, 93,000 elements, 280,000 nodes, about
  2 minutes of ccx each, run once with LEVELS = [2, 3, 4]):
    circle   2.3927190e-7  2.3927290e-7  2.3927300e-7  2.3927310e-7  (2.3927310e-7)
    h2 poly  2.3898870e-7  2.3899090e-7  2.3899180e-7  2.3899220e-7  (2.3899230e-7)
    h1 poly  2.3919730e-7  2.3919860e-7  2.3919880e-7  2.3919890e-7  (2.3919900e-7)
    h05 poly 2.3925300e-7  2.3925390e-7  2.3925400e-7  2.3925400e-7  (2.3925410e-7)
  so the level-3 values differ from level 4 by at most 4.2e-7 relative (one unit of the last
  printed digit; the level-to-level changes fall by about 2.3 per level on h2, whose polygon
  corners converge slowest), and the circle equals plate_hole.csv's 2.3927310e-7 m to all 7
  digits.

    mesh   hole nodes  area deficit (m^2)  ux polygon (m)  geometric effect
    h2          5         5.0078e-7         2.3899220e-7       -0.1174 %
    h1          9         1.2592e-7         2.3919890e-7       -0.0310 %
    h05        17         3.1526e-8         2.3925400e-7       -0.0080 %
  The polygon is a smaller hole, hence a stiffer plate: the geometric effect is negative
  and scales like the area deficit, as h^2 (ratios 3.8 and 3.9; the deficit's 4.0 and 4.0).
  It does not explain perinom's positive errors (+0.73, +0.30, +0.09 % against the circle);
  against its own polygon they are larger:
  100 ((1 + e/100) 2.3927310e-7 / ux_polygon - 1) = +0.848, +0.331, +0.098 %
  (perinom's probe ux_right, --threads 1: 2.4102312e-7, 2.3998328e-7, 2.3948863e-7 m,
  i.e. +0.731, +0.297, +0.090 % against the circle, +0.850, +0.328, +0.098 % against the
  polygon).

Outputs (in this folder; work files go to a temporary folder and are deleted)
  plate_hole_chords.csv   one row per body-fitted mesh: mesh, hole_nodes,
                          polygon_area_deficit (m^2, quarter disc minus quarter polygon),
                          ux_polygon_fem (m, ux at (0.05, 0)), ux_circle_fem (m, the same
                          for the circle), geometric_effect_percent
                          (100 (ux_polygon / ux_circle - 1)).
  The console shows every level and perinom's error against its own polygon.

Usage: python3 verification/fem/plate_hole_chords.py [--max-seconds S] [--keep DIR] [--out DIR]
Needs gmsh, CalculiX and the gmsh Python API (Debian: apt-get install gmsh calculix-ccx
python3-gmsh), python3 with numpy. Runs single-threaded.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ccx_common as cc   # the shared helpers (it re-runs this under /usr/bin/python3 without numpy)
import numpy as np

# ---- problem data (SI), as in plate_hole.py ---------------------------------------------
W = 0.05                       # half width of the plate, m
R = 0.005                      # hole radius, m
E, NU = 200e9, 0.3             # Pa, -
S = 1e6                        # applied traction, Pa
TOL = 1e-9                     # m, for finding nodes on the straight edges
UX_REF = 2.3927310e-7          # m, ux at (W, 0) for the true circle: plate_hole.csv (h -> 0 row)

# the body-fitted meshes of perinom's plate_hole_mesh.yaml and perinom's error in ux at (W, 0)
# against UX_REF, in %, on each (the quoted results of that case)
FORMULATION = os.path.join(cc.HERE, "..", "formulation")
MESHES = [("plate_hole_h2.msh", 0.73), ("plate_hole_h1.msh", 0.30), ("plate_hole_h05.msh", 0.09)]

# the fine FEM meshes: element size H_HOLE / 2^k on the hole, growing linearly with the
# distance from it up to H_FAR / 2^k (before gmsh's full-quad split, which halves both)
H_HOLE, H_FAR, D_GROW = 4e-4, 4e-3, 0.02
LEVELS = [0, 1, 2, 3]
CONVERGED = 1e-5               # largest relative change of ux between the last two levels


# ---- the hole polygon of a body-fitted mesh ---------------------------------------------
def hole_polygon(msh_path):
    """The hole nodes of a gmsh mesh (physical curve "hole"), as an (n + 1) x 2 array ordered
    along the hole's edges from (R, 0) to (0, R). Read with the gmsh Python API."""
    import gmsh
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Verbosity", 1)
        gmsh.open(msh_path)
        names = {gmsh.model.getPhysicalName(d, t): (d, t) for d, t in gmsh.model.getPhysicalGroups()}
        dim, tag = names["hole"]
        tags, xyz = gmsh.model.mesh.getNodesForPhysicalGroup(dim, tag)
        pos = {int(t): p[:2] for t, p in zip(tags, xyz.reshape(-1, 3))}
        edges = []
        for curve in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            types, _, nodes = gmsh.model.mesh.getElements(1, curve)
            assert list(types) == [1], f"{msh_path}: the hole's edges are not 2-node lines"
            edges += [tuple(int(v) for v in e) for e in nodes[0].reshape(-1, 2)]
    finally:
        gmsh.finalize()
    return chain(edges, pos)


def chain(edges, pos):
    """The nodes of the open chain of edges (pairs of node tags), from the node at (R, 0) to
    the node at (0, R), as coordinates."""
    neighbours = {}
    for a, b in edges:
        neighbours.setdefault(a, []).append(b)
        neighbours.setdefault(b, []).append(a)
    start = min(neighbours, key=lambda v: np.hypot(pos[v][0] - R, pos[v][1]))
    path = [start]
    while len(path) < len(neighbours):
        path.append(next(v for v in neighbours[path[-1]] if v not in path[-2:]))
    xy = np.array([pos[v] for v in path], dtype=float)
    assert np.allclose(xy[0], (R, 0), atol=TOL) and np.allclose(xy[-1], (0, R), atol=TOL)
    assert np.allclose(np.hypot(xy[:, 0], xy[:, 1]), R, rtol=1e-12, atol=0), "hole node off the circle"
    xy[0], xy[-1] = (R, 0.0), (0.0, R)   # exactly on the plate's edges
    return xy


def area_deficit(poly):
    """Area of the quarter disc minus that of the polygon origin-poly (shoelace), m^2."""
    x, y = np.r_[0.0, poly[:, 0]], np.r_[0.0, poly[:, 1]]
    polygon = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    return np.pi * R ** 2 / 4 - polygon


# ---- step 1: mesh with gmsh -------------------------------------------------------------
def geo_text(poly, level):
    """The gmsh .geo of the quarter plate whose hole is the polygon poly (straight segments
    between its nodes) or, with poly None, the circle of radius R. 8-node quads."""
    h_hole, h_far = H_HOLE / 2 ** level, H_FAR / 2 ** level
    g = ["// quarter plate with a hole, unstructured 8-node quads graded from the hole",
         f"Point(1) = {{{W!r}, 0, 0}}; Point(2) = {{{W!r}, {W!r}, 0}}; Point(3) = {{0, {W!r}, 0}};",
         "Line(1) = {1, 2}; Line(2) = {2, 3};"]
    if poly is None:   # the circle: (R, 0) is point 10, (0, R) point 11, the centre 12
        g += [f"Point(10) = {{{R!r}, 0, 0}}; Point(11) = {{0, {R!r}, 0}}; Point(12) = {{0, 0, 0}};",
              "Circle(10) = {11, 12, 10};"]
        hole, last = [10], 11
    else:              # the polygon: points 10, 11, ... from (R, 0) to (0, R), lines between
        n = len(poly) - 1
        g += [f"Point({10 + i}) = {{{x!r}, {y!r}, 0}};" for i, (x, y) in enumerate(poly)]
        g += [f"Line({10 + i}) = {{{11 + i}, {10 + i}}};" for i in range(n)]   # from (0, R) back
        hole, last = [10 + i for i in range(n - 1, -1, -1)], 10 + n
    g += [f"Line(3) = {{3, {last}}}; Line(4) = {{10, 1}};",   # x = 0 from (0, W); y = 0 to (W, 0)
          f"Curve Loop(1) = {{1, 2, 3, {', '.join(map(str, hole))}, 4}};",
          "Plane Surface(1) = {1};",
          f"Field[1] = Distance; Field[1].CurvesList = {{{', '.join(map(str, hole))}}}; Field[1].NumPointsPerCurve = 200;",
          f"Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = {h_hole!r};",
          f"Field[2].SizeMax = {h_far!r}; Field[2].DistMin = 0; Field[2].DistMax = {D_GROW!r};",
          "Background Field = 2;",
          "Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0; Mesh.MeshSizeExtendFromBoundary = 0;",
          "Mesh.Algorithm = 6; Mesh.RecombinationAlgorithm = 2; Recombine Surface{1};",
          "Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;",
          'Physical Surface("plate") = {1};', ""]
    return "\n".join(g)


def mesh(work, poly, level):
    """Node ids, coordinates (n x 2) and 8-node quads (ccx order) of the plate."""
    lines = cc.gmsh(geo_text(poly, level), work, "plate")
    assert not cc.msh_elements(lines, 9), "triangles left in the full-quad mesh"
    ids, xy, elems = cc.quad8_mesh(lines)
    for col, val in ((0, 0.0), (1, 0.0), (0, W), (1, W)):   # snap gmsh's ~1e-17 m round-off
        xy[np.abs(xy[:, col] - val) < TOL, col] = val
    return ids, xy, elems


# ---- step 2: CalculiX input -------------------------------------------------------------
def node_at(ids, xy, x, y):
    k = np.nonzero((np.abs(xy[:, 0] - x) < TOL) & (np.abs(xy[:, 1] - y) < TOL))[0]
    assert len(k) == 1, (x, y, k)
    return ids[k[0]]


def write_inp(path, ids, xy, elems):
    """Plane strain CPE8, rollers on x = 0 and y = 0, traction S on x = W; prints U at (W, 0)
    and the total reactions of the rollers."""
    left = ids[np.abs(xy[:, 0]) < TOL]
    bottom = ids[np.abs(xy[:, 1]) < TOL]
    dload = cc.faces_on(ids, elems, np.abs(xy[:, 0] - W) < TOL)
    with open(path, "w") as f:
        cc.write_mesh(f, "quarter plate with a polygonal or circular hole, plane strain, CPE8",
                      ids, xy, elems, "CPE8")
        cc.write_nset(f, "NLEFT", left)
        cc.write_nset(f, "NBOT", bottom)
        cc.write_nset(f, "NPROBE", [node_at(ids, xy, W, 0.0)])
        cc.write_rollers_in_tension(f, E, NU, dload, S)
        f.write("*NODE PRINT, NSET=NPROBE\nU\n")
        f.write("*NODE PRINT, NSET=NLEFT, TOTALS=ONLY\nRF\n")
        f.write("*NODE PRINT, NSET=NBOT, TOTALS=ONLY\nRF\n")
        f.write("*END STEP\n")


# ---- step 3: solve one geometry on one mesh level ---------------------------------------
def solve(work, poly, level):
    """ux at (W, 0), the mesh size and the ccx wall time."""
    ids, xy, elems = mesh(work, poly, level)
    write_inp(os.path.join(work, "plate.inp"), ids, xy, elems)
    seconds = cc.run_ccx(work, "plate", f"level {level}")
    u, ((lx, _), (_, by)) = cc.parse_dat(os.path.join(work, "plate.dat"))
    assert abs(lx + S * W) <= 1e-6 * S * W, f"reaction on x = 0: {lx} != {-S * W}"
    assert abs(by) <= 1e-6 * S * W, f"total reaction on y = 0: {by}"
    (ux, _), = u.values()
    return dict(level=level, ux=ux, elements=len(elems), nodes=len(ids), seconds=seconds)


def converged_ux(name, poly, a):
    """ux at (W, 0) on the refinement levels (until the predicted ccx time exceeds
    a.max_seconds); prints each level and returns the rows."""
    def report(level, r):
        print(f"  {name} level {level}: {r['elements']:6d} elements {r['nodes']:7d} nodes  "
              f"ccx {r['seconds']:6.1f} s  ux(W, 0) = {r['ux']:.7e} m", flush=True)
    rows = cc.mesh_series(LEVELS, 5, a.max_seconds, lambda k: f"{name} level {k}",
                          lambda k: cc.in_work_folder(f"perinom_fem_chords_{name}_{k}_", a.keep,
                                                      f"{name}_{k}", solve, poly, k), report)
    f = [r["ux"] for r in rows]
    print(f"  {name}: relative differences between levels "
          + ", ".join(f"{d:.1e}" for d in np.diff(f) / f[-1]), flush=True)
    assert len(rows) >= 3, f"{name}: fewer than three levels ran (raise --max-seconds)"
    assert abs(f[-1] / f[-2] - 1) < CONVERGED, f"{name}: not converged"
    return rows


# ---- step 4: the three meshes, the circle, outputs --------------------------------------
def main():
    a = cc.parse_args(__doc__, max_seconds=120.0)
    circle = converged_ux("circle", None, a)
    ux_circle = circle[-1]["ux"]
    print(f"circle: ux = {ux_circle:.7e} m vs plate_hole.csv {UX_REF:.7e} m: "
          f"{ux_circle / UX_REF - 1:+.1e} relative", flush=True)
    assert abs(ux_circle / UX_REF - 1) < 1e-5, "the circle does not reproduce plate_hole.csv"
    rows = []
    for msh, perinom_err in MESHES:
        poly = hole_polygon(os.path.join(FORMULATION, msh))
        fem = converged_ux(msh[:-4], poly, a)
        ux = fem[-1]["ux"]
        effect = 100 * (ux / ux_circle - 1)
        own = 100 * ((1 + perinom_err / 100) * UX_REF / ux - 1)
        print(f"{msh}: {len(poly)} hole nodes, area deficit {area_deficit(poly):.4e} m^2, "
              f"ux polygon {ux:.7e} m, geometric effect {effect:+.4f} %, perinom "
              f"{perinom_err:+.2f} % vs the circle -> {own:+.3f} % vs its own polygon", flush=True)
        rows.append(f"{msh},{len(poly)},{area_deficit(poly):.6e},{ux:.7e},{ux_circle:.7e},{effect:.5f}")
    os.makedirs(a.out, exist_ok=True)
    cc.write_csv(os.path.join(a.out, "plate_hole_chords.csv"),
                 "mesh,hole_nodes,polygon_area_deficit,ux_polygon_fem,ux_circle_fem,geometric_effect_percent",
                 rows)
    print("wrote plate_hole_chords.csv in", a.out)


if __name__ == "__main__":
    main()
