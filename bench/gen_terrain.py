#!/usr/bin/env python3
"""Writes a deterministic height-field terrain as an OFF mesh (bench/run_all, section f).

    bench/gen_terrain.py OUT.off [--grid 708]

A GRID x GRID grid of vertices over [-1, 1]^2 (default 708 x 708: 707^2 cells, two
triangles each, 999,698 triangles), heights a fixed sum of sines and cosines (a few
long ridges, some hills, fine ripples: a "real-looking" scene whose ridges hide what
lies behind them in an oblique view). Coordinates are written with 6 decimals, so the
file is the same byte for byte on every machine. Python standard library only.
"""

import argparse
import math
import sys

# (amplitude, kx, ky, phase): z = sum a * sin(kx x + ky y + phase), plus a product term.
WAVES = [
    (0.120, 2.1, 0.7, 0.3),
    (0.080, -1.3, 2.9, 1.1),
    (0.045, 4.7, -3.1, 2.0),
    (0.030, 7.3, 5.9, 0.7),
    (0.015, -11.9, 9.1, 4.2),
    (0.008, 17.3, 19.7, 1.9),
    (0.004, -31.1, 27.3, 0.4),
]


def height(x, y):
    z = sum(a * math.sin(kx * x + ky * y + ph) for a, kx, ky, ph in WAVES)
    z += 0.06 * math.cos(3.3 * x) * math.cos(2.7 * y + 0.5)
    return z


def write_terrain(path, grid):
    if grid < 2:
        raise ValueError("--grid must be at least 2")
    cells = grid - 1
    nv, nf = grid * grid, 2 * cells * cells
    with open(path, "w") as f:
        f.write("OFF\n")
        f.write(f"# height-field terrain, bench/gen_terrain.py --grid {grid}\n")
        f.write(f"{nv} {nf} 0\n")
        step = 2.0 / cells
        lines = []
        for j in range(grid):
            y = -1.0 + j * step
            for i in range(grid):
                x = -1.0 + i * step
                lines.append(f"{x:.6f} {y:.6f} {height(x, y):.6f}\n")
            if len(lines) >= 65536:
                f.writelines(lines)
                lines = []
        f.writelines(lines)
        lines = []
        for j in range(cells):
            for i in range(cells):
                a = j * grid + i
                b, c, d = a + 1, a + grid + 1, a + grid
                # alternate the diagonal so the triangulation has no preferred direction
                if (i + j) % 2 == 0:
                    lines.append(f"3 {a} {b} {c}\n3 {a} {c} {d}\n")
                else:
                    lines.append(f"3 {a} {b} {d}\n3 {b} {c} {d}\n")
            if len(lines) >= 32768:
                f.writelines(lines)
                lines = []
        f.writelines(lines)
    return nv, nf


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="the OFF file to write")
    ap.add_argument("--grid", type=int, default=708, help="vertices per side (default 708: about 10^6 triangles)")
    args = ap.parse_args()
    nv, nf = write_terrain(args.out, args.grid)
    print(f"{args.out}: {nv} vertices, {nf} triangles", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
