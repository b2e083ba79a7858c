#!/usr/bin/python3
"""The Lame quarter cylinder (a = 10 mm, b = 20 mm) cut from a square lattice: the
staircase counterpart of the gmsh meshes, for the lattice-against-mesh comparison of
verification/lame/README.md.

  verification/lame/lattice_points.py M OUTDIR

writes OUTDIR/lame_lattice_mM_points.csv and _facets.csv: the cells of spacing h = (b - a)/M
on [0, b]^2 whose centre lies in a <= r <= b, one particle per cell (volume h^2, thickness
1 m), and a facet on every cell side whose neighbour is not in the body, with its axis-aligned
outward normal, grouped as on the mesh: xaxis (y = 0), yaxis (x = 0), inner (the neighbour's
centre inside r < a) and outer. Run it with lame.yaml and
--set geometry.points=... --set geometry.facets=... (geometry.mesh removed: see the README).
"""
import math
import os
import sys

A, B = 0.01, 0.02


def main():
    m, out = int(sys.argv[1]), sys.argv[2]
    h = (B - A) / m
    n = int(round(B / h))
    inside = lambda i, j: 0 <= i < n and 0 <= j < n and A <= math.hypot((i + 0.5) * h, (j + 0.5) * h) <= B
    index = {}
    with open(os.path.join(out, f"lame_lattice_m{m}_points.csv"), "w") as f:
        f.write("x,y,volume\n")
        for j in range(n):
            for i in range(n):
                if inside(i, j):
                    index[(i, j)] = len(index)
                    f.write(f"{(i + 0.5) * h!r},{(j + 0.5) * h!r},{h * h!r}\n")
    with open(os.path.join(out, f"lame_lattice_m{m}_facets.csv"), "w") as f:
        f.write("particle,area,nx,ny,x,y,group\n")
        for (i, j), k in index.items():
            for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1)):
                if inside(i + di, j + dj):
                    continue
                x, y = (i + 0.5 + 0.5 * di) * h, (j + 0.5 + 0.5 * dj) * h
                if i + di < 0:
                    group = "yaxis"
                elif j + dj < 0:
                    group = "xaxis"
                else:
                    r = math.hypot((i + di + 0.5) * h, (j + dj + 0.5) * h)
                    group = "inner" if r < A else "outer"
                f.write(f"{k},{h!r},{di},{dj},{x!r},{y!r},{group}\n")
    print(f"{len(index)} particles, spacing {h} m")


if __name__ == "__main__":
    main()
