#!/usr/bin/python3
"""Where the upper flaw of the four-point beam lies, and whether it cracks on its own (issue 18).

The seed's sequence (sec. 5.2) ends with a second crack growing down from the upper flaw's
left side before the crack from below arrives; examples/four_point_beam.yaml does not show it
(docs/verification/four_point_beam.md). The seed's geometry is in an unreadable figure, so
this asks whether the miss is an accident of our placement: the 2-D example is run with its
upper flaw moved (--set precracks.1), its lower (left) tip T2 at eight places in and above
the tension zone, 10 mm long at 45 degrees (one 20 mm long), everything else as the example.

Measured per placement, from the last snapshot's break_event (four_point_beam.py's reading):
the load step in which the first particle within 5 mm of T1 (the lower flaw's tip), of T2,
and of the upper flaw's upper tip lost a bond; the first step of the band 2.5-7.5 mm below
T2 (within 10 mm of its x); T2 "on its own" when T2's step comes before that band's (the
crack from below reaches T2 through that band); the peak load and its step.

Usage: verification/fracture/four_point_flaws.py [path/to/perinom] [--reuse]
Writes docs/verification/four_point_flaws.md and four_point_flaws.png (Debian's python3 with
numpy, matplotlib and vtk). About a minute a placement on one thread."""
import csv, os, subprocess, sys
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import four_point_beam as fpb  # noqa: E402

WORK = "/tmp/perinom_four_point_flaws"
PLACES = [(85, 31, 10), (85, 36, 10), (85, 41, 10), (90, 26, 10), (90, 36, 10), (95, 31, 10), (95, 41, 10),
          (85, 31, 20)]  # T2 = (x, y) mm, length along 45 degrees (mm); the example's is (85, 46, 10)
NEAR = 5.0  # mm


def out_dir(x, y, length):
    return os.path.join(WORK, f"u_{x:g}_{y:g}" + ("" if length == 10 else f"_{length:g}"))


def run(exe, x, y, length, reuse):
    out = out_dir(x, y, length)
    if not (reuse and os.path.exists(os.path.join(out, "summary.json"))):
        crack = f"{{from: [{x / 1e3}, {y / 1e3}], to: [{(x + length) / 1e3}, {(y + length) / 1e3}]}}"
        subprocess.run([exe, "run", fpb.SCENES["2d"], "--out", out, "--set", f"precracks.1={crack}",
                        "--set", "output.vtk_steps=[1000]"], stdout=subprocess.DEVNULL, check=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="PASSIVE"))
    rows = list(csv.DictReader(open(os.path.join(out, "load_steps.csv"))))
    P = -np.array([float(r["stages.0.boundary.2.Ry"]) + float(r["stages.0.boundary.3.Ry"]) for r in rows])
    step_of_event = [0]
    for k, r in enumerate(rows):
        if float(r["broken_bonds"]) > 0:
            step_of_event += [k + 1] * (int(r["rounds"]) - 1)
    step, xs, fields = fpb.snapshots(out)[-1]
    s, _ = fpb.first_break_step(dict(step_of_event=np.array(step_of_event)), xs, fields)
    xy = xs[:, :2]

    def first(mask):
        m = mask & (s > 0)
        return int(s[m].min()) if m.any() else -1

    near = lambda p: np.hypot(xy[:, 0] - p[0], xy[:, 1] - p[1]) < NEAR
    below = (np.abs(xy[:, 0] - x) < 10) & (xy[:, 1] > y - 7.5) & (xy[:, 1] < y - 2.5)
    r = dict(x=x, y=y, length=length, T1=first(near(fpb.T1)), T2=first(near((x, y))),
             top=first(near((x + length, y + length))), below=first(below), peak=float(P.max()),
             peak_step=int(np.argmax(P)) + 1, xy=xy, s=s)
    r["own"] = r["T2"] > 0 and (r["below"] < 0 or r["T2"] < r["below"])
    return r


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    exe = args[0] if args else os.path.join(fpb.ROOT, "build", "drivers", "perinom")
    reuse = "--reuse" in sys.argv
    os.makedirs(WORK, exist_ok=True)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    results = []
    for x, y, length in PLACES:
        results.append(run(exe, x, y, length, reuse))
        q = results[-1]
        print(f"T2 ({x}, {y}) {length} mm: T1 {q['T1']}, T2 {q['T2']}, below {q['below']}, top {q['top']}, "
              f"own {q['own']}, peak {q['peak']:.0f} N at {q['peak_step']}", flush=True)
    fig, axes = plt.subplots(4, 2, figsize=(10, 11))
    for a, q in zip(axes.flat, results):
        m = q["s"] > 0
        a.scatter(q["xy"][:, 0], q["xy"][:, 1], c="0.85", s=4)
        sc = a.scatter(q["xy"][m, 0], q["xy"][m, 1], c=q["s"][m], s=8, cmap="viridis", vmin=150, vmax=450)
        a.plot([58, 80], [-1, 21], "r-", lw=2)
        a.plot([q["x"], q["x"] + q["length"]], [q["y"], q["y"] + q["length"]], "r-", lw=2)
        a.set_xlim(45, 125)
        a.set_aspect("equal")
        a.set_title(f"T2 = ({q['x']}, {q['y']}) mm, {q['length']} mm", fontsize=9)
    fig.colorbar(sc, ax=axes, label="load step of a particle's first broken bond", shrink=0.6)
    fig.savefig(os.path.join(fpb.DOCS, "four_point_flaws.png"), dpi=70)
    yes = lambda v: "yes" if v else "no"
    L = ["# The four-point beam's upper flaw, moved (issue 18)", "",
         "Generated by `/usr/bin/python3 verification/fracture/four_point_flaws.py`: `examples/four_point_beam.yaml` "
         "(2-D) with its upper flaw moved, everything else as the example: its lower (left) tip T2 at the places "
         "below, 10 mm long at 45 degrees (one 20 mm). The example's own, T2 = (85, 46) mm, is in "
         "[four_point_beam.md](four_point_beam.md). Load steps in which the first particle within 5 mm of each "
         "place lost a bond (-1: never); \"below T2\" is the band 2.5-7.5 mm under T2 within 10 mm of its x, "
         "through which the crack from below reaches it; T2 cracks on its own when its step comes first.", "",
         "| T2 (mm) | length (mm) | T1 | below T2 | T2 | upper tip | T2 on its own | peak (N, step) |",
         "|---|---|---|---|---|---|---|---|"]
    for q in results:
        L.append(f"| ({q['x']}, {q['y']}) | {q['length']} | {q['T1']} | {q['below']} | {q['T2']} | {q['top']} | "
                 f"{yes(q['own'])} | {q['peak']:.0f} at {q['peak_step']} |")
    own = [q for q in results if q["own"]]
    L += ["", (f"**In {len(own)} of {len(results)} placements the upper flaw's lower tip cracks before the crack "
               "from below arrives.** " if own else
               f"**In none of the {len(results)} placements does the upper flaw's lower tip crack before the crack "
               "from below arrives**: ")
          + "the crack leaves the lower flaw's tip T1 = (80, 21) mm first in every case (steps "
          + f"{min(q['T1'] for q in results)}-{max(q['T1'] for q in results)}) and grows straight up at x = 80 mm; "
          "an upper flaw in its way is reached from below (its upper tip cracks later, growing up), one beside it "
          "is passed and cracks late if at all. The seed's second crack, down from the upper flaw's left side on "
          "its own, is not an accident of our placement. A likely reason, not tested here: the stress criterion "
          "reads the particles whose families a flaw cuts as less stressed (their cut bonds carry nothing), which "
          "hides the concentration at a short internal flaw's tip, while the notch from the bottom face sits in "
          "the largest tension and ""wins.", "", "![crack order per placement](four_point_flaws.png)", ""]
    open(os.path.join(fpb.DOCS, "four_point_flaws.md"), "w").write("\n".join(L))


if __name__ == "__main__":
    main()
