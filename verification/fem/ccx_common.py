"""Helpers shared by the CalculiX FEM reference scripts of this folder (cantilever_2d.py,
cantilever_3d.py, plate_hole.py, lame.py, uniaxial_compression.py): running gmsh and ccx,
reading the gmsh mesh, writing the ccx input, reading the .dat and .frd results, Richardson
extrapolation, the command line, the work folders, CSV files and figures.

The scripts import it from their own folder:
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import ccx_common as cc
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

HERE = os.path.dirname(os.path.abspath(__file__))
ENV = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1",
           CCX_NPROC_RESULTS="1", CCX_NPROC_STIFFNESS="1")


# ---- command line, work folders ---------------------------------------------------------
def parse_args(doc, max_seconds=120.0, factor=6):
    """--max-seconds, --keep and --out; exits when gmsh or ccx is missing."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--max-seconds", type=float, default=max_seconds,
                    help=f"skip a mesh whose predicted ccx time ({factor} x the previous one) exceeds this "
                         f"(default {max_seconds:g})")
    ap.add_argument("--keep", help="keep the work files in this folder")
    ap.add_argument("--out", default=HERE, help="output folder (default: this script's)")
    a = ap.parse_args()
    for tool in ("gmsh", "ccx"):
        if shutil.which(tool) is None:
            sys.exit(f"{tool} not found: apt-get install gmsh calculix-ccx")
    return a


def too_slow(results, factor, max_seconds, what):
    """True (and says so) when the next mesh, predicted at factor x the last one's ccx time,
    would take longer than max_seconds."""
    if results and results[-1]["seconds"] * factor > max_seconds:
        print(f"{what} skipped: the previous mesh took {results[-1]['seconds']:.1f} s")
        return True
    return False


def mesh_series(values, factor, max_seconds, what, run, report):
    """run(v) for each mesh parameter v in turn, then report(v, result); stops before a mesh
    whose predicted ccx time (factor x the last one's) exceeds max_seconds. what(v) names the
    mesh in the message. Returns the results."""
    results = []
    for v in values:
        if too_slow(results, factor, max_seconds, what(v)):
            break
        results.append(run(v))
        report(v, results[-1])
    return results


def in_work_folder(prefix, keep, name, fn, *args):
    """fn(work, *args) in a fresh temporary folder, deleted afterwards; with keep, the folder
    is first copied to keep/name."""
    work = tempfile.mkdtemp(prefix=prefix)
    try:
        return fn(work, *args)
    finally:
        if keep:
            dst = os.path.join(keep, name)
            shutil.rmtree(dst, ignore_errors=True)
            shutil.copytree(work, dst)
        shutil.rmtree(work)


# ---- step 1: mesh with gmsh -------------------------------------------------------------
def gmsh(geo_text, work, name, dim=2):
    """Writes work/name.geo, meshes it in dim dimensions into work/name.msh (format 2.2) and
    returns the lines of the .msh file."""
    geo = os.path.join(work, name + ".geo")
    msh = os.path.join(work, name + ".msh")
    with open(geo, "w") as f:
        f.write(geo_text)
    subprocess.run(["gmsh", f"-{dim}", geo, "-o", msh, "-format", "msh22", "-v", "1"],
                   check=True, env=ENV, stdout=subprocess.DEVNULL)
    return open(msh).read().split("\n")


def msh_nodes(lines, dim):
    """Node ids and coordinates (n x dim) of a .msh 2.2 file."""
    i = lines.index("$Nodes")
    n = int(lines[i + 1])
    ids = np.empty(n, dtype=np.int64)
    xyz = np.empty((n, dim))
    for k in range(n):
        t = lines[i + 2 + k].split()
        ids[k] = int(t[0])
        xyz[k] = [float(v) for v in t[1:1 + dim]]
    return ids, xyz


def msh_elements(lines, etype):
    """The node ids of the elements of gmsh type etype (16: 8-node quad, 17: 20-node hexahedron)."""
    i = lines.index("$Elements")
    m = int(lines[i + 1])
    elems = []
    for k in range(m):
        t = [int(v) for v in lines[i + 2 + k].split()]
        if t[1] == etype:
            elems.append(t[3 + t[2]:])
    return elems


def quad8_mesh(lines):
    """Node ids, coordinates (n x 2) and 8-node quads (m x 8, node ids, ccx order, counter-
    clockwise) of a 2-D .msh 2.2 file."""
    ids, xy = msh_nodes(lines, 2)
    # gmsh and ccx both number corners 1-4, then mid-edges 12, 23, 34, 41
    elems = np.array(msh_elements(lines, 16), dtype=np.int64)
    # ccx wants counter-clockwise elements in the x-y plane
    pos = node_index(ids)
    c = np.array([[xy[pos[v]] for v in e[:4]] for e in elems])
    area2 = sum(c[:, a, 0] * c[:, (a + 1) % 4, 1] - c[:, (a + 1) % 4, 0] * c[:, a, 1] for a in range(4))
    cw = area2 < 0
    elems[cw] = elems[cw][:, [0, 3, 2, 1, 7, 6, 5, 4]]
    return ids, xy, elems


def node_index(ids):
    """{node id: row}."""
    return {nid: k for k, nid in enumerate(ids)}


# ---- step 2: CalculiX input -------------------------------------------------------------
def num(v):
    """A number for the ccx input. ccx reads a number from its first 20 characters (Fortran
    f20.0): a longer one whose first 20 characters still read as a number is silently cut.
    Python's shortest repr can be longer (a node at y = 6.135769156722633e-05 m was read as
    6.1357 m), so write 14 significant digits, which fit in 20 characters with the sign."""
    return f"{v:.13e}"


def faces_on(ids, elems, on):
    """(element id, face number) of the quad faces whose two corners are both on (a boolean
    per node row): CPE8 face k (P1..P4) joins corners k and k+1."""
    pos = node_index(ids)
    faces = []
    for eid, e in enumerate(elems, start=1):
        for k in range(4):
            if on[pos[e[k]]] and on[pos[e[(k + 1) % 4]]]:
                faces.append((eid, k + 1))
    return faces


def write_mesh(f, heading, ids, coords, elems, etype, fmt=num):
    """The *HEADING, *NODE (NALL; z = 0.0 for 2-D coordinates) and *ELEMENT (EALL) blocks."""
    f.write(f"*HEADING\n{heading}\n*NODE, NSET=NALL\n")
    for nid, p in zip(ids, coords):
        f.write(f"{nid}, " + ", ".join(fmt(v) for v in p) + (", 0.0\n" if len(p) == 2 else "\n"))
    f.write(f"*ELEMENT, TYPE={etype}, ELSET=EALL\n")
    for eid, e in enumerate(elems, start=1):
        s = [str(v) for v in e]
        if len(s) > 15:   # ccx: at most 16 entries on the first line
            f.write(f"{eid}, " + ", ".join(s[:15]) + ",\n" + ", ".join(s[15:]) + "\n")
        else:
            f.write(f"{eid}, " + ", ".join(s) + "\n")


def write_nset(f, name, nodes):
    f.write(f"*NSET, NSET={name}\n" + "".join(f"{v},\n" for v in nodes))


def write_rollers_in_tension(f, e_mod, nu, faces, traction):
    """A unit-thickness isotropic plate held by rollers on NLEFT (x) and NBOT (y), and the
    opening of its static step: the traction pulling the element faces (a negative *DLOAD
    pressure). The caller adds its outputs and *END STEP."""
    f.write(f"*MATERIAL, NAME=M\n*ELASTIC\n{num(e_mod)}, {num(nu)}\n")
    f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=M\n1.0\n")
    f.write("*BOUNDARY\nNLEFT, 1, 1, 0.0\nNBOT, 2, 2, 0.0\n")
    f.write("*STEP\n*STATIC\n*DLOAD\n")
    for eid, face in faces:
        f.write(f"{eid}, P{face}, {num(-traction)}\n")   # negative pressure = tension


# ---- step 3: run ccx, read .dat and .frd ------------------------------------------------
def run_ccx(work, job, what):
    """Runs ccx on work/job.inp; returns its wall time in seconds, exits on failure."""
    t0 = time.time()
    r = subprocess.run(["ccx", "-i", job], cwd=work, env=ENV,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    seconds = time.time() - t0
    if r.returncode != 0 or "ERROR" in r.stdout:
        sys.exit(f"ccx failed for {what}:\n{r.stdout[-3000:]}")
    return seconds


def parse_dat(path, ncomp=2):
    """Displacements {node: (ux, uy[, uz])} (ncomp components) and the total reactions
    [(fx, fy[, fz]), ...] in print order."""
    u, totals = {}, []
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
            u[int(t[0])] = tuple(float(v) for v in t[1:1 + ncomp])
        elif mode == "rf":
            totals.append(tuple(float(v) for v in t[:ncomp]))
            mode = None
    return u, totals


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


# ---- convergence ------------------------------------------------------------------------
def richardson(f1, f2, f3, p=None):
    """Richardson extrapolation of three values on meshes refined by 2 (coarse, medium, fine):
    observed order p (unless given) and the limit."""
    if p is None:
        p = np.log((f1 - f2) / (f2 - f3)) / np.log(2.0)
    return p, f3 + (f3 - f2) / (2 ** p - 1)


def richardson_monotone(f1, f2, f3, p=None):
    """richardson(), except that without a clean monotone convergence (differences of
    opposite signs, an observed order below 0.5, or a last difference at the round-off of the
    printed digits) it returns p = nan and the finest value."""
    if p is None:
        d1, d2 = f1 - f2, f2 - f3
        if d2 == 0 or d1 / d2 < 2 ** 0.5 or abs(d2) <= 3e-7 * abs(f3):
            return np.nan, f3
        p = np.log(d1 / d2) / np.log(2.0)
    return p, f3 + (f3 - f2) / (2 ** p - 1)


def corner_exponent(kappa):
    """Williams' exponent lambda (u ~ r^lambda) of a 90-degree corner between a fixed and a free
    edge: kappa sin^2(lambda pi/2) = (1 + kappa)^2/4 - lambda^2, with kappa = 3 - 4 nu in plane
    strain and (3 - nu)/(1 + nu) in plane stress. The pollution it causes in a point
    displacement converges like h^(2 lambda)."""
    k = kappa
    f = lambda l: k * np.sin(l * np.pi / 2) ** 2 - (1 + k) ** 2 / 4 + l ** 2
    a, b = 0.5, 0.99
    for _ in range(60):
        m = (a + b) / 2
        a, b = (a, m) if f(a) * f(m) <= 0 else (m, b)
    return m


# ---- outputs ----------------------------------------------------------------------------
def mesh_columns(r):
    """The h_m, elements, nodes columns of a result row."""
    return f"{r['h']:.6g},{r['elements']},{r['nodes']}"


def write_csv(path, header, rows):
    with open(path, "w") as f:
        f.write(header + "\n")
        for row in rows:
            f.write(row + "\n")


def figure(ncols):
    """A figure of ncols axes side by side, 960 x 360 pixels (matplotlib, Agg backend)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt.subplots(1, ncols, figsize=(9.6, 3.6), dpi=100)


def save_figure(fig, axes, path):
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path)
