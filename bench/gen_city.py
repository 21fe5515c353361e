#!/usr/bin/env python3
"""Writes a city of box buildings as OFF: the many-object scene of the BSP and
priority benchmarks (issue 14). Each building is a closed box of 6 quads on a
jittered grid, heights varied, some blocks with a lower annex that touches the
main building (shared face planes: degenerate on purpose).

    bench/gen_city.py OUT.off [--buildings N] [--seed S]

Deterministic for a given seed (Python's random). Standard library only.
"""
import argparse
import math
import random


def box(x0, y0, z0, x1, y1, z1):
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    # Outward-facing quads (counter-clockwise seen from outside).
    f = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return v, f


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--buildings", type=int, default=10000)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    rng = random.Random(a.seed)
    side = max(1, math.ceil(math.sqrt(a.buildings)))
    verts, faces = [], []
    for i in range(a.buildings):
        gx, gy = i % side, i // side
        # Lot of 1 x 1 with a street of 0.3: the building within it, jittered on a 1/64 grid.
        w = 0.4 + rng.randrange(0, 20) / 64
        d = 0.4 + rng.randrange(0, 20) / 64
        x0 = gx * 1.3 + rng.randrange(0, 16) / 64
        y0 = gy * 1.3 + rng.randrange(0, 16) / 64
        h = 0.3 + rng.randrange(0, 160) / 64
        parts = [(x0, y0, 0, x0 + w, y0 + d, h)]
        if rng.random() < 0.3:   # an annex against the east wall, lower
            parts.append((x0 + w, y0, 0, x0 + w + 0.2, y0 + d / 2, h / 2))
        for p in parts:
            v, f = box(*p)
            base = len(verts)
            verts.extend(v)
            faces.extend(tuple(base + k for k in q) for q in f)
    write_off(a.out, "city of %d buildings, seed %d (bench/gen_city.py)" % (a.buildings, a.seed), verts, faces)


def write_off(path, comment, verts, faces):
    """Quads as OFF, coordinates exactly (%.17g)."""
    with open(path, "w") as out:
        out.write("OFF\n# %s\n" % comment)
        out.write("%d %d 0\n" % (len(verts), len(faces)))
        for x, y, z in verts:
            out.write("%.17g %.17g %.17g\n" % (x, y, z))
        for q in faces:
            out.write("4 %d %d %d %d\n" % q)


if __name__ == "__main__":
    main()
