#!/usr/bin/python3
"""The notched concrete beam of Gregoire, Rojas-Solano and Pijaudier-Cabot (2013) on a load path
(issue 18): examples/notched_beam.yaml, 175 x 50 mm, 50 mm thick, span 125 mm,
a 25 mm notch at mid-span (a precrack), plane stress, E = 37 GPa, nu = 0.2, the stress
criterion with f_t = 3.9 MPa, solved by ADR. Their experiments peak at 0.93-1.11 kN.

The plain criterion: the load point displaced by 0.15 mm in 1,500 load steps (0.1 um each, so
the peak is resolved to about 1%), at the spacings 2.5, 1.786 and 1.25 mm (70, 98 and 140
particles along the beam; each puts the notch between two particle columns) at ADR tolerance
1e-6, and for work against error the tolerances 1e-5 and 1e-7 at the two coarser spacings and
1e-5 at the finest. For each: the peak load and its displacement, the load at the end, the bonds
broken, the wall time (one thread) and the peak resident memory. The error of a peak is against
the finest spacing at 1e-6. Also the energy dissipated per unit crack area (load_steps.csv
dissipated_energy) while the crack grew 15 mm, against Gregoire's G_f = 143.2 N/m.

Softening bonds (damage.fracture_energy = G_f): 0.09 mm in 900 steps at the three spacings
and at 0.893 mm (SOFT_FINEST)
with the horizon 3.015 dx, and at the two finer ones with the coarsest one's horizon; read
against the cohesive-crack FEM reference of verification/fem/notched_beam_cohesive.py (the
limit their model should reach; its CSVs are committed).

Usage: verification/fracture/notched_beam.py [path/to/perinom] [--reuse]
(--reuse: take the runs in /tmp/perinom_notched_beam that finished, with their timing.json.)
Writes docs/verification/notched_beam.md and notched_beam.png (Debian's python3 with numpy and
matplotlib; /usr/bin/time for the memory). Two runs at a time; about 35 minutes on two cores."""
import csv, json, os, subprocess, sys, time
import numpy as np
import vtk  # here, not in the threads that read the snapshots: a lazy import there races
from vtk.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SCENE = os.path.join(ROOT, "examples", "notched_beam.yaml")
DOCS = os.path.join(ROOT, "docs", "verification")
STEPS, TOTAL = 1500, 1.5e-4  # load steps, load-point displacement (m)
SPACINGS = [0.0025, 0.0025 / 1.4, 0.00125]
SOFT_FINEST = 0.00125 / 1.4  # the softening bonds go one spacing further (about 7 min)
RATIO = 3.015  # the horizon over dx, as in the example
# Measured by hand (the same runs with 1,800 steps of 0.05 um), quoted in the report:
LOAD_STEP_NOTE = ("Halving the load step moves the peaks by less than 0.5% (by hand, 2026-12-07, with the supports' "
                  "ties broken alike: 0.05 um steps give 1.3570, 1.3293 and 1.3240 kN at 2.5, 1.786 and 1.25 mm, "
                  "2.5% apart, against 1.3634, 1.3340 and 1.3267 with the table's 0.1 um). ")
SOFT_STEPS, SOFT_TOTAL = 900, 0.9e-4  # the softening runs: the same 0.1 um steps, past the peak
NOTCH_X, NOTCH_TIP, THICKNESS = 0.0875, 0.025, 0.05  # m
GROWN, G_F = 0.015, 143.2  # the crack growth the energy is read at (m); Gregoire's G_f (N/m)


FEM = os.path.join(ROOT, "verification", "fem")


def cohesive_reference():
    """The finest grid's peaks of verification/fem/notched_beam_cohesive.py by law (N), and its
    curves by law (displacement m, load N)."""
    rows = list(csv.DictReader(open(os.path.join(FEM, "notched_beam_cohesive.csv"))))
    finest = min(float(r["h_m"]) for r in rows)
    peaks = {r["law"]: float(r["peak_N"]) for r in rows if float(r["h_m"]) == finest}
    curves = {}
    for r in csv.DictReader(open(os.path.join(FEM, "notched_beam_cohesive_curves.csv"))):
        curves.setdefault(r["law"], []).append((float(r["displacement_m"]), float(r["load_N"])))
    return peaks, {k: np.array(v) for k, v in curves.items()}


def crack_events(out, rows):
    """From the run's last snapshot: the particles' positions, their first break event (0: none),
    the spacing, and for each load step the last break event it holds."""
    snapshot = sorted(f for f in os.listdir(out) if f.endswith(".vtu"))[-1]
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(os.path.join(out, snapshot))
    reader.Update()
    g = reader.GetOutput()
    x = vtk_to_numpy(g.GetPoints().GetData())
    event = vtk_to_numpy(g.GetPointData().GetArray("break_event")).astype(int)
    dx = abs(np.diff(np.unique(np.round(x[:, 0], 9)))).min()
    last_event = np.cumsum([int(r["rounds"]) - 1 if float(r["broken_bonds"]) > 0 else 0 for r in rows])
    return x, event, dx, last_event


def cracked_by(out, rows):
    """A function of a load step k (0-based): the crack's tip above the notch tip by then (m;
    the highest particle within two spacings of the notch line that has lost a bond), or None."""
    x, event, dx, last_event = crack_events(out, rows)
    ligament = (np.abs(x[:, 0] - NOTCH_X) < 2 * dx) & (x[:, 1] > NOTCH_TIP)

    def reach(k):
        cracked = ligament & (event > 0) & (event <= last_event[k])
        return float(x[cracked, 1].max() - NOTCH_TIP) if cracked.any() else None
    return reach


def energy_per_crack_area(out, rows):
    """The energy dissipated (load_steps.csv) per unit crack area while the crack grew GROWN
    above the notch tip: at the first load step whose crack tip (cracked_by) is GROWN above the
    notch tip. None if it never got there."""
    reach = cracked_by(out, rows)
    for k, r in enumerate(rows):
        a = reach(k)
        if a is not None and a >= GROWN:
            return float(r["dissipated_energy"]) / (a * THICKNESS), a
    return None, None


def run(exe, dx, tol, work, reuse, soft=False, ratio=RATIO):
    """One run: the plain criterion, or with soft the softening bonds (G_f) over SOFT_STEPS;
    ratio: the horizon over dx."""
    steps, total = (SOFT_STEPS, SOFT_TOTAL) if soft else (STEPS, TOTAL)
    out = os.path.join(work, f"dx{dx * 1e3:.4f}_tol{tol:g}" + (f"_soft_m{ratio:g}" if soft else ""))
    sets = {"discretization.dx": repr(dx), "stages.0.steps": steps, "stages.0.boundary.2.displacement.y": -total,
            "solver.tolerance": tol, "solver.displacement_tolerance": tol, "output.vtk_steps": f"[{steps}]",
            "discretization.horizon": f"{{ratio: {ratio!r}}}"}
    if soft:
        sets["damage.fracture_energy"] = G_F
    timing = os.path.join(out, "timing.json")
    if not (reuse and os.path.exists(timing)):
        cmd = ["/usr/bin/time", "-f", "%M", exe, "run", SCENE, "--out", out]
        cmd += sum([["--set", f"{k}={v}"] for k, v in sets.items()], [])
        t0 = time.time()
        p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                           env=dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="PASSIVE"))
        wall = time.time() - t0
        rss = int(p.stderr.strip().splitlines()[-1]) / 1024.0  # MiB
        json.dump({"wall": wall, "rss": rss, "code": p.returncode}, open(timing, "w"))
    t = json.load(open(timing))
    wall, rss = t["wall"], t["rss"]
    summary = json.load(open(os.path.join(out, "summary.json")))
    rows = list(csv.DictReader(open(os.path.join(out, "load_steps.csv"))))
    P = np.array([-float(r["stages.0.boundary.2.Ry"]) for r in rows])  # the load, pushing down
    u = total * np.array([float(r["load_factor"]) for r in rows])
    broken = sum(float(r["broken_bonds"]) for r in rows)
    k = int(np.argmax(P))
    g_eff, grown = energy_per_crack_area(out, rows)
    reach = cracked_by(out, rows)(k)
    spent = summary["solver"].get("fracture", {}).get("softening_bonds_spent", 0)
    return dict(dx=dx, tol=tol, soft=soft, ratio=ratio, spent=spent, code=t["code"], status=summary.get("status", "?"),
                peak=P[k], at=u[k], end=P[-1],
                broken=int(broken), iterations=summary["solver"].get("iterations", 0), wall=wall, rss=rss,
                particles=summary.get("particles", 0), curve=(u, P), g_eff=g_eff, grown=grown, reach=reach,
                dissipated=float(rows[-1]["dissipated_energy"]))


def soft_report(soft, plain, plain_moved):
    """The softening-bond section of the report: its table and what it shows (plain: the plain
    criterion's runs at the three spacings; plain_moved: how far their peak moved, %)."""
    m3 = [r for r in soft if abs(r["ratio"] - RATIO) < 1e-9 and r["tol"] == 1e-6]
    three = [r for r in m3 if r["dx"] in SPACINGS]  # the issue's three spacings
    same = [r for r in soft if abs(r["ratio"] * r["dx"] - RATIO * SPACINGS[0]) < 1e-9 and r["tol"] == 1e-6]
    loose = [r for r in soft if r["tol"] == 1e-5]
    ref = m3[-1]
    lines = [f"## Softening bonds (`damage.fracture_energy: {G_F}`)", "",
             "The same beam with Gregoire's G_f: a bond the stress criterion breaks keeps a softening pair force "
             "whose work per unit crack area is G_f, and the criterion hands a bond over only when it is opened to "
             "its law's peak or both its particles have such a bond (docs/theory.md, \"Softening bonds\"; eta_u = "
             f"pi G_f / (2 f_t) = {np.pi * G_F / (2 * 3.9e6) * 1e6:.1f} um). The load point goes {SOFT_TOTAL * 1e3:g} mm "
             f"in {SOFT_STEPS} load steps (0.1 um each); at the three spacings and at {SOFT_FINEST * 1e3:.3f} mm "
             "with the horizon 3.015 dx (ADR tolerance 1e-6, and 1e-5 at the three for work against error), and at the two finer spacings again with the "
             "coarsest one's horizon (7.54 mm). `spent`: bonds opened past eta_u. `crack at the peak`: the "
             "highest particle near the notch line that has lost a bond by the peak's load step, above the notch.", "",
             "| dx (mm) | horizon (mm) | ADR tolerance | particles | peak (kN) | at (mm) | crack at the peak (mm) "
             "| load at the end (kN) | bonds broken | spent | ADR iterations | wall (s) | memory (MiB) "
             f"| peak against dx = {SOFT_FINEST * 1e3:.3f} mm, horizon 3.015 dx, 1e-6 |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in soft:
        reach = f"{r['reach'] * 1e3:.2f}" if r["reach"] is not None else "-"
        lines.append(f"| {r['dx'] * 1e3:.3f} | {r['ratio'] * r['dx'] * 1e3:.2f} | {r['tol']:g} | {r['particles']} | "
                     f"{r['peak'] / 1e3:.4f} | {r['at'] * 1e3:.4f} | {reach} | {r['end'] / 1e3:.4f} | {r['broken']} | "
                     f"{r['spent']} | {r['iterations']} | {r['wall']:.1f} | {r['rss']:.0f} | "
                     f"{(r['peak'] - ref['peak']) / ref['peak'] * 100:+.1f}% |")
    peaks = [r["peak"] for r in three]
    spread = (max(peaks) - min(peaks)) / min(peaks) * 100
    hi, lo = max(three, key=lambda r: r["peak"]), min(three, key=lambda r: r["peak"])
    held = [r["peak"] for r in same]
    held_spread = (max(held) - min(held)) / min(held) * 100
    fem, fem_curves = cohesive_reference()
    fem_end = float(np.interp(SOFT_TOTAL, *fem_curves["bonds"].T))
    grip_end = float(np.interp(SOFT_TOTAL, *fem_curves["bonds_grip"].T))
    apart = np.abs(np.interp(fem_curves["bonds"][:, 0], *fem_curves["bonds_grip"].T) - fem_curves["bonds"][:, 1])
    same_until = fem_curves["bonds"][np.argmax(apart > 0.01 * fem["bonds"]), 0]  # the two FEM curves 1% apart
    vs_fem = ", ".join(f"{(r['peak'] - fem['bonds']) / fem['bonds'] * 100:+.1f}%" for r in m3)
    last = (m3[-1]["peak"] - m3[-2]["peak"]) / m3[-2]["peak"] * 100
    lines += ["", "**The limit the model should reach.** As the spacing and the horizon shrink, the softening "
              "bonds should turn into a local elastic body with a cohesive crack whose traction is what the "
              "bonds crossing a flat crack carry: T(w) = f_t (2/pi) int cos^2(theta) max(0, 1 - w cos(theta) / "
              "eta_u) dtheta (a bond at theta to the normal opens by w cos(theta)); its area is G_f. "
              "verification/fem/notched_beam_cohesive.py solves that beam by FEM (the same geometry, supports "
              "and load patch; half beam, bilinear quadrilaterals at h = 1.25, 0.625, 0.3125 mm, the finest two "
              f"within 0.1%): peak **{fem['bonds'] / 1e3:.3f} kN** with this law, the crack then 16.25 mm above the "
              f"notch; {fem['linear'] / 1e3:.3f} kN with Hillerborg's linear law and {fem['bilinear'] / 1e3:.3f} kN "
              "with Petersson's bilinear one, the same f_t and G_f. The experiments' band (0.93-1.11 kN) lies below "
              f"all three (the lowest, the bilinear law's, is {(fem['bilinear'] - 1110.0) / 1110.0 * 100:.0f}% above "
              "the band's top): a model that converges to a cohesive crack with these inputs peaks above the band, "
              "so of the issue's two targets for this beam (converged, in or near the band) the first is the one "
              "to aim at, at the FEM's peak.", "",
              f"**Result.** With the horizon at 3.015 dx the peaks at the issue's three spacings are "
              + ", ".join(f"{r['peak'] / 1e3:.3f}" for r in three) + " kN at dx = "
              + ", ".join(f"{r['dx'] * 1e3:.3f}" for r in three) + f" mm: a spread of **{spread:.2f}%** (the plain "
              f"criterion's {plain_moved:.0f}%); one spacing further, {m3[-1]['dx'] * 1e3:.3f} mm, "
              f"{m3[-1]['peak'] / 1e3:.3f} kN ({last:+.1f}% from the one before). Against the FEM's limit: {vs_fem}. "
              + ("The issue's 5% is met. " if spread <= 5.0 else
                 f"The issue asks for 5%: **missed** by {spread - 5.0:.2f} points, between the highest peak "
                 f"(dx = {hi['dx'] * 1e3:.3f} mm, {(hi['peak'] - fem['bonds']) / fem['bonds'] * 100:+.1f}% from the "
                 f"FEM) and the lowest (dx = {lo['dx'] * 1e3:.3f} mm, "
                 f"{(lo['peak'] - fem['bonds']) / fem['bonds'] * 100:+.1f}%): the peaks straddle the limit rather "
                 "than approach it monotonically. ")
              + LOAD_STEP_NOTE
              + f"With the horizon held at 7.54 mm the three spacings' peaks spread by {held_spread:.1f}% ("
              + ", ".join(f"{r['peak'] / 1e3:.3f}" for r in same) + " kN at m = "
              + ", ".join(f"{r['ratio']:.2f}" for r in same) + " horizons per spacing, "
              + ", ".join(str(r["broken"]) for r in same) + " bonds broken)"
              + (": the peak converges at a fixed ratio of horizon to spacing (the seed's practice), where the "
                 "horizon shrinks with the spacing towards the local cohesive crack, not at a fixed horizon, where "
                 "the family grows towards a nonlocal model whose horizon is 0.3 of the ligament. It is not the "
                 "gate's second condition (by hand: with the first condition alone the 1.786 mm run at 7.54 mm "
                 "peaks at 1.633 kN, higher still). "
                 if held_spread > 5.0 else ": within 5% too. ")
              + "Work against error (the ADR tolerance 1e-5 against 1e-6 at each spacing): "
              + ", ".join(f"{(l['peak'] - t['peak']) / t['peak'] * 100:+.2f}% of the peak in {l['wall']:.0f} s "
                          f"against {t['wall']:.0f} s at {t['dx'] * 1e3:.3f} mm" for l, t in zip(loose, three))
              + (": the tolerance moves the peak far less than the spacing does. "
                 if max(abs(l["peak"] - t["peak"]) / t["peak"] * 100 for l, t in zip(loose, three)) < spread / 3
                 else ": the tolerance moves the peak as much as a spacing does. ")
              + "Where the crack is at the peak: "
              + ", ".join(f"{r['reach'] * 1e3:.2f}" if r["reach"] is not None else "-" for r in m3)
              + " mm above the notch at the four spacings, the FEM's cohesive crack 16.25 mm (the old rule's: 16.25, 11.6, 10.6 mm). Past the peak the runs soften more "
              f"slowly than the FEM: at {SOFT_TOTAL * 1e3:g} mm they carry "
              + ", ".join(f"{r['end'] / 1e3:.3f}" for r in m3) + f" kN against its {fem_end / 1e3:.3f} kN. That tail is the grip's: the scene's no-fail box under "
              "the load (y >= 42 mm) holds the top of the ligament, where the FEM's crack runs on; the FEM with "
              f"the ligament held closed above 42 mm (law `bonds_grip`) carries {grip_end / 1e3:.3f} kN at "
              f"{SOFT_TOTAL * 1e3:g} mm, a plateau, and follows the free ligament's curve within 1% up to "
              f"{same_until * 1e3:.3f} mm, past the peak: the peak is not the grip's, the tail is, and the "
              "runs lie between the two FEM curves there.", "",
              "**Before the gate** (the rule of the last session, by hand on 2026-12-05 with "
              "builds changed for the test, not kept; the same scene, 900 steps of 0.1 um unless said): "
              "every bond the plain criterion breaks became a softening bond, and the peaks were 1.471, 1.337 and "
              "1.220 kN (21%; +8.9%, -1.0%, -9.7% from the FEM, crossing the limit), the softening bonds adding "
              "a nearly constant +0.49 to +0.53 kN to the plain criterion's peaks, with up to 4.5% of load-step "
              "error at 0.1 um. What was tried, with the peaks at the three spacings: a softening force only on "
              "the bonds crossing the notch's line, all others breaking as before: 1.204, 1.029, 0.950 kN; each "
              "particle's stress scaled by its share of live bonds: 1.351, 1.207, 1.007; the criterion on the "
              "bond's own normal stress e . sigma e (sigma the pair's mean): 1.592, 1.432, 1.263; breaking only "
              "the bonds across the notch's line (a diagnostic that knows the path): **1.398, 1.348, 1.338**; "
              "the stress criterion and the bond at its law's peak (the gate's first condition alone): 1.398, "
              "1.353, 1.339, unchanged with 0.05 um steps (1.3985, 1.3534, 1.3394), but a bar under uniform "
              "tension then carries 1.95 f_t A, its inclined bonds renormalised and never opened, which the "
              "second condition mends (the bar test: 195 N against f_t A = 200 N, 1.032 G_f A dissipated, as "
              "before); the bond's stretch over f_t / E alone (no stress criterion): 1.328, 1.313, 1.323. "
              "So what moved the peak was the band of bonds cut beside the crack, which no crack opens.", ""]
    return lines


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    exe = args[0] if args else os.path.join(ROOT, "build", "drivers", "perinom")
    reuse = "--reuse" in sys.argv
    work = "/tmp/perinom_notched_beam"
    os.makedirs(work, exist_ok=True)
    cases = [(dx, 1e-6) for dx in SPACINGS] + [(dx, t) for dx in SPACINGS[:2] for t in (1e-5, 1e-7)]
    cases += [(SPACINGS[2], 1e-5)]
    # The softening bonds at the three spacings and one finer (horizon 3.015 dx), at the two finer ones
    # with the coarsest one's horizon (7.54 mm): which of the two lengths moves the peak.
    soft_cases = [(dx, 1e-6, True, RATIO) for dx in SPACINGS + [SOFT_FINEST]]
    soft_cases += [(dx, 1e-6, True, RATIO * SPACINGS[0] / dx) for dx in SPACINGS[1:]]
    soft_cases += [(dx, 1e-5, True, RATIO) for dx in SPACINGS]  # work against error
    # Two runs at a time (the machine's two cores): the wall times are those of a busy machine.
    from concurrent.futures import ThreadPoolExecutor
    with ThreadPoolExecutor(2) as pool:
        jobs = [pool.submit(run, exe, *c[:2], work, reuse, *c[2:]) for c in cases + soft_cases]
        done = [j.result() for j in jobs]
    for r in done:
        print(f"dx {r['dx'] * 1e3:.3f} mm tol {r['tol']:g}{' softening, horizon %.2f mm' % (r['ratio'] * r['dx'] * 1e3) if r['soft'] else ''}: "
              f"peak {r['peak'] / 1e3:.4f} kN at {r['at'] * 1e3:.4f} mm, {r['wall']:.1f} s, {r['rss']:.0f} MiB", flush=True)
    res, soft = done[:len(cases)], done[len(cases):]
    ref = next(r for r in res if r["dx"] == SPACINGS[2] and r["tol"] == 1e-6)
    lines = ["# A notched concrete beam in three-point bending: the plain stress criterion and softening bonds", "",
             "Generated by `/usr/bin/python3 verification/fracture/notched_beam.py` on "
             "`examples/notched_beam.yaml`: the geometry of Gregoire, Rojas-Solano and "
             "Pijaudier-Cabot (2013), 175 x 50 mm, 50 mm thick, span 125 mm, a 25 mm notch at mid-span "
             "(a precrack between two particle columns), plane stress, E = 37 GPa, nu = 0.2, classical "
             "formulation, horizon 3.015 dx, C_hg = 0.5, the stress criterion with f_t = 3.9 MPa (seed 000 "
             "eq. 49-51, no fracture-energy regularisation), no-fail grips at the supports and under the load; "
             f"the load point displaced by {TOTAL * 1e3:g} mm in {STEPS} load steps, solved by ADR. "
             "The point supports at x = 25 and 150 mm fall midway between two particle columns at every "
             "spacing: the lowest-numbered particle is taken, both half a spacing to the left, so the span is "
             "125 mm at every spacing. Until 2026-12-07 rounding broke those ties, and the span was 122.5, "
             "123.2, 125.0 and 124.1 mm at dx = 2.5, 1.786, 1.25 and 0.893 mm: the shorter spans' peaks were "
             "higher (the softening peaks 1.412, 1.382, 1.327, 1.366 kN, 6.4% apart, where they are now "
             "within 3%). "
             "Their experiments peak at 0.93-1.11 kN. One thread each, two runs at a time on the two cores (the "
             "wall times are a busy machine's); memory is the peak resident set.", "",
             "| dx (mm) | particles | ADR tolerance | peak (kN) | at (mm) | load at 0.15 mm (kN) | bonds broken "
             "| ADR iterations | wall (s) | memory (MiB) | peak against the finest | dissipated per crack area (N/m) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in res:
        g = f"{r['g_eff']:.1f} (at {r['grown'] * 1e3:.1f} mm)" if r["g_eff"] is not None else "-"
        lines.append(f"| {r['dx'] * 1e3:.3f} | {r['particles']} | {r['tol']:g} | {r['peak'] / 1e3:.4f} | {r['at'] * 1e3:.4f} | "
                     f"{r['end'] / 1e3:.4f} | {r['broken']} | {r['iterations']} | {r['wall']:.1f} | {r['rss']:.0f} | "
                     f"{(r['peak'] - ref['peak']) / ref['peak'] * 100:+.1f}% | {g} |")
    base = [r for r in res if r["tol"] == 1e-6]
    moved = (base[0]["peak"] - base[-1]["peak"]) / base[-1]["peak"] * 100
    slope = np.polyfit(np.log([r["dx"] for r in base]), np.log([r["peak"] for r in base]), 1)[0]
    in_band = [r for r in base if 930.0 <= r["peak"] <= 1110.0]
    lines += ["", f"The plain criterion's peak at dx = 2.5 mm is {moved:.0f}% above the one at dx = 1.25 mm (the "
              f"peak goes as dx^{slope:.2f} over these three spacings): it does not converge. The criterion compares the "
              "stress at the notch tip with f_t, and the tip's stress grows as the spacing resolves the "
              "singularity better, so a finer model breaks the first bonds at a lower load. This is what "
              "`damage.fracture_energy` (softening bonds, below) is for. "
              + (f"In the experiments' band: dx = " + ", ".join(f"{r['dx'] * 1e3:.3f}" for r in in_band)
                 + " mm, by accident of the spacing. " if in_band else
                 f"None falls in the experiments' band (the coarsest, {base[0]['peak'] / 1e3:.3f} kN, is nearest). ")
              + "The ADR tolerance moves the peak "
              "far less than the spacing does (the rows at 1e-5 and 1e-7 against 1e-6 at the same spacing). "
              "Past about 0.03 mm the crack has run up to the no-fail grip under the load, which cannot break: "
              "the ligament it leaves carries a load that rises again with the displacement, so the tail of "
              "the curves is the grip's, not the concrete's softening.", "",
              "In energy terms (the last column; load_steps.csv's `dissipated_energy`, the work done on the beam "
              f"less the strain energy it holds, divided by the crack area when the crack tip has first grown "
              f"{GROWN * 1e3:g} mm above the notch, the tip being the highest particle near the notch line that has "
              f"lost a bond): the plain criterion dissipates a small part of the concrete's G_f = {G_F} N/m, and less "
              "the finer the spacing, as a stress criterion at a crack tip must (the energy a break releases scales "
              "with the spacing).", ""]
    lines += soft_report(soft, base, moved)
    lines += ["![load against load-point displacement](notched_beam.png)", ""]
    open(os.path.join(DOCS, "notched_beam.md"), "w").write("\n".join(lines))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
    for ax, runs, title in ((axes[0], base, "plain stress criterion"), (axes[1], [r for r in soft if r["tol"] == 1e-6], f"softening bonds, G_f = {G_F} N/m")):
        for r in runs:
            u, P = r["curve"]
            ax.plot(u * 1e3, P / 1e3, label=f"dx = {r['dx'] * 1e3:.3f} mm, horizon {r['ratio'] * r['dx'] * 1e3:.2f} mm")
        if runs is not base:
            c = cohesive_reference()[1]["bonds"]
            ax.plot(c[:, 0] * 1e3, c[:, 1] / 1e3, "k--", label="cohesive crack, FEM (the bonds' law)")
            c = cohesive_reference()[1]["bonds_grip"]
            ax.plot(c[:, 0] * 1e3, c[:, 1] / 1e3, "k:", label="the same, ligament held above 42 mm (the grip)")
        ax.axhspan(0.93, 1.11, color="0.85", label="experiments' peaks")
        ax.set_xlabel("load-point displacement (mm)")
        ax.set_title(title)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("load (kN)")
    fig.tight_layout()
    fig.savefig(os.path.join(DOCS, "notched_beam.png"), dpi=100)


if __name__ == "__main__":
    main()
