#!/usr/bin/python3
"""Verlet's energy balance over 10,000 steps (issue 14): the largest |kinetic + strain - external
work| over the run, divided by the largest external work, on the vibrating bar of the examples
(2-D) and on verlet_bar_3d.yaml, at the program's stable step times safety 0.8 (the default),
0.4 and 0.2, the run's time span kept. An error that falls as the step squared is the
integrator's own step error, not an energy account that disagrees with the forces.

Usage: verification/formulation/verlet_energy.py [path/to/perinom]   (about 4 minutes)
Prints a markdown table.
"""
import csv, os, subprocess, sys, time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(os.path.dirname(here))
exe = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/drivers/perinom")
work = "/tmp/perinom_verlet_energy"
env = dict(os.environ, OMP_WAIT_POLICY="PASSIVE")
cases = [("2-D vibrating bar", os.path.join(root, "examples/vibrating_bar.yaml")),
         ("3-D bar", os.path.join(here, "verlet_bar_3d.yaml"))]


def balance(out):
    rows = list(csv.DictReader(open(os.path.join(out, "history.csv"))))
    work_done = max(float(r["external_work"]) for r in rows)
    worst = max(rows, key=lambda r: abs(float(r["total_energy"])))
    return abs(float(worst["total_energy"])) / work_done, int(worst["step"])


print("| case | safety | steps | max abs(E - W) / max W | at step | wall (s) |")
print("|---|---:|---:|---:|---:|---:|")
for name, scene in cases:
    for safety in (0.8, 0.4, 0.2):
        steps = round(10000 * 0.8 / safety)
        out = os.path.join(work, "%s_%g" % (os.path.basename(scene)[:-5], safety))
        t = time.time()
        subprocess.run([exe, "run", scene, "--out", out, "--set", "solver.safety=%g" % safety,
                        "--set", "solver.steps=%d" % steps, "--set", "solver.history_every=10"],
                       check=True, env=env, stdout=subprocess.DEVNULL)
        error, step = balance(out)
        print("| %s | %g | %d | %.3e | %d | %.1f |" % (name, safety, steps, error, step, time.time() - t))
