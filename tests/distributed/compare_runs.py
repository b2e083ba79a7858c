#!/usr/bin/env python3
"""Runs a scene serially and on R MPI ranks and compares what the two runs report (issue 19).

Checks: both exit 0 with status converged; the same particle and bond counts; every point
probe, line probe row and support reaction within --tolerance of the serial value (relative
to the largest magnitude of its kind); the history's columns alike (and, for a dynamic run,
every row within the tolerance; for a load path, load_steps.csv's steps and reactions, its
counts of LBC rounds and flagged, yielding and plastic particles exactly, and the point
probes' histories row by row); the final snapshot's pieces, one per rank, holding every
particle once between them. Prints "compare: passed" or what differs, and exits 1 then.
Standard library only: the CI's python3 runs it.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys


def run(command):
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.stdout.write(done.stdout)
        sys.exit("compare: %s exited with %d" % (" ".join(command), done.returncode))
    return done.stdout


def rows(path):
    with open(path) as f:
        table = list(csv.reader(f))
    return table[0], [[float(x) for x in r] for r in table[1:]]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--perinom", required=True)
    ap.add_argument("--mpiexec", required=True)
    ap.add_argument("--ranks", type=int, required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--tolerance", type=float, required=True)
    a = ap.parse_args()
    sets = [x for s in a.set for x in ("--set", s)]
    serial, ranked = os.path.join(a.out, "serial"), os.path.join(a.out, "ranks%d" % a.ranks)
    run([a.perinom, "run", a.scene, "--out", serial, "--threads", "1"] + sets)
    run([a.mpiexec, "-np", str(a.ranks), "--oversubscribe", a.perinom, "run", a.scene, "--out", ranked,
         "--threads", "1"] + sets)
    s = json.load(open(os.path.join(serial, "summary.json")))
    m = json.load(open(os.path.join(ranked, "summary.json")))
    failures = []
    worst = [0.0]

    def close(what, x, y, scale):
        worst[0] = max(worst[0], abs(x - y) / scale)
        if not abs(x - y) <= a.tolerance * scale:
            failures.append("%s: %.12g serial, %.12g on %d ranks" % (what, x, y, a.ranks))

    def same_table(what, path_s, path_m):
        """The two runs' CSV tables: the same columns and rows, each value against its column's largest."""
        if not os.path.exists(path_m):
            failures.append("%s: the serial run wrote it, the ranks did not" % what)
            return
        head_s, ts = rows(path_s)
        head_m, tm = rows(path_m)
        if head_s != head_m or len(ts) != len(tm):
            failures.append("%s: %d rows of %s serial, %d rows of %s on the ranks" % (what, len(ts), head_s, len(tm), head_m))
            return
        for c, column in enumerate(head_s):
            scale = max(max(abs(r[c]) for r in ts), 1e-300)
            for r in range(len(ts)):
                close("%s row %d %s" % (what, r + 1, column), ts[r][c], tm[r][c], scale)

    for key in ("status", "particles", "bonds"):
        if s[key] != m[key]:
            failures.append("%s: %s serial, %s on %d ranks" % (key, s[key], m[key], a.ranks))
    if m.get("ranks") != a.ranks:
        failures.append("ranks: the summary says %s" % m.get("ranks"))
    for name, value in s["probes"].items():
        if isinstance(value, dict):
            same_table("probe " + name, os.path.join(serial, value["file"]), os.path.join(ranked, value["file"]))
        else:
            close("probe " + name, value, m["probes"][name], max(abs(value), 1e-300))
    # A plastic run's summary: the same particles yielded, the plastic strain's range and mean
    # (it was missing under mpirun).
    if "plasticity" in s:
        if "plasticity" not in m:
            failures.append("plasticity: in the serial summary, not in the ranks'")
        else:
            ps, pm = s["plasticity"], m["plasticity"]
            if ps["particles_yielded"] != pm["particles_yielded"]:
                failures.append("plasticity: %d particles yielded serial, %d on the ranks"
                                % (ps["particles_yielded"], pm["particles_yielded"]))
            for key in ("eq_plastic_strain_min", "eq_plastic_strain_mean", "eq_plastic_strain_max"):
                close("plasticity " + key, ps[key], pm[key], max(ps["eq_plastic_strain_max"], 1e-300))
    # Reactions against the largest, or the loads' scale when they are all rounding (a free
    # body pinned by rigid_body); the pins themselves must be the same particles.
    if s.get("constraints") != m.get("constraints"):
        failures.append("constraints: %s serial, %s on %d ranks" % (s.get("constraints"), m.get("constraints"), a.ranks))
    reactions = s.get("reactions", {})
    scale = max([abs(x) for r in reactions.values() for x in r] + [s.get("equilibrium", {}).get("scale", 0.0), 1e-300])
    for name, r in reactions.items():
        for c, x in enumerate(r):
            close("reaction %s[%d]" % (name, c), x, m["reactions"][name][c], scale)
    load_path = "load_steps" in s["solver"]
    head_s, hs = rows(os.path.join(serial, "load_steps.csv" if load_path else "history.csv"))
    head_m, hm = rows(os.path.join(ranked, "load_steps.csv" if load_path else "history.csv"))
    if head_s != head_m:
        failures.append("history: the columns differ")
    elif load_path:
        # One row per load step: the same steps, and each step's reactions against the
        # largest (the balances' iteration counts, residuals and times may differ).
        if len(hs) != len(hm):
            failures.append("load_steps: %d rows serial, %d on %d ranks" % (len(hs), len(hm), a.ranks))
        supports = [c for c, column in enumerate(head_s) if re.search(r"\.R[xyz]?$", column)]
        largest = max([abs(r[c]) for r in hs for c in supports] + [1e-300])
        for c in [0, 1, 2] + supports:
            for r in range(min(len(hs), len(hm))):
                close("load step %d %s" % (r + 1, head_s[c]), hs[r][c], hm[r][c], largest if c in supports else 1.0)
        # LBC's decisions, counted over the whole body: the same in every step.
        for c, column in enumerate(head_s):
            if column in ("rounds", "newly_flagged", "yielding", "plastic"):
                for r in range(min(len(hs), len(hm))):
                    if hs[r][c] != hm[r][c]:
                        failures.append("load step %d %s: %d serial, %d on %d ranks" % (r + 1, column, hs[r][c], hm[r][c], a.ranks))
        # The point probes' histories, column by column against each column's largest.
        for name in sorted(f for f in os.listdir(serial) if f.startswith("probe_") and f.endswith("_history.csv")):
            same_table(name, os.path.join(serial, name), os.path.join(ranked, name))
    elif s["solver"]["type"] == "verlet":
        if len(hs) != len(hm):
            failures.append("history: %d rows serial, %d on %d ranks" % (len(hs), len(hm), a.ranks))
        # Reaction columns against the largest reaction (a held component's is rounding), the
        # energies against the largest energy or work (total_energy is their cancelling sum).
        supports = [c for c, column in enumerate(head_s) if re.search(r"\.R[xyz]?$", column)]
        energies = [c for c, column in enumerate(head_s) if column.endswith(("_energy", "_work"))]
        largest = max([abs(r[c]) for r in hs for c in supports] + [1e-300])
        energy = max([abs(r[c]) for r in hs for c in energies] + [1e-300])
        for c, column in enumerate(head_s):
            scale = largest if c in supports else energy if c in energies else max(max(abs(r[c]) for r in hs), 1e-300)
            for r in range(min(len(hs), len(hm))):
                close("history row %d %s" % (r, column), hs[r][c], hm[r][c], scale)
    # The final snapshot: its .pvtu names one piece per rank, which hold every particle once.
    pvd = open(os.path.join(ranked, m["name"] + ".pvd")).read()
    last = re.findall(r'file="([^"]+)"', pvd)[-1]
    pieces = re.findall(r'Source="([^"]+)"', open(os.path.join(ranked, last)).read())
    points = 0
    for piece in pieces:
        with open(os.path.join(ranked, piece), "rb") as f:
            head = f.read(4096).decode("latin-1")
        points += int(re.search(r'NumberOfPoints="(\d+)"', head).group(1))
    if len(pieces) != a.ranks or points != s["particles"]:
        failures.append("snapshot %s: %d pieces with %d points, for %d ranks and %d particles"
                        % (last, len(pieces), points, a.ranks, s["particles"]))
    # output.csv: the final snapshot as CSV, gathered in the whole cloud's order, row by row
    # (each column against its largest magnitude), the last of each run's series.
    pvd_s = open(os.path.join(serial, s["name"] + ".pvd")).read()
    csv_s = os.path.join(serial, re.findall(r'file="([^"]+)"', pvd_s)[-1][:-4] + ".csv")
    if os.path.exists(csv_s):
        same_table("snapshot CSV " + os.path.basename(csv_s), csv_s, os.path.join(ranked, last[:-5] + ".csv"))
    for f in failures[:20]:
        print("compare: " + f)
    print("compare: largest relative difference %.3e (tolerance %g); iterations %d serial, %d on %d ranks"
          % (worst[0], a.tolerance, s["solver"]["iterations"], m["solver"]["iterations"], a.ranks))
    print("compare: %s (%d ranks, %s)" % ("FAILED" if failures else "passed", a.ranks, s["solver"]["type"]))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
