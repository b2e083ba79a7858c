#!/usr/bin/python3
"""Accuracy of the second-order nonlocal Hessian and gradient (seed 002 sec. 6.1).

w(x, y) = exp(xy) (sin 3(x - y) - cos 2(x + y)) on [-1, 1]^2, n x n regular particles (spacing
h = 2/n), k nearest neighbours, influence 1/r^2. Relative L2 errors (seed 002 eq. 102) of the
nonlocal Hessian and gradient against the exact ones, over all particles, over the interior
(families not cut by the boundary) and over the boundary band; least-squares rates in h
(e ~ h^p; in N = n^2 the rate is p/2).
  1. the seed's resolution sweep, k = 14, n = 20 ... 200;
  2. the same with k = 12 (a complete ring of neighbours, symmetric families), to separate the
     boundary from the interior;
  3. the neighbour sweep at N = 60^2 and at the seed's N = 180^2;
  4. the error by layer from the boundary at n = 100 and 200, k = 14.
Run (about 30 s; one thread):
  /usr/bin/python3 verification/hessian_accuracy/hessian_accuracy.py \\
      build/verification/hessian_accuracy/hessian_accuracy
Writes docs/verification/hessian_accuracy.md and hessian_accuracy_*.png."""
import csv, io, os, platform, subprocess, sys
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
DOCS = os.path.join(ROOT, "docs", "verification")
NS = [20, 40, 60, 80, 100, 140, 160, 180, 200]
KS = list(range(5, 31))
SEED_RATE = 0.835


def table(exe, *args):
    # One thread: the errors do not depend on it, and on a shared 2-core machine the times of
    # sub-millisecond products on two threads measure the other jobs, not the bond loop.
    env = dict(os.environ, OMP_NUM_THREADS="1")
    out = subprocess.run([exe, *map(str, args)], check=True, capture_output=True, text=True, env=env).stdout
    return list(csv.DictReader(io.StringIO(out)))


def sweep(exe, ns, ks):
    rows = table(exe, "sweep", ",".join(map(str, ns)), ",".join(map(str, ks)))
    for r in rows:
        for key, v in r.items():
            if key != "status":
                r[key] = float(v) if v else None
    return rows


def rate(rows, key, n_min=0):
    """Least-squares slope p of log e = p log h + c."""
    pts = [(r["h"], r[key]) for r in rows if r["n"] >= n_min]
    h, e = np.log([p[0] for p in pts]), np.log([p[1] for p in pts])
    return np.polyfit(h, e, 1)[0]


def plots(k14, k12, by_k, layers):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for ax, what, title in ((axes[0], "hess", "Hessian"), (axes[1], "grad", "gradient")):
        h = [r["h"] for r in k14]
        for key, style, label in ((f"{what}_err", "o-", "all"), (f"{what}_err_interior", "s--", "interior"),
                                  (f"{what}_err_boundary", "^:", "boundary band")):
            ax.loglog(h, [r[key] for r in k14], style, label=f"k = 14, {label} (p = {rate(k14, key):.2f})")
        for key, style, label in ((f"{what}_err", "o-", "all"), (f"{what}_err_interior", "s--", "interior")):
            ax.loglog(h, [r[key] for r in k12], style, color="gray", alpha=0.7,
                      label=f"k = 12, {label} (p = {rate(k12, key):.2f})")
        if what == "grad":
            for key, style, label in (("grad1_err", "o-", "all"), ("grad1_err_boundary", "^:", "boundary band")):
                ax.loglog(h, [r[key] for r in k14], style, color="tab:red", alpha=0.7,
                          label=f"first-order, k = 14, {label} (p = {rate(k14, key):.2f})")
        ax.set(xlabel="spacing h (N = (2/h)^2)", ylabel=f"relative L2 error of the {title}",
               title=f"{title} of w = exp(xy)(sin 3(x-y) - cos 2(x+y))")
        ax.grid(alpha=0.3, which="both"); ax.legend(fontsize=7)
    fig.tight_layout(); fig.savefig(os.path.join(DOCS, "hessian_accuracy_convergence.png"), dpi=90)

    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for n, rows in by_k.items():
        ok = [r for r in rows if r["hess_err"] is not None]
        ax.semilogy([r["k"] for r in ok], [r["hess_err"] for r in ok], "o-", label=f"Hessian, all, N = {n}^2")
        ax.semilogy([r["k"] for r in ok], [r["hess_err_interior"] for r in ok], "s--", label=f"Hessian, interior, N = {n}^2")
        ax.semilogy([r["k"] for r in ok], [r["grad_err"] for r in ok], "^:", label=f"gradient, all, N = {n}^2")
    for k in (8, 12, 20, 24, 28):
        ax.axvline(k, color="gray", lw=0.5)
    ax.set(xlabel="k (neighbours per family; grey: complete rings 8, 12, 20, 24, 28)", ylabel="relative L2 error",
           title="error against the number of neighbours")
    ax.grid(alpha=0.3, which="both"); ax.legend(fontsize=7)
    fig.tight_layout(); fig.savefig(os.path.join(DOCS, "hessian_accuracy_neighbours.png"), dpi=90)

    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for n, rows in layers.items():
        ax.semilogy([r["layer"] for r in rows], [r["hess"] for r in rows], "o-", label=f"Hessian, n = {n}")
        ax.semilogy([r["layer"] for r in rows], [r["grad"] for r in rows], "^:", label=f"gradient, n = {n}")
    ax.set(xlabel="layer (0 = outermost row of particles)",
           ylabel="RMS error in the layer / RMS exact value over all",
           title="error by distance from the boundary, k = 14")
    ax.grid(alpha=0.3, which="both"); ax.legend(fontsize=7)
    fig.tight_layout(); fig.savefig(os.path.join(DOCS, "hessian_accuracy_layers.png"), dpi=90)


def report(k14, k12, by_k, layers):
    fmt = lambda v: "-" if v is None else f"{v:.3e}"
    L = ["# Accuracy of the second-order nonlocal Hessian and gradient (seed 002 sec. 6.1)", "",
         "Generated by `/usr/bin/python3 verification/hessian_accuracy/hessian_accuracy.py "
         "build/verification/hessian_accuracy/hessian_accuracy` (see the script's and the program's headers). "
         f"Release build, one OpenMP thread ({platform.machine()}, {os.cpu_count()} cores; load average "
         f"{os.getloadavg()[0]:.1f} when the run ended: other jobs shared the machine). Times: neighbour search, "
         "assembly of the weights (bond_weights and the second-order NonlocalOperator), and the best of 20 products.", "",
         "w(x, y) = exp(xy) (sin 3(x - y) - cos 2(x + y)) on [-1, 1]^2, n x n particles at the cell centres of "
         "a regular lattice (h = 2/n), families of the k nearest neighbours (k-d tree), influence 1/r^2, "
         "operators `NonlocalOperator` of order 2 (THEORY sec. 6). Errors: relative L2 over particles (seed 002 eq. 102, "
         "Frobenius norm of the 2 x 2 Hessian error over that of the exact Hessian; the gradient likewise). "
         "*Interior*: particles whose family disc (radius delta_i, the distance to the k-th neighbour) lies inside "
         "the square; *boundary band*: the rest. Rates p are least-squares slopes of log e against log h "
         "(e ~ h^p); against N = n^2 the rate is p/2.", ""]

    p_all, p_fine = rate(k14, "hess_err"), rate(k14, "hess_err", 80)
    L += ["## 1. Resolution sweep, k = 14 (the seed's study)", "",
          "| n | N | h | Hessian, all | interior | boundary band | interior share | gradient, all | interior | boundary band "
          "| first-order gradient, all | boundary band "
          "| search (s) | assembly (s) | Hessian product (ms) | gradient product (ms) | operator (MB) |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in k14:
        L.append(f"| {int(r['n'])} | {int(r['N'])} | {r['h']:.4f} | {fmt(r['hess_err'])} | {fmt(r['hess_err_interior'])} "
                 f"| {fmt(r['hess_err_boundary'])} | {r['interior_fraction']:.3f} | {fmt(r['grad_err'])} "
                 f"| {fmt(r['grad_err_interior'])} | {fmt(r['grad_err_boundary'])} | {fmt(r['grad1_err'])} "
                 f"| {fmt(r['grad1_err_boundary'])} | {r['t_search']:.3f} "
                 f"| {r['t_assembly']:.3f} | {1e3 * r['t_hessian']:.3f} | {1e3 * r['t_gradient']:.3f} "
                 f"| {r['operator_bytes'] / 1e6:.1f} |")
    L += ["", "Fitted rates p (e ~ h^p), all nine resolutions / only n >= 80:", "",
          "| quantity | k = 14, all n | k = 14, n >= 80 | k = 12, all n | k = 12, n >= 80 |", "|---|---|---|---|---|"]
    for key, name in (("hess_err", "Hessian, all particles"), ("hess_err_interior", "Hessian, interior"),
                      ("hess_err_boundary", "Hessian, boundary band"), ("grad_err", "gradient, all particles"),
                      ("grad_err_interior", "gradient, interior"), ("grad_err_boundary", "gradient, boundary band"),
                      ("grad1_err", "first-order gradient, all"), ("grad1_err_interior", "first-order gradient, interior"),
                      ("grad1_err_boundary", "first-order gradient, boundary band")):
        L.append(f"| {name} | {rate(k14, key):.3f} | {rate(k14, key, 80):.3f} | {rate(k12, key):.3f} "
                 f"| {rate(k12, key, 80):.3f} |")
    L += ["", f"**Hessian rate, k = 14: p = {p_all:.3f} in h** ({p_fine:.3f} over n >= 80), that is "
          f"{p_all / 2:.3f} in N; the seed reports {SEED_RATE} (its figure plots against N, but the text does "
          "not say which variable the rate refers to). The gradient converges with p = "
          f"{rate(k14, 'grad_err'):.2f}.", "",
          "![convergence](hessian_accuracy_convergence.png)", ""]

    L += ["## 2. The same with k = 12 (symmetric families)", "",
          "| n | Hessian, all | interior | boundary band | gradient, all | interior | boundary band "
          "| first-order gradient, all | interior | boundary band |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for r in k12:
        L.append(f"| {int(r['n'])} | {fmt(r['hess_err'])} | {fmt(r['hess_err_interior'])} | {fmt(r['hess_err_boundary'])} "
                 f"| {fmt(r['grad_err'])} | {fmt(r['grad_err_interior'])} | {fmt(r['grad_err_boundary'])} "
                 f"| {fmt(r['grad1_err'])} | {fmt(r['grad1_err_interior'])} | {fmt(r['grad1_err_boundary'])} |")
    L.append("")

    L += ["## 3. Neighbour sweep", ""]
    for n, rows in by_k.items():
        singular = [int(r["k"]) for r in rows if r["hess_err"] is None]
        L += [f"N = {n}^2" + (f"; k = {', '.join(map(str, singular))}: K singular at some particle "
                              "(reported by the operator, not measured)" if singular else "") + ".", "",
              "| k | Hessian, all | interior | boundary band | gradient, all | interior share |", "|---|---|---|---|---|---|"]
        for r in rows:
            if r["hess_err"] is not None:
                L.append(f"| {int(r['k'])} | {fmt(r['hess_err'])} | {fmt(r['hess_err_interior'])} "
                         f"| {fmt(r['hess_err_boundary'])} | {fmt(r['grad_err'])} | {r['interior_fraction']:.3f} |")
        L.append("")
    L += ["![neighbours](hessian_accuracy_neighbours.png)", ""]

    L += ["## 4. Error by layer from the boundary, k = 14", "",
          "Layer l: particles at distance [l h, (l + 1) h) from the boundary. Error: the RMS error over the layer "
          "divided by the RMS of the exact value over all particles (so layers compare with each other and with "
          "the *all* column of section 1). *Share*: the layer's part of the squared Hessian error summed over all "
          "particles. The last row: layers 6 and more together.", "",
          "| layer | " + " | ".join(f"Hessian, n = {n} | share | gradient, n = {n}" for n in layers) + " |",
          "|---|" + "---|---|---|" * len(layers)]
    for l in range(6):
        cells = []
        for n, rows in layers.items():
            total = sum(r["hess_sq_err"] for r in rows)
            r = rows[l]
            cells.append(f"{fmt(r['hess'])} | {r['hess_sq_err'] / total:.2f} | {fmt(r['grad'])}")
        L.append(f"| {l} | " + " | ".join(cells) + " |")
    cells = []
    for n, rows in layers.items():
        inner = [r for r in rows if r["layer"] >= 6]
        total = sum(r["hess_sq_err"] for r in rows)
        rms = lambda key: np.sqrt(sum(r[key + "_sq_err"] for r in inner) / sum(r["particles"] for r in inner))
        cells.append(f"{fmt(rms('hess') / rows[0]['hess_rms'])} | {sum(r['hess_sq_err'] for r in inner) / total:.2f} "
                     f"| {fmt(rms('grad') / rows[0]['grad_rms'])}")
    L.append("| 6 and more | " + " | ".join(cells) + " |")
    L += ["", "![layers](hessian_accuracy_layers.png)", ""]
    return L


def main():
    exe = os.path.abspath(sys.argv[1])
    k14 = sweep(exe, NS, [14])
    k12 = sweep(exe, NS, [12])
    by_k = {n: sweep(exe, [n], KS) for n in (60, 180)}
    layers = {}
    for n in (100, 200):
        rows = [{k: float(v) for k, v in r.items()} for r in table(exe, "layers", n, 14)]
        count = sum(r["particles"] for r in rows)
        for what in ("grad", "hess"):
            rms = np.sqrt(sum(r[what + "_sq_exact"] for r in rows) / count)
            for r in rows:
                r[what] = np.sqrt(r[what + "_sq_err"] / r["particles"]) / rms
                r[what + "_rms"] = rms
        layers[n] = rows
    plots(k14, k12, by_k, layers)
    lines = report(k14, k12, by_k, layers)
    explanation = os.path.join(HERE, "explanation.md")
    lines += open(explanation).read().splitlines()
    open(os.path.join(DOCS, "hessian_accuracy.md"), "w").write("\n".join(lines) + "\n")
    print(f"Hessian rate (k = 14): {rate(k14, 'hess_err'):.3f} in h; gradient {rate(k14, 'grad_err'):.3f}")


if __name__ == "__main__":
    main()
