#!/usr/bin/python3
"""The classical formulation's surface effect on a body from a mesh, against the lattice: a
uniform strain eps_xx = 1e-4 (plane stress, E = 1 GPa, nu = 0.3) imposed at the faces, which
every formulation must reproduce where it has no surface effect. The L-shaped body (2 x 2 m
with a 1 x 1 m corner cut, l_shape.geo, meshed by gmsh into triangles and into quadrilaterals
of side 0.05 m) is held in x at its left side and in y at its bottom, and its right side and
its inner step are moved along x to eps x. The lattice is a 2 x 1 m box at dx = 0.05 m, held
and moved the same way at its left, bottom and right sides. Both formulations, direct solver.

Prints a markdown table: the largest displacement and particle stress errors (over eps L and
E eps) and the reactions of the moved faces against E eps times their length.

Usage: verification/formulation/classical_mesh.py [path/to/perinom]   (about 20 seconds)
The meshes are made with gmsh when missing (python3-gmsh): l_shape_tri.msh, l_shape_quad.msh.
"""
import csv, glob, json, os, subprocess, sys

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(os.path.dirname(here))
exe = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/drivers/perinom")
work = "/tmp/perinom_classical_mesh"
E, nu, eps = 1.0e9, 0.3, 1.0e-4


def mesh(kind):
    path = os.path.join(here, "l_shape_%s.msh" % kind)
    if not os.path.exists(path):
        import gmsh
        gmsh.initialize()
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(os.path.join(here, "l_shape.geo"))
        if kind == "quad":
            gmsh.option.setNumber("Mesh.RecombineAll", 1)
        gmsh.model.mesh.generate(2)
        gmsh.write(path)
        gmsh.finalize()
    return path


SCENE = """name: {name}
dimension: 2
geometry: {geometry}
discretization: {{dx: 0.05, horizon: {{ratio: 3.015}}}}
material: {{type: linear_elastic, E: 1.0e9, nu: 0.3, density: 1000.0, plane: stress}}
model: {{formulation: {form}}}
boundary:
{boundary}
solver: {{type: direct}}
output: {{csv: true}}
"""
MESH_BOUNDARY = """  - {region: {group: left}, fix: [x], at: face}
  - {region: {group: bottom}, fix: [y], at: face}
  - {region: {group: right}, displacement: {x: 2.0e-4}, at: face}
  - {region: {group: inner}, displacement: {x: 1.0e-4}, at: face}"""
BOX_BOUNDARY = """  - {region: left, fix: [x], at: face}
  - {region: bottom, fix: [y], at: face}
  - {region: right, displacement: {x: 2.0e-4}, at: face}"""


def run(name, geometry, boundary, form, moved):
    os.makedirs(work, exist_ok=True)
    scene = os.path.join(work, name + ".yaml")
    open(scene, "w").write(SCENE.format(name=name, geometry=geometry, boundary=boundary, form=form))
    out = os.path.join(work, name)
    subprocess.run([exe, "run", scene, "--out", out], check=True, stdout=subprocess.DEVNULL)
    rows = list(csv.DictReader(open(sorted(glob.glob(os.path.join(out, name + "_0*.csv")))[-1])))
    u_err = max(max(abs(float(r["displacement_0"]) - eps * float(r["x"])),
                    abs(float(r["displacement_1"]) + nu * eps * float(r["y"]))) for r in rows) / (eps * 2.0)
    s_err = max(max(abs(float(r["stress_0"]) - E * eps), abs(float(r["stress_1"])), abs(float(r["stress_4"])))
                for r in rows) / (E * eps)
    reactions = json.load(open(os.path.join(out, "summary.json")))["reactions"]
    return len(rows), u_err, s_err, [reactions[k][0] / (E * eps * 1.0) - 1.0 for k in moved]


print("| body | formulation | particles | max u error / (eps L) | max stress error / (E eps) | moved faces' reactions |")
print("|---|---|---:|---:|---:|---|")
for label, geometry, boundary, moved in [
        ("lattice 2 x 1 m box", "{box: {min: [0.0, 0.0], max: [2.0, 1.0]}}", BOX_BOUNDARY, ["boundary.2"]),
        ("L from triangles", "{mesh: %s}" % mesh("tri"), MESH_BOUNDARY, ["boundary.2", "boundary.3"]),
        ("L from quadrilaterals", "{mesh: %s}" % mesh("quad"), MESH_BOUNDARY, ["boundary.2", "boundary.3"])]:
    for form in ("consistent", "classical"):
        n, u_err, s_err, r = run(label.split()[0] + "_" + label.split()[-1] + "_" + form, geometry, boundary, form, moved)
        print("| %s | %s | %d | %.2e | %.2e | %s |" % (label, form, n, u_err, s_err,
                                                     " / ".join("%+.2f%%" % (100 * x) for x in r)))
