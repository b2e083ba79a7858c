#!/usr/bin/python3
"""Kalthoff-Winkler impact (issue 17): examples/kalthoff_winkler.yaml, a 100 x 200 mm plate of
maraging steel in plane strain (E = 190 GPa, nu = 0.25, rho = 8000) with two 50 mm edge notches
50 mm apart (precracks on y = +-25 mm from the impacted edge x = 0 to x = 50 mm), the outer
particle layer of the strip |y| < 25 mm moved in x at 32 m/s, to t = 90 us; classical
formulation, horizon 3.015 dx. The experiment's cracks leave the notch tips at about 70 degrees
to the notch (the issue asks for 65-72).

Parameters, the same for every criterion and every run (nothing tuned to a case):
- G_c = 22170 J/m^2, the value of the peridynamic Kalthoff-Winkler studies (Peridynamics.jl's
  tutorial states it beside E = 191 GPa, rho = 8000).
- stretch: s_c = sqrt(5 pi G_c / (12 E delta)), Ha and Bobaru's critical stretch for 2-D plane
  strain (bond-based, nu = 1/4, the nu used here), at each run's horizon delta = 3.015 dx.
- instability: s_max = that same s_c (no source gives an arming stretch for this steel).
- stress: f_t = sqrt(27 E G_c / (256 l0)) = 1.07 GPa, the AT2 phase-field critical stress with
  l0 = 0.39 mm, Borden et al. 2012's length for this benchmark (as the SENT stress test takes its
  benchmark's phase-field strength).

What is measured, from the final state's damage field (the last good state for a run the
guards stopped): the crack leaving each notch tip, as the damage-weighted mean direction in
rings of width dx around the tip (radius from the horizon to 30 mm), on the side of the notch
away from the strip, of the particles with damage > 0.3 connected to the tip (the rows along
the notch excluded; the connection may run through the strip); the angle is that of the
straight line fitted through the ring points, from the x axis (the notch and the impact
direction), positive away from the strip; the lower tip is mirrored; no angle when the crack
reaches less than 10 mm. In a field that has fragmented this is the direction of the
damaged region, not of a crack: see the figure. Also: particles with
damage > 0.3 inside the impacted strip (x < 60 mm, |y| < 25 mm - 2 dx; the experiment has
none); exit code; time reached; bonds broken; particles detached (summary.json); the energy
balance |total_energy| / max external_work (history.csv; total = kinetic + strain + released
- work); max |u| over v t and the largest particle speed between the last two snapshots (a
detached particle flying off shows in both); wall time.

Runs, all at 0.8 of the intact stable step (the default `solver.safety`) unless said, for
90 us / dt steps (perinom lowers dt with the stable step after breaks, so a run can end
earlier; the table says when):
(1) each criterion at dx = 1, 0.625 and 0.5 mm, C_hg = 0.5; (2) the stability stress test at
dx = 1 mm: each criterion with C_hg = 0, 0.5, 2; (3) the C_hg = 0.5 runs of (2) again at 0.2 of
the stable step, to see how much the path depends on the step; (4) the three criteria at
16.5 m/s (the impedance-matched interface speed of a 32 m/s projectile of the same steel, which
FE and phase-field studies impose), dx = 1 mm, C_hg = 0.5.

Usage: verification/fracture/kalthoff.py [path/to/perinom] [--quick]   (--quick: dx = 1 mm only)
Writes docs/verification/kalthoff.md and kalthoff.png (Debian's python3 with numpy, matplotlib,
vtk); about 12 minutes on 2 cores."""
import csv, json, math, os, re, subprocess, sys, time
from collections import deque
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SCENE = os.path.join(ROOT, "examples", "kalthoff_winkler.yaml")
DOCS = os.path.join(ROOT, "docs", "verification")
E, G_C, L0, RATIO = 190e9, 22170.0, 0.39e-3, 3.015
V, T_END = 32.0, 90e-6
TIP = (0.05, 0.025)  # the upper notch tip (m); the lower one is its mirror
F_T = float(f"{math.sqrt(27 * E * G_C / (256 * L0)):.4g}")  # 1.067e9 Pa, as in the example
SAFETY = 0.8  # the default fraction of the stable step
DAMAGED, R_MAX, R_MEASURED = 0.3, 0.03, 0.01  # damage threshold, ring radii (m), shortest crack measured


def s_c(dx):
    return math.sqrt(5 * math.pi * G_C / (12 * E * RATIO * dx))


def criteria(dx):
    return [("instability", "s_max", s_c(dx)), ("stretch", "s_c", s_c(dx)), ("stress", "f_t", F_T)]


def snapshots(folder):
    """(time, x, u, damage) of the last two snapshots of the run's .pvd."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    pvd = open(os.path.join(folder, "kalthoff_winkler.pvd")).read()
    sets = dict((float(t), f) for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', pvd))
    out = []
    for t, f in sorted(sets.items())[-2:]:
        r = vtk.vtkXMLUnstructuredGridReader()
        r.SetFileName(os.path.join(folder, f))
        r.Update()
        g = r.GetOutput()
        pd = g.GetPointData()
        out.append((t, vtk_to_numpy(g.GetPoints().GetData())[:, :2].copy(),
                    vtk_to_numpy(pd.GetArray("displacement"))[:, :2].copy(), vtk_to_numpy(pd.GetArray("damage")).copy()))
    return out


def crack_branches(x, d, dx, sign):
    """The cracks leaving the notch tip at (TIP[0], sign * TIP[1]) on the side away from the strip,
    each a list of ring points (r, theta), theta from the x axis toward sign * y: the damaged
    particles connected to the tip on either side (a crack may reach that side through the
    strip), split in each ring into angular clusters, which continue the nearest branch or fork."""
    X, Y = x[:, 0] - TIP[0], sign * x[:, 1] - TIP[1]
    i = np.rint((x[:, 0] - x[:, 0].min()) / dx).astype(int)
    j = np.rint((x[:, 1] - x[:, 1].min()) / dx).astype(int)
    grid = -np.ones((i.max() + 1, j.max() + 1), int)
    grid[i, j] = np.arange(len(x))
    ok = (d > DAMAGED) & ~((X < 0) & (np.abs(Y) < dx))  # not the rows along the notch
    seen = ok & (np.hypot(X, Y) < 2.5 * dx)
    queue = deque(np.flatnonzero(seen))
    while queue:  # flood fill over the lattice's 8 neighbours
        k = queue.popleft()
        for a in (-1, 0, 1):
            for b in (-1, 0, 1):
                ii, jj = i[k] + a, j[k] + b
                if 0 <= ii < grid.shape[0] and 0 <= jj < grid.shape[1]:
                    m = grid[ii, jj]
                    if m >= 0 and ok[m] and not seen[m]:
                        seen[m] = True
                        queue.append(m)
    r, th = np.hypot(X, Y), np.arctan2(Y, X)
    branches = []
    for r0 in np.arange(RATIO * dx, R_MAX, dx):
        ring = np.flatnonzero(seen & (Y > 0) & (r >= r0) & (r < r0 + dx))  # the side away from the strip
        ring = ring[np.argsort(th[ring])]
        rc, grown = r0 + dx / 2, set()
        for c in np.split(ring, np.flatnonzero(np.diff(th[ring]) * r0 > 2 * dx) + 1) if len(ring) else []:
            t = math.atan2(np.sum(d[c] * np.sin(th[c])), np.sum(d[c] * np.cos(th[c])))
            gap = [math.dist((rc * math.cos(t), rc * math.sin(t)), (b[-1][0] * math.cos(b[-1][1]), b[-1][0] * math.sin(b[-1][1])))
                   - (rc - b[-1][0]) for b in branches]
            k = int(np.argmin(gap)) if branches else -1
            if k < 0 or gap[k] > 3 * dx:
                branches.append([(rc, t)])
            elif k in grown:  # a fork: the new branch shares the path so far
                branches.append(branches[k][:-1] + [(rc, t)])
            else:
                branches[k].append((rc, t))
                grown.add(k)
    return [np.array(b) for b in branches]


def crack_angle(points):
    """Angle (degrees from x) of the line fitted through a branch's ring points, and its reach (m)."""
    if len(points) < 3 or points[-1, 0] < R_MEASURED:
        return float("nan"), (points[-1, 0] if len(points) else 0.0)
    P = np.column_stack([points[:, 0] * np.cos(points[:, 1]), points[:, 0] * np.sin(points[:, 1])])
    v = np.linalg.svd(P - P.mean(axis=0))[2][0]
    if v @ (P[-1] - P[0]) < 0:
        v = -v
    return math.degrees(math.atan2(v[1], v[0])), points[-1, 0]


def measured_cracks(x, d, dx, sign):
    """The branches that reach R_MEASURED, longest first (the first is the crack reported), as
    (angle, reach, points); and the reach of the longest branch."""
    found = sorted(((*crack_angle(b), b) for b in crack_branches(x, d, dx, sign)), key=lambda c: (-c[1], -len(c[2])))
    return [c for c in found if not math.isnan(c[0])], (found[0][1] if found else 0.0)


def stable_step(exe, dx, work):
    """The intact stable step perinom takes at spacing dx (one step of the scene)."""
    out = os.path.join(work, f"stable_{dx:g}")
    subprocess.run([exe, "run", SCENE, "--out", out, "--set", f"discretization.dx={dx}", "--set", "solver.steps=1"] +
                   sum([["--set", f"{k}={v}"] for k, v in geometry_sets(dx).items()], []),
                   check=True, stdout=subprocess.DEVNULL, env=dict(os.environ, OMP_WAIT_POLICY="PASSIVE"))
    return json.load(open(os.path.join(out, "summary.json")))["solver"]["stable_time_step"]


def geometry_sets(dx):
    strip = f"{{box: {{min: [0.0, -0.025], max: [{dx}, 0.025]}}}}"  # the outer layer of the strip
    return {"precracks.0.from": f"[{-dx}, 0.025]", "precracks.1.from": f"[{-dx}, -0.025]",
            "boundary.0.region": strip, "boundary.1.region": strip}


def run(exe, criterion, key, value, dx, c_hg, safety, stable, work, v=V):
    dt = safety * stable
    steps = int(math.ceil(T_END / dt))
    out = os.path.join(work, f"{criterion}_dx{dx * 1e3:g}_c{c_hg:g}_s{safety:g}_v{v:g}")
    sets = {"discretization.dx": dx, "solver.dt": dt, "solver.steps": steps, "output.vtk_every": max(1, steps // 10),
            "solver.history_every": max(1, steps // 400), "model.stabilization": c_hg,
            "damage": f"{{criterion: {criterion}, {key}: {value}}}", "boundary.1.velocity": f"{{x: {v}}}"}
    sets.update(geometry_sets(dx))
    cmd = [exe, "run", SCENE, "--out", out] + sum([["--set", f"{k}={x}"] for k, x in sets.items()], [])
    t0 = time.time()
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                       env=dict(os.environ, OMP_WAIT_POLICY="PASSIVE"))
    row = dict(criterion=criterion, key=key, value=value, dx=dx, c_hg=c_hg, safety=safety, dt=dt, steps=steps, v=v,
               code=p.returncode, wall=time.time() - t0, why=(p.stderr.strip().splitlines() or [""])[-1])
    if p.returncode not in (0, 3):  # bad input or a crash: nothing to measure
        return row
    rows = list(csv.DictReader(open(os.path.join(out, "history.csv"))))
    work_ = max(abs(float(r["external_work"])) for r in rows)
    row.update(t_end=float(rows[-1]["time"]), broken=int(float(rows[-1]["broken_bonds"])),
               balance=abs(float(rows[-1]["total_energy"])) / max(work_, 1e-300), work=work_,
               released=float(rows[-1]["released_energy"]))
    summary = json.load(open(os.path.join(out, "summary.json")))
    row["t_end"] = summary["solver"].get("end_time", row["t_end"])
    row["detached"] = summary["solver"].get("fracture", {}).get("detached_particles", -1)
    snaps = snapshots(out)
    t, x, u, d = snaps[-1]
    row["finite"] = bool(np.all(np.isfinite(u)))
    row["u_ratio"] = float(np.max(np.linalg.norm(u, axis=1))) / (v * max(t, 1e-300))
    row["speed"] = (float(np.max(np.linalg.norm(u - snaps[0][2], axis=1))) / (t - snaps[0][0])
                    if len(snaps) == 2 and t > snaps[0][0] else float("nan"))
    row["x"], row["d"] = x, d
    row["cracks"], row["angles"], row["reach"] = [], [], []
    for sign in (1, -1):
        cracks, reach = measured_cracks(x, d, dx, sign)
        row["cracks"].append(cracks)
        row["angles"].append(cracks[0][0] if cracks else float("nan"))
        row["reach"].append(reach)
    strip = (x[:, 0] < 0.06) & (np.abs(x[:, 1]) < 0.025 - 2 * dx)
    row["strip"] = int(np.sum(strip & (d > DAMAGED)))
    return row


def passes(r):
    return (r["code"] == 0 and r.get("finite", False) and r.get("u_ratio", 1e9) < 5 and r.get("speed", 1e9) < 10 * r["v"]
            and r.get("balance", 1.0) < 0.01)


def fmt_angle(r):
    if "angles" not in r:
        return "-"
    return " / ".join("-" if math.isnan(a) else f"{a:.1f}" for a in r["angles"])


def fmt_branches(r):
    if "cracks" not in r:
        return "-"
    return " / ".join(", ".join(f"{a:.0f}" for a, _, _ in cracks) or "-" for cracks in r["cracks"])


def table(rows, with_stability):
    names = (["criterion", "dx (mm)", "C_hg", "dt / stable", "exit", "t reached (us)", "angle upper / lower (deg)",
              "all branches (deg)", "crack reach (mm)", "damaged in the strip", "bonds broken", "detached", "released (J)",
              "energy balance / max work", "max \\|u\\| / v t", "max speed (m/s)"] + (["passes"] if with_stability else [])
             + ["wall (s)"])
    lines = ["| " + " | ".join(names) + " |", "|" + "---|" * len(names)]
    for r in rows:
        if "balance" not in r:
            lines.append(f"| {r['criterion']} | {r['dx'] * 1e3:g} | {r['c_hg']:g} | {r['safety']:g} | {r['code']} | "
                         + "- | " * 11 + ("NO | " if with_stability else "") + f"{r['wall']:.1f} |")
            continue
        speed = "-" if math.isnan(r["speed"]) else f"{r['speed']:.0f}"  # one snapshot only
        lines.append(
            f"| {r['criterion']} | {r['dx'] * 1e3:g} | {r['c_hg']:g} | {r['safety']:g} | {r['code']} | "
            f"{r['t_end'] * 1e6:.1f} | {fmt_angle(r)} | {fmt_branches(r)} | "
            f"{r['reach'][0] * 1e3:.0f} / {r['reach'][1] * 1e3:.0f} | "
            f"{r['strip']} | {r['broken']} | {r['detached']} | {r['released']:.3g} | {100 * r['balance']:.2f}% | "
            f"{r['u_ratio']:.2f} | {speed} |" + (f" {'yes' if passes(r) else 'NO'} |" if with_stability else "")
            + f" {r['wall']:.1f} |")
    return lines


def figure(grid, path):
    """Damage maps, one row of runs per spacing, the measured branches and 65 and 72 degrees."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(grid), len(grid[0]), figsize=(3.0 * len(grid[0]) + 1, 5.2 * len(grid)), squeeze=False,
                             constrained_layout=True)
    sc = None
    for row_axes, rows in zip(axes, grid):
        for ax, r in zip(row_axes, rows):
            ax.set_aspect("equal")
            ax.set_xlim(0, 100)
            ax.set_ylim(-100, 100)
            if "x" not in r:
                ax.set_title(f"{r['criterion']}, dx = {r['dx'] * 1e3:g} mm: exit {r['code']}", fontsize=9)
                continue
            x, dx = r["x"], r["dx"]  # the particles are a lattice: show the damage as an image
            i = np.rint((x[:, 0] - x[:, 0].min()) / dx).astype(int)
            j = np.rint((x[:, 1] - x[:, 1].min()) / dx).astype(int)
            image = np.full((j.max() + 1, i.max() + 1), np.nan)
            image[j, i] = r["d"]
            sc = ax.imshow(image, origin="lower", extent=(0, 100, -100, 100), cmap="viridis", vmin=0, vmax=1,
                           interpolation="nearest")
            for sign, cracks in zip((1, -1), r["cracks"]):
                for n, (_, _, pts) in enumerate(cracks):  # the crack reported in red, other branches in orange
                    px = TIP[0] + pts[:, 0] * np.cos(pts[:, 1])
                    py = sign * (TIP[1] + pts[:, 0] * np.sin(pts[:, 1]))
                    ax.plot(px * 1e3, py * 1e3, ".", color="red" if n == 0 else "orange", markersize=2)
                for ref in (65, 72):
                    a = math.radians(ref)
                    ax.plot([50, 50 + 45 * math.cos(a)], [sign * 25, sign * (25 + 45 * math.sin(a))], "w--", linewidth=0.6)
            ax.set_title(f"{r['criterion']}, dx = {r['dx'] * 1e3:g} mm\n{fmt_angle(r)} deg, t = {r['t_end'] * 1e6:.0f} us",
                         fontsize=9)
            ax.set_xlabel("x (mm)")
        row_axes[0].set_ylabel("y (mm)")
    if sc is not None:
        fig.colorbar(sc, ax=axes.ravel().tolist(), shrink=0.5, label="damage")
    fig.savefig(path, dpi=130)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    exe = args[0] if args else os.path.join(ROOT, "build", "drivers", "perinom")
    spacings = [1e-3] if "--quick" in sys.argv else [1e-3, 0.625e-3, 0.5e-3]
    work = "/tmp/perinom_kalthoff"
    os.makedirs(work, exist_ok=True)
    stable = {dx: stable_step(exe, dx, work) for dx in spacings}
    # 1. The angles: every criterion at each spacing, C_hg = 0.5.
    angles = [run(exe, c, k, v, dx, 0.5, SAFETY, stable[dx], work) for dx in spacings for c, k, v in criteria(dx)]
    # 2. The stability stress test at dx = 1 mm (the C_hg = 0.5 runs are step 1's).
    done = {(r["criterion"], r["dx"], r["c_hg"]): r for r in angles}
    sweep = [done.get((c, 1e-3, c_hg)) or run(exe, c, k, v, 1e-3, c_hg, SAFETY, stable[1e-3], work)
             for c, k, v in criteria(1e-3) for c_hg in (0.0, 0.5, 2.0)]
    # 3. A quarter of the step.
    small = [run(exe, c, k, v, 1e-3, 0.5, 0.2, stable[1e-3], work) for c, k, v in criteria(1e-3)]
    # 4. The impedance-matched interface speed.
    slow = [run(exe, c, k, v, 1e-3, 0.5, SAFETY, stable[1e-3], work, v=16.5) for c, k, v in criteria(1e-3)]

    params = ", ".join(f"dx = {dx * 1e3:g} mm: s_c = s_max = {s_c(dx):.5f}, stable step {stable[dx]:.4g} s" for dx in spacings)
    lines = ["# Kalthoff-Winkler impact", "",
             "Generated by `/usr/bin/python3 verification/fracture/kalthoff.py` on `examples/kalthoff_winkler.yaml`: a "
             "100 x 200 mm maraging-steel plate in plane strain (E = 190 GPa, nu = 0.25, rho = 8000), two 50 mm edge "
             "notches 50 mm apart (precracks), the outer particle layer of the strip between them moved at 32 m/s, to "
             f"t = {T_END * 1e6:g} us; classical formulation, horizon 3.015 dx, time step 0.8 of the intact stable step "
             "(the default) unless said, lowered by perinom with the stable step after breaks, so that the runs of "
             f"{T_END * 1e6:g} us / dt steps end earlier ('t reached'). G_c = {G_C:g} J/m^2 for every criterion: stretch s_c = sqrt(5 pi G_c / (12 E "
             "delta)) (Ha and Bobaru, 2-D plane strain, w = 1; `damage.G_c` with this scene's inverse-square weight gives "
             f"1.22 times more), instability s_max = the same s_c, stress f_t = sqrt(27 E G_c / (256 l0)) = "
             f"{F_T / 1e9:.3f} GPa (l0 = 0.39 mm, Borden et al. 2012); {params}. See the script for how the cracks "
             "are traced: the angle is that of the longest branch leaving the tip, from the x axis (the notch), "
             "positive away from the strip, the lower tip mirrored; 'all branches' lists every branch reaching 10 mm. "
             "The experiment shows about 70 degrees, the issue asks for 65-72. "
             "'damaged in the strip': particles with damage > 0.3 in x < 60 mm, |y| < 25 mm - 2 dx (the experiment "
             "has none). A run passes the stability test when it ends with exit 0, finite fields, max |u| below 5 v t, "
             "no particle faster than 10 v between the last two snapshots, and an energy balance below 1% of the "
             "largest external work. The strip is first held in x, then given its velocity (the example's comment says "
             "why). 'released' is the strain energy the breaks released (negative: breaking raised the strain energy). "
             "The angle of a fragmented field is the direction of the damaged region, not of a crack; see the "
             "figure.", "",
             "## Crack angles (C_hg = 0.5)", ""] + table(angles, False)
    lines += ["", "![damage at the end of the runs above, a row per spacing; red: the ring points of the crack "
              "reported, orange: other branches; white: 65 and 72 degrees](kalthoff.png)", "",
              "## Stability stress test (dx = 1 mm)", ""] + table(sweep, True)
    lines += ["", "## At 0.2 of the stable step (dx = 1 mm, C_hg = 0.5)", ""] + table(small, True)
    lines += ["", "## At 16.5 m/s (dx = 1 mm, C_hg = 0.5)", ""] + table(slow, True)
    stopped = [r for r in angles + sweep + small + slow if r["code"] != 0]
    if stopped:
        lines += ["", "Runs that stopped:", ""]
        seen = set()
        for r in stopped:
            tag = (r["criterion"], r["dx"], r["c_hg"], r["safety"], r["v"])
            if tag not in seen:
                seen.add(tag)
                why = r["why"].replace("perinom: solve failed: ", "").split(" (the discrete problem")[0]
                lines.append(f"- {r['criterion']}, dx = {r['dx'] * 1e3:g} mm, C_hg = {r['c_hg']:g}, {r['safety']:g} of the "
                             f"stable step, {r['v']:g} m/s: {why}")
    with open(os.path.join(DOCS, "kalthoff.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    figure([[r for r in angles if r["dx"] == dx] for dx in spacings], os.path.join(DOCS, "kalthoff.png"))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
