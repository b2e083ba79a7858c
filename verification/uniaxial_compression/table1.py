#!/usr/bin/env python3
"""Seed 000 Table 1: the uniaxial compression plate (THEORY sec. 11) at eight discretizations,
against the CalculiX reference of verification/fem/, in four variants:
  classical        weak form everywhere, support on the bottom particle layer (seed's classical)
  improved/layer   improved formulation, support on the bottom particle layer (seed's improved)
  improved/face    improved formulation, support imposed at the bottom face (perinom's option)
  consistent/face  the default consistent formulation (operator order 2), support at the face

  m-convergence at delta = 12 mm: m = 2.015, 3.015, 4.015, 5.015 (dx = 6, 4, 3, 2.4 mm)
  delta-convergence at m = 3.015: delta = 9, 12, 15, 18 mm (dx = 3, 4, 5, 6 mm)

Errors, all along the vertical centre line x = 18 mm (where it falls between two particle
columns, the two columns are averaged row by row; the plate is symmetric about it):
  top-centre u_y   relative error of u_y at (18, 72) mm, reconstructed from the nearest
                   particle (probe top_center_uy), against the FEM value there
  top row          the top row's own u_y against the FEM value at its y = 72 mm - h/2
  L2 u_y           |u_pd - u_fem| / |u_fem| over the centre-line particles (FEM interpolated)
  L2 von Mises     the same for the von Mises stress
  oscillation      RMS of (vm_pd - vm_fem) over the particles within six layers of the loaded
                   surface, divided by the applied 200 kPa
Run:  /usr/bin/python3 verification/uniaxial_compression/table1.py build/drivers/perinom
(Debian's python3 with python3-numpy and python3-matplotlib, which scripts/install-deps.sh installs)
Writes docs/verification/uniaxial_compression.md and its PNG plots."""
import csv, json, os, subprocess, sys
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SCENE = os.path.join(ROOT, "examples", "uniaxial_compression.yaml")
FEM = os.path.join(ROOT, "verification", "fem")
DOCS = os.path.join(ROOT, "docs", "verification")
LOAD = 200e3
RUNS = [("m", 2.015, 6e-3), ("m", 3.015, 4e-3), ("m", 4.015, 3e-3), ("m", 5.015, 2.4e-3),
        ("delta", 3.015, 3e-3), ("delta", 3.015, 4e-3), ("delta", 3.015, 5e-3), ("delta", 3.015, 6e-3)]


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


VARIANTS = [("classical", "classical", "layer"), ("improved/layer", "improved", "layer"),
            ("improved/face", "improved", "face"), ("consistent/face", "consistent", "face")]


def run(exe, out, m, dx, formulation, at):
    sets = {"discretization.dx": dx, "discretization.horizon.ratio": m, "model.formulation": formulation,
            "boundary.0.at": at,
            "solver.tolerance": 1e-9, "solver.displacement_tolerance": 1e-11, "solver.max_iterations": 1000000}
    cmd = [exe, "run", SCENE, "--out", out]
    for k, v in sets.items():
        cmd += ["--set", f"{k}={v}"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    summary = json.load(open(os.path.join(out, "summary.json")))
    line = read_csv(os.path.join(out, "probe_center_line.csv"))
    # Average the two columns that straddle x = 18 mm, row by row.
    ys = np.unique(np.round(line["y"], 12))
    uy = np.array([line["uy"][np.isclose(line["y"], y)].mean() for y in ys])
    vm = np.array([line["von_mises"][np.isclose(line["y"], y)].mean() for y in ys])
    return summary, ys, uy, vm


def errors(ys, uy, vm, fem, spacing, top_probe):
    fu = np.interp(ys, fem["y_m"], fem["uy_m"])
    fv = np.interp(ys, fem["y_m"], fem["von_mises_pa"])
    top = np.interp(0.072, fem["y_m"], fem["uy_m"])
    near = ys > 0.072 - 6 * spacing
    own = np.interp(ys[-1], fem["y_m"], fem["uy_m"])
    return {"top": (top_probe - top) / abs(top), "top_own": (uy[-1] - own) / abs(own),
            "l2u": np.linalg.norm(uy - fu) / np.linalg.norm(fu),
            "l2vm": np.linalg.norm(vm - fv) / np.linalg.norm(fv),
            "osc": np.sqrt(np.mean((vm[near] - fv[near]) ** 2)) / LOAD}


def main():
    exe = os.path.abspath(sys.argv[1])
    work = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "out", "table1")
    fem = read_csv(os.path.join(FEM, "uniaxial_compression_centerline.csv"))
    os.makedirs(DOCS, exist_ok=True)
    results = []
    for study, m, dx in RUNS:
        for form, formulation, at in VARIANTS:
            out = os.path.join(work, f"{formulation}_{at}_m{m}_dx{dx*1e3:g}")
            summary, ys, uy, vm = run(exe, out, m, dx, formulation, at)
            spacing = 0.072 / round(0.072 / dx)
            e = errors(ys, uy, vm, fem, spacing, summary["probes"]["top_center_uy"])
            results.append(dict(study=study, m=m, dx=dx, delta=m * dx, form=form, ys=ys, uy=uy, vm=vm,
                                particles=summary["particles"], iterations=summary["solver"]["iterations"],
                                converged=summary["solver"]["converged"],
                                solve=summary["wall_time"]["solve"],
                                total=sum(summary["wall_time"].values()), **e))
            print(f"{study:5s} m={m} dx={dx*1e3:g} mm {form:14s}: top {e['top']*100:+.3f}% (row {e['top_own']*100:+.2f}%)  "
                  f"L2 uy {e['l2u']*100:.2f}%  L2 vm {e['l2vm']*100:.2f}%  osc {e['osc']*100:.2f}%  "
                  f"{summary['wall_time']['solve']:.2f} s", flush=True)
    plots(results, fem)
    report(results, fem)


def plots(results, fem):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fine = [r for r in results if r["study"] == "m" and r["m"] == 5.015]
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.5))
    ax[0].plot(fem["y_m"] * 1e3, fem["uy_m"] * 1e3, "k-", label="FEM (CalculiX)")
    ax[1].plot(fem["y_m"] * 1e3, fem["von_mises_pa"] / 1e3, "k-", label="FEM (CalculiX)")
    for r, style in zip(fine, ["s--", "o-", "^:"]):
        ax[0].plot(r["ys"] * 1e3, r["uy"] * 1e3, style, ms=4, label=r["form"])
        ax[1].plot(r["ys"] * 1e3, r["vm"] / 1e3, style, ms=4, label=r["form"])
    ax[0].set(xlabel="y (mm)", ylabel="u_y (mm)", title="centre line, m = 5.015, delta = 12 mm")
    ax[1].set(xlabel="y (mm)", ylabel="von Mises (kPa)", title="centre line, m = 5.015, delta = 12 mm")
    for a in ax:
        a.legend(); a.grid(alpha=0.3)
    fig.tight_layout(); fig.savefig(os.path.join(DOCS, "uniaxial_compression_profiles.png"), dpi=90)
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.5))
    for a, study in zip(ax, ["m", "delta"]):
        a.plot(fem["y_m"] * 1e3, fem["von_mises_pa"] / 1e3, "k-", label="FEM")
        for r in [r for r in results if r["study"] == study]:
            if r["form"] == "improved/face":
                continue  # the same stress field as improved/layer near the top
            a.plot(r["ys"] * 1e3, r["vm"] / 1e3, "--" if r["form"] == "classical" else "-", marker=".",
                   label=f"{r['form']} m={r['m']} dx={r['dx']*1e3:g}")
        a.set(xlim=(44, 72.5), xlabel="y (mm)", ylabel="von Mises (kPa)",
              title=f"stress near the loaded surface ({study}-convergence)")
        a.grid(alpha=0.3); a.legend(fontsize=6)
    fig.tight_layout(); fig.savefig(os.path.join(DOCS, "uniaxial_compression_oscillation.png"), dpi=90)


def report(results, fem):
    top = np.interp(0.072, fem["y_m"], fem["uy_m"])
    lines = ["# Uniaxial compression plate: seed 000 Table 1", "",
             "Generated by `/usr/bin/python3 verification/uniaxial_compression/table1.py build/drivers/perinom`; "
             "see the script's header for the definitions of the errors. FEM reference: "
             f"CalculiX, top-centre u_y = {top*1e3:.5f} mm (docs/verification/fem.md). "
             "ADR to a relative residual of 1e-9; C_hg = 0.5; weight (delta/r)^2; 2 threads.", "",
             "| study | m | dx (mm) | delta (mm) | variant | particles | top-centre u_y error | top row error | L2 u_y | L2 von Mises | oscillation (6 layers) | ADR iterations | solve (s) | total (s) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        lines.append(f"| {r['study']} | {r['m']} | {r['dx']*1e3:g} | {r['delta']*1e3:.3g} | {r['form']} | {r['particles']} | "
                     f"{r['top']*100:+.3f}% | {r['top_own']*100:+.2f}% | {r['l2u']*100:.2f}% | {r['l2vm']*100:.2f}% | {r['osc']*100:.2f}% | "
                     f"{r['iterations']}{'' if r['converged'] else ' (not converged)'} | {r['solve']:.3f} | {r['total']:.3f} |")
    pairs = {}
    for r in results:
        pairs.setdefault((r["study"], r["m"], r["dx"]), {})[r["form"]] = r
    lines += ["", "Ratio of the near-surface oscillation, classical over improved (layer support):", "",
              "| study | m | dx (mm) | ratio |", "|---|---|---|---|"]
    for (study, m, dx), p in pairs.items():
        lines.append(f"| {study} | {m} | {dx*1e3:g} | {p['classical']['osc'] / max(p['improved/layer']['osc'], 1e-30):.0f} |")
    lines += ["", "![centre-line profiles](uniaxial_compression_profiles.png)", "",
              "![stress near the loaded surface](uniaxial_compression_oscillation.png)", ""]
    with open(os.path.join(DOCS, "uniaxial_compression_table1.md"), "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
