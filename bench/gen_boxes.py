#!/usr/bin/env python3
"""Writes N^3 boxes on a cubic lattice as OFF: the other many-object scene of the
BSP and priority benchmarks (issue 14: "20^3 boxes"). Box (i, j, k) is a closed
cube of 6 quads from (i, j, k) with a side of 0.3 to 0.53 (on a 1/64 grid), so
the boxes never touch and many of their edges lie on common lines.

    bench/gen_boxes.py OUT.off [--n N] [--seed S]

Deterministic for a given seed (Python's random). Standard library only.
"""
import argparse
import random

from gen_city import box, write_off   # (bench/: the city's box and writer)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--n", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    rng = random.Random(a.seed)
    verts, faces = [], []
    for i in range(a.n):
        for j in range(a.n):
            for k in range(a.n):
                s = 0.3 + rng.randrange(0, 16) / 64
                v, f = box(i, j, k, i + s, j + s, k + s)
                base = len(verts)
                verts.extend(v)
                faces.extend(tuple(base + q for q in quad) for quad in f)
    write_off(a.out, "%d^3 boxes, seed %d (bench/gen_boxes.py)" % (a.n, a.seed), verts, faces)


if __name__ == "__main__":
    main()
