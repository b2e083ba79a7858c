#!/usr/bin/python3
"""Work against precision: ADR at several tolerances against Newton (KINSOL + UMFPACK; on the
plate also Newton through PETSc with MUMPS and with GAMG, solver.linear_solver), on
  - the uniaxial compression plate (examples/uniaxial_compression.yaml, 2-D, dx = 1 mm), with
    errors against the converged Newton answer and against the CalculiX reference;
  - a 3-D column 12 x 12 x 24 mm under 200 kPa, bottom fixed at its face (horizon ratio 2.015,
    dx = 1 mm, the improved formulation, which PETSc's Newton refuses: its constraints are
    collocated), with errors against Newton (no 3-D FEM reference is committed yet).
Errors: relative L2 of u_y along the centre line (probe center_line) against Newton's, and the
top-centre u_y against CalculiX (2-D). Times: the solve phase of summary.json (setup excluded,
it is common to both). Run:
  /usr/bin/python3 verification/work_precision/work_precision.py build/drivers/perinom
Writes docs/verification/work_precision.md and work_precision.png."""
import csv, json, os, subprocess, sys, tempfile
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
DOCS = os.path.join(ROOT, "docs", "verification")
FEM_TOP = -0.4466475e-3
TOLERANCES = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
COLUMN_3D = """name: column3d
dimension: 3
geometry: {box: {min: [0, 0, 0], max: [0.012, 0.012, 0.024]}}
discretization: {dx: 0.001, horizon: {ratio: 2.015}}
material: {type: linear_elastic, E: 30.0e6, nu: 0.25, density: 2000}
model: {formulation: improved, stabilization: 0.5}
boundary:
  - {region: bottom, fix: [x, y, z], at: face}
  - {region: top, pressure: 200.0e3}
solver: {type: adr, max_iterations: 1000000}
probes:
  - {name: top_center_uz, point: [0.006, 0.006, 0.024], component: z, reconstruct: true}
  - {name: center_line, line: {from: [0.0055, 0.0055, 0.0], to: [0.0055, 0.0055, 0.024]}, component: z}
"""


def line_u(out):
    with open(os.path.join(out, [f for f in os.listdir(out) if f.startswith("probe_center_line")][0])) as f:
        rows = list(csv.DictReader(f))
    return np.array([float(r["value"]) for r in rows])


def run(exe, scene, out, sets):
    cmd = [exe, "run", scene, "--out", out]
    for k, v in sets.items():
        cmd += ["--set", f"{k}={v}"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    s = json.load(open(os.path.join(out, "summary.json")))
    top = [v for k, v in s["probes"].items() if k.startswith("top_center")][0]
    return s, top, line_u(out)


def study(exe, name, scene, work, fem_top=None, petsc=False):
    newton, ntop, nline = run(exe, scene, os.path.join(work, name + "_newton"), {"solver.type": "newton"})
    rows = [dict(solver="newton", tol=newton["solver"]["residual"], iters=newton["solver"]["iterations"],
                 time=newton["wall_time"]["solve"], err_newton=0.0,
                 err_fem=None if fem_top is None else abs(ntop - fem_top) / abs(fem_top))]
    for linear in (("mumps", "gamg") if petsc else ()):
        s, top, line = run(exe, scene, os.path.join(work, f"{name}_newton_{linear}"),
                           {"solver.type": "newton", "solver.linear_solver": linear})
        rows.append(dict(solver=f"newton ({linear})", tol=s["solver"]["residual"], iters=s["solver"]["iterations"],
                         time=s["wall_time"]["solve"], err_newton=np.linalg.norm(line - nline) / np.linalg.norm(nline),
                         err_fem=None if fem_top is None else abs(top - fem_top) / abs(fem_top)))
        print(f"{name}: Newton ({linear}) {rows[-1]['time']:.3f} s, error vs Newton {rows[-1]['err_newton']:.2e}", flush=True)
    for tol in TOLERANCES:
        s, top, line = run(exe, scene, os.path.join(work, f"{name}_adr_{tol:g}"),
                           {"solver.type": "adr", "solver.tolerance": tol,
                            "solver.displacement_tolerance": tol * 1e-2, "solver.max_iterations": 1000000})
        rows.append(dict(solver="adr", tol=tol, iters=s["solver"]["iterations"], time=s["wall_time"]["solve"],
                         err_newton=np.linalg.norm(line - nline) / np.linalg.norm(nline),
                         err_fem=None if fem_top is None else abs(top - fem_top) / abs(fem_top)))
        print(f"{name}: ADR tol {tol:g}: {s['solver']['iterations']} it, {s['wall_time']['solve']:.3f} s, "
              f"error vs Newton {rows[-1]['err_newton']:.2e}", flush=True)
    print(f"{name}: Newton {rows[0]['iters']} it, {rows[0]['time']:.3f} s", flush=True)
    return dict(name=name, particles=newton["particles"], bonds=newton["bonds"], rows=rows)


def main():
    exe = os.path.abspath(sys.argv[1])
    work = tempfile.mkdtemp(prefix="perinom_wp_")
    scene3d = os.path.join(work, "column3d.yaml")
    open(scene3d, "w").write(COLUMN_3D)
    studies = [study(exe, "plate2d", os.path.join(ROOT, "examples", "uniaxial_compression.yaml"), work, FEM_TOP, petsc=True),
               study(exe, "column3d", scene3d, work)]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for ax, st in zip(axes, studies):
        adr = [r for r in st["rows"] if r["solver"] == "adr"]
        ax.loglog([r["time"] for r in adr], [max(r["err_newton"], 1e-16) for r in adr], "o-", label="ADR vs Newton")
        if adr[0]["err_fem"] is not None:
            ax.loglog([r["time"] for r in adr], [r["err_fem"] for r in adr], "s--", label="ADR vs CalculiX (top-centre)")
            ax.axhline(st["rows"][0]["err_fem"], color="gray", ls=":", label="Newton vs CalculiX")
        ax.axvline(st["rows"][0]["time"], color="k", label="Newton (UMFPACK) solve time")
        for r, style in zip([r for r in st["rows"] if r["solver"].startswith("newton (")], ("--", "-.")):
            ax.axvline(r["time"], color="k", ls=style, label=f"{r['solver']} solve time")
        for r in adr:
            ax.annotate(f"{r['tol']:g}", (r["time"], max(r["err_newton"], 1e-16)), fontsize=7)
        ax.set(xlabel="solve time (s)", ylabel="relative error", title=f"{st['name']}: {st['particles']} particles")
        ax.grid(alpha=0.3, which="both"); ax.legend(fontsize=7)
    fig.tight_layout(); fig.savefig(os.path.join(DOCS, "work_precision.png"), dpi=90)
    lines = ["# Work against precision: ADR and Newton", "",
             "On the plate, Newton also through PETSc (`solver.linear_solver: mumps`, `gamg`; at 10^5 particles "
             "and more see docs/performance.md). The column uses the improved formulation, which they refuse.", "",
             "Generated by `/usr/bin/python3 verification/work_precision/work_precision.py build/drivers/perinom`; "
             "see the script's header. 2 threads; solve phase only (setup is common to both).", ""]
    for st in studies:
        lines += [f"## {st['name']} ({st['particles']} particles, {st['bonds']} bonds)", "",
                  "| solver | tolerance | iterations | solve (s) | error vs Newton | error vs CalculiX (top-centre) |",
                  "|---|---|---|---|---|---|"]
        for r in st["rows"]:
            fem = "-" if r["err_fem"] is None else f"{r['err_fem']:.2e}"
            tol = f"(residual {r['tol']:.1e})" if r["solver"].startswith("newton") else f"{r['tol']:g}"
            lines.append(f"| {r['solver']} | {tol} | {r['iters']} | {r['time']:.3f} | {r['err_newton']:.2e} | {fem} |")
        lines.append("")
    lines += ["![work-precision](work_precision.png)", ""]
    open(os.path.join(DOCS, "work_precision.md"), "w").write("\n".join(lines))


if __name__ == "__main__":
    main()
