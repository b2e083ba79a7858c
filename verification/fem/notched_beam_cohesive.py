#!/usr/bin/env python3
"""A cohesive-crack FEM reference for the notched beam (docs/verification/notched_beam.md).

Why
  perinom's softening bonds (damage.fracture_energy) are meant to converge, as the spacing
  and the horizon shrink, to a local elastic body with a cohesive crack. This script solves
  that limit directly, so that the peaks of notched_beam.py can be read against the answer
  their model should reach, and against the experiments (Gregoire, Rojas-Solano and
  Pijaudier-Cabot 2013: 0.93-1.11 kN).

What is solved
  The beam of examples/notched_beam.yaml: 175 x 50 mm, 50 mm thick, plane stress, E = 37 GPa,
  nu = 0.2, supports at x = 25 and 150 mm on the bottom face (points), a 25 mm notch at
  x = 87.5 mm, the load by a rigid patch x in [85, 90] mm, y >= 47.5 mm (the scene's grip box)
  moved down by Delta. By symmetry the left half, with the crack on x = 87.5 mm: the notch
  (y < 25 mm) is free, the ligament (y >= 25 mm) carries a cohesive traction T(w) along x,
  w = -2 u_x the opening, f_t = 3.9 MPa, G_f = 143.2 N/m. Three softening laws of the same
  f_t and G_f:
  - "bonds": what perinom's softening bonds give a flat crack in 2-D in the continuum limit:
    a bond at angle theta to the normal opens by w cos(theta) and its normal force falls
    linearly to zero at eta_u = pi G_f / (2 f_t) (docs/theory.md, "Softening bonds"), so
    T(w) = f_t (2/pi) int_{-pi/2}^{pi/2} cos^2(theta) max(0, 1 - w cos(theta) / eta_u) dtheta
    (T(0) = f_t, its area G_f);
  - "linear": T = f_t (1 - w / w_c), w_c = 2 G_f / f_t (Hillerborg's fictitious crack);
  - "bilinear": Petersson (1981), from f_t to f_t / 3 at w_1 = 0.8 G_f / f_t, then to zero at
    3.6 G_f / f_t;
  - "bonds_grip": the bonds' law with the ligament above y = 42 mm held closed (the penalty
    only), as the scene's no-fail box under the load holds it (its bonds never break).
  Before it opens the crack is held by a penalty k_p = f_t / w_e, w_e = 1e-10 m (about 600
  times an element's stiffness E / h at h = 0.625 mm), which also keeps the faces from
  interpenetrating.

How
  Bilinear quadrilaterals (2 x 2 Gauss points) on a uniform square grid of size h = 1.25,
  0.625 and 0.3125 mm, so that the notch tip, the support and the patch's edge are nodes.
  The body is linear: K is factorised once (scipy splu), and the problem is condensed onto
  the ligament's u_x: u_L = a Delta + C q(u_L), q the cohesive nodal forces (tributary length
  times the thickness times T), C the flexibility between ligament nodes, and the load is
  P = 2 (p_D Delta + p . q). Each load step (0.1 um of Delta, as in notched_beam.py) solves
  the small system by Newton from the last state (halving the step where it does not
  converge); the crack only opens under this monotone loading, so no unloading branch is
  needed (checked: every ligament node's opening grows from step to step).

Checks the script makes (it stops if one fails): the work of the load (the trapezoid of the
curve) equals the strain energy plus the work of the cohesive tractions to 1e-3; openings
never decrease (the loading is monotone); the finest two grids' peaks agree to 1%.

Output: verification/fem/notched_beam_cohesive.csv (law, h, peak, displacement at the peak),
verification/fem/notched_beam_cohesive_curves.csv (the finest grid's curves).

Run: /usr/bin/python3 verification/fem/notched_beam_cohesive.py   (about a minute)
"""
import csv
import os
import sys

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

HERE = os.path.dirname(os.path.abspath(__file__))
E, NU, B = 37.0e9, 0.2, 0.05  # Pa, -, thickness (m)
F_T, G_F = 3.9e6, 143.2  # Pa, N/m
HALF, DEPTH, NOTCH, SUPPORT = 0.0875, 0.05, 0.025, 0.025  # m
PATCH_X, PATCH_Y = 0.085, 0.0475  # the load patch: x >= PATCH_X, y >= PATCH_Y (m)
W_E = 1.0e-10  # the penalty's opening at f_t (m)
GRIP_Y = 0.042  # "bonds_grip": the ligament above this height never opens (the scene's no-fail box under the load)
STEP, TOTAL = 1.0e-7, 9.0e-5  # load-point displacement per step and in all (m), as notched_beam.py


def law(name):
    """T(w) and dT/dw for w >= 0 (the penalty is added by the caller)."""
    if name == "linear":
        wc = 2.0 * G_F / F_T
        return lambda w: (F_T * max(0.0, 1.0 - w / wc), -F_T / wc if w < wc else 0.0)
    if name == "bilinear":
        w1, wc = 0.8 * G_F / F_T, 3.6 * G_F / F_T
        k1, k2 = (F_T - F_T / 3.0) / w1, (F_T / 3.0) / (wc - w1)
        return lambda w: ((F_T - k1 * w, -k1) if w < w1 else ((F_T / 3.0 - k2 * (w - w1), -k2) if w < wc else (0.0, 0.0)))
    if name in ("bonds", "bonds_grip"):
        eta_u = np.pi * G_F / (2.0 * F_T)
        n = 20000
        th = (np.arange(n) + 0.5) * (np.pi / n) - np.pi / 2.0  # midpoints on (-pi/2, pi/2)
        c, dth = np.cos(th), np.pi / n

        def T(w):
            live = w * c < eta_u
            val = F_T * (2.0 / np.pi) * np.sum(c[live] ** 2 * (1.0 - w * c[live] / eta_u)) * dth
            der = -F_T * (2.0 / np.pi) * np.sum(c[live] ** 3 / eta_u) * dth
            return val, der
        return T
    raise ValueError(name)


def traction(T, w):
    """The traction with the penalty before the crack opens (and against interpenetration)."""
    if w < W_E:
        return F_T * w / W_E, F_T / W_E
    return T(w - W_E)


def assemble(h):
    nx, ny = round(HALF / h), round(DEPTH / h)
    D = E / (1.0 - NU * NU) * np.array([[1.0, NU, 0.0], [NU, 1.0, 0.0], [0.0, 0.0, (1.0 - NU) / 2.0]])
    ke = np.zeros((8, 8))
    g = 1.0 / np.sqrt(3.0)
    for xi in (-g, g):
        for eta in (-g, g):
            dN = 0.25 * np.array([[-(1 - eta), (1 - eta), (1 + eta), -(1 + eta)],
                                  [-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)]]) * (2.0 / h)
            Bm = np.zeros((3, 8))
            Bm[0, 0::2], Bm[1, 1::2] = dN[0], dN[1]
            Bm[2, 0::2], Bm[2, 1::2] = dN[1], dN[0]
            ke += Bm.T @ D @ Bm * (h * h / 4.0) * B
    node = lambda i, j: j * (nx + 1) + i
    I, J = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    corners = np.stack([node(I, J), node(I + 1, J), node(I + 1, J + 1), node(I, J + 1)], -1).reshape(-1, 4)
    dofs = np.repeat(corners * 2, 2, axis=1) + np.tile([0, 1], 4)
    rows, cols = np.repeat(dofs, 8, axis=1).ravel(), np.tile(dofs, 8).ravel()
    n = 2 * (nx + 1) * (ny + 1)
    K = sp.coo_matrix((np.tile(ke.ravel(), len(dofs)), (rows, cols)), shape=(n, n)).tocsc()
    xs = np.tile(np.arange(nx + 1) * h, ny + 1)
    ys = np.repeat(np.arange(ny + 1) * h, nx + 1)
    return K, xs, ys, nx, ny


def solve(h, names):
    K, xs, ys, nx, ny = assemble(h)
    n = K.shape[0]
    eps = 1e-9 * h
    support = np.flatnonzero((np.abs(xs - SUPPORT) < eps) & (ys < eps))
    patch = np.flatnonzero((xs > PATCH_X - eps) & (ys > PATCH_Y - eps))
    lig = np.flatnonzero((np.abs(xs - HALF) < eps) & (ys > NOTCH - eps))
    lig = lig[np.argsort(ys[lig])]
    # The top node of the crack's line is held at u_x = 0: the half beam has no other hold on
    # x, and the compressed top never opens (its reaction is checked to push, below).
    top, lig = lig[-1], lig[:-1]
    trib = np.full(len(lig), h)
    trib[0] = h / 2.0  # the notch tip
    prescribed = np.concatenate([2 * support + 1, [2 * top], 2 * patch + 1])
    p = np.concatenate([np.zeros(len(support) + 1), -np.ones(len(patch))])  # u_P = p Delta
    free = np.setdiff1d(np.arange(n), prescribed)
    Kff, Kfp = K[free][:, free].tocsc(), K[free][:, prescribed]
    lu = spla.splu(Kff)
    at = {d: k for k, d in enumerate(free)}
    L = np.array([at[2 * i] for i in lig])  # the ligament's u_x among the free dofs
    rhs = np.zeros((len(free), 1 + len(L)))
    rhs[:, 0] = -(Kfp @ p)
    rhs[L, 1 + np.arange(len(L))] = 1.0
    G = lu.solve(rhs)  # u_F for Delta = 1, and for a unit force at each ligament dof
    a, C = G[L, 0], G[L, 1:]
    load = np.arange(len(support) + 1, len(prescribed))
    hold = len(support)  # the top node's x
    Kpf, Kpp = K[prescribed][:, free], K[prescribed][:, prescribed]
    R = Kpf @ G  # the prescribed dofs' forces for each column (u_P = 0 but column 0)
    R[:, 0] += Kpp @ p
    pD, pq = -R[load, 0].sum(), -R[load, 1:].sum(axis=0)  # the downward load on the patch
    out = {}
    for name in names:
        T = law(name)
        # "bonds_grip": the nodes in the scene's no-fail grip keep the penalty, never softening.
        held = (ys[lig] >= GRIP_Y - eps) if name == "bonds_grip" else np.zeros(len(lig), bool)

        def q_of(u):
            w = -2.0 * u
            tq = [(F_T * x / W_E, F_T / W_E) if k else traction(T, x) for x, k in zip(w, held)]
            q = np.array([t[0] for t in tq]) * trib * B
            dq = np.array([t[1] for t in tq]) * trib * B * (-2.0)
            return q, dq

        u = np.zeros(len(L))
        D, dD = 0.0, STEP
        curve, w_last = [(0.0, 0.0)], -2.0 * u
        while D < TOTAL - 1e-15:
            target = min(D + dD, TOTAL)
            x = u.copy()
            ok = False
            for _ in range(60):
                q, dq = q_of(x)
                r = x - a * target - C @ q
                if np.linalg.norm(r) < 1e-12 * max(1e-9, np.abs(x).max()) + 1e-18:
                    ok = True
                    break
                x -= np.linalg.solve(np.eye(len(L)) - C * dq[None, :], r)
            if not ok:
                dD /= 2.0
                if dD < STEP / 1024:
                    sys.exit(f"{name} h {h}: Newton does not converge at Delta = {D}")
                continue
            u, D = x, target
            w = -2.0 * u
            if np.any((w_last > W_E) & (w < w_last - 1e-15) & ~held):  # an open face closing
                sys.exit(f"{name} h {h}: an opening decreased (unloading is not modelled)")
            w_last = w
            q, _ = q_of(u)
            curve.append((D, 2.0 * (pD * D + pq @ q)))
            if R[hold, 0] * D + R[hold, 1:] @ q > 0.0:
                sys.exit(f"{name} h {h}: the top node of the crack's line is pulled open (its hold is wrong)")
            dD = min(STEP, dD * 2.0)
        c = np.array(curve)
        # The energy: the work of the load (trapezoid) less the strain energy of the half beam,
        # against the cohesive work done along the ligament (both halves: times 2).
        uF = G[:, 0] * D + G[:, 1:] @ q
        uP = p * D
        full = np.zeros(n)
        full[free], full[prescribed] = uF, uP
        strain = 0.5 * full @ (K @ full)
        work = np.trapz(c[:, 1], c[:, 0]) / 2.0  # per half
        w = -2.0 * u
        ws = np.linspace(0.0, max(w.max(), 2.0 * W_E), 20001)  # the work of T up to each opening
        Ts = np.array([traction(T, x)[0] for x in ws])
        area = np.concatenate([[0.0], np.cumsum(0.5 * (Ts[1:] + Ts[:-1]) * np.diff(ws))])
        stored = np.where(held, 0.5 * F_T / W_E * w * w, np.interp(w, ws, area))  # per unit area
        cohesive = float(np.sum(stored * trib * B / 2.0))  # the half's faces move w / 2
        out[name] = dict(curve=c, peak=c[:, 1].max(), at=c[np.argmax(c[:, 1]), 0],
                         work=work, strain=strain, cohesive=cohesive, nodes=len(L))
        print(f"h {h * 1e3:.4f} mm {name:8s}: peak {c[:, 1].max():8.2f} N at {c[np.argmax(c[:, 1]), 0] * 1e3:.4f} mm; "
              f"work {work:.5g} J = strain {strain:.5g} + cohesive {cohesive:.5g} ({(strain + cohesive) / work - 1:+.1e})",
              flush=True)
        if abs((strain + cohesive) / work - 1.0) > 1e-3:
            sys.exit(f"{name} h {h}: the energy does not balance")
    return out


def main():
    names = ["bonds", "linear", "bilinear", "bonds_grip"]
    sizes = [1.25e-3, 0.625e-3, 0.3125e-3]
    res = {h: solve(h, names) for h in sizes}
    for name in names:
        a, b = res[sizes[-2]][name]["peak"], res[sizes[-1]][name]["peak"]
        if abs(a - b) / b > 0.01:
            sys.exit(f"{name}: the finest two grids' peaks differ by {abs(a - b) / b:.2%}")
    with open(os.path.join(HERE, "notched_beam_cohesive.csv"), "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["law", "h_m", "peak_N", "at_m"])
        for h in sizes:
            for name in names:
                r = res[h][name]
                wr.writerow([name, h, f"{r['peak']:.6g}", f"{r['at']:.6g}"])
    with open(os.path.join(HERE, "notched_beam_cohesive_curves.csv"), "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["law", "displacement_m", "load_N"])
        for name in names:
            for D, P in res[sizes[-1]][name]["curve"][::10]:
                wr.writerow([name, f"{D:.6g}", f"{P:.6g}"])


if __name__ == "__main__":
    main()
