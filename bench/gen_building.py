#!/usr/bin/env python3
"""Writes a deterministic generated building as an OFF mesh (bench/run_all, section g).

    bench/gen_building.py OUT.off [--rooms NX,NY] [--floors K]

A grid of NX x NY rooms (default 6 x 6) on K floors (default 2), every part a closed box
of 6 quads, each counter-clockwise seen from outside (outward normals), boxes touching
face to face where a real building's parts touch (walls on slabs, walls against pillars,
books on boards), never interpenetrating:

  * a slab under every floor and a roof slab (0.2 m thick, over the whole footprint);
  * walls 0.2 m thick on a grid of 4 m (x) by 5 m (y), floor to floor 3 m, a square
    pillar at every grid crossing, the wall segments between pillars;
  * openings cut out of the wall segments: a wall with an opening is the boxes around
    it (left and right parts full height, a lintel above, a sill below a window).
    Interior walls get a door (0.9 x 2.1 m) with probability 0.65, off-centre; the
    exterior walls a window (1.2 x 1.2 m, sill at 0.9 m), on the ground floor one of
    them the entrance door instead;
  * furniture in every room: a table (top and four legs), two to four chairs (seat,
    four legs, back), a shelf against an interior wall (two sides and four or five
    boards) with rows of books of random widths and heights on its boards, and a
    cabinet in a corner.

Sizes, positions and counts come from a fixed 64-bit generator with a fixed seed; every
coordinate is an integer number of millimetres, written in metres with 3 decimals, so
touching faces coincide exactly and the file is the same byte for byte on every machine.
Each box's closure is checked before writing (every edge used by exactly two of its faces,
once in each direction; positive volume). Python standard library only.

The parts are written in an order that keeps a part's edges drawn where they lie on the
face of the part it touches (see Mesh). The defaults give 4 840 boxes, 29 040 quads.

It prints two suggested cameras on standard output (with the defaults):

    interior: --eye 4.8,17.5,1.8 --target 8,17.02,1.6 --fov 60
    exterior: --eye 57.3,-37.85,40.85 --target 12,15,3.1 --fov 30

The interior eye is in room (1, NY/2) on the ground floor, 1.6 m above its floor, on the
room's middle line 0.7 m in front of its -x wall, looking at the middle of the door in its
+x wall (slightly down), through it into the next room: the room's own table and chairs,
its walls, floor and ceiling, and the next room through the door. The exterior eye is
section (f)'s perspective view: the bounding box's centre + L*(1.5, -1.75, 1.25), L its
largest side, looking at the centre, fov 30.
"""

import argparse
import sys

PX, PY = 4000, 5000       # the room grid's pitch (mm)
T = 200                   # wall thickness, pillar side
H = 3000                  # floor to floor
S = 200                   # slab thickness
DOOR_W, DOOR_H = 900, 2100
WIN_W, WIN_SILL, WIN_TOP = 1200, 900, 2100
EYE_H = 1600              # interior eye above the floor
EYE_BACK = 700            # and in front of the room's -x wall (clear of shelves and the cabinet)
SEED = 0x5EED0B1D


class Rng:
    """splitmix64: the same numbers on every machine and Python version."""

    def __init__(self, seed):
        self.s = seed & 0xFFFFFFFFFFFFFFFF

    def next(self):
        self.s = (self.s + 0x9E3779B97F4A7C15) & 0xFFFFFFFFFFFFFFFF
        z = self.s
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & 0xFFFFFFFFFFFFFFFF
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & 0xFFFFFFFFFFFFFFFF
        return z ^ (z >> 31)

    def int(self, lo, hi):
        """An integer in [lo, hi]."""
        return lo + self.next() % (hi - lo + 1)

    def chance(self, p_percent):
        return self.next() % 100 < p_percent


class Mesh:
    """Boxes, written by level: level 0 first, then what those parts stand on or lean against
    (level 1: wall parts beside an opening, shelf boards, seats, table tops; 2: shelf sides;
    3: slabs). Where a part's edge lies inside a face of the part it touches, the two are at
    equal depth there, and the face with the lower index wins (the JSON spec's tie rule): the
    part's edge (a wall's foot on the slab, a book's on its board, a lintel's against the jamb)
    stays drawn."""

    def __init__(self):
        self.levels = {}
        self.verts = []
        self.faces = []

    def box(self, x0, x1, y0, y1, z0, z1, level=0):
        if not (x0 < x1 and y0 < y1 and z0 < z1):
            raise ValueError(f"empty box {(x0, x1, y0, y1, z0, z1)}")
        self.levels.setdefault(level, []).append((x0, x1, y0, y1, z0, z1))

    @property
    def boxes(self):
        return sum(len(b) for b in self.levels.values())

    def build(self):
        """Vertices (8 per box) and faces (6 quads per box, counter-clockwise seen from outside)."""
        self.verts, self.faces = [], []
        for x0, x1, y0, y1, z0, z1 in (b for level in sorted(self.levels) for b in self.levels[level]):
            b = len(self.verts)
            for z in (z0, z1):
                for y in (y0, y1):
                    for x in (x0, x1):
                        self.verts.append((x, y, z))

            def v(ix, iy, iz):
                return b + ix + 2 * iy + 4 * iz
            self.faces += [
                (v(0, 0, 0), v(0, 1, 0), v(1, 1, 0), v(1, 0, 0)),   # -z
                (v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1)),   # +z
                (v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1)),   # -y
                (v(0, 1, 0), v(0, 1, 1), v(1, 1, 1), v(1, 1, 0)),   # +y
                (v(0, 0, 0), v(0, 0, 1), v(0, 1, 1), v(0, 1, 0)),   # -x
                (v(1, 0, 0), v(1, 1, 0), v(1, 1, 1), v(1, 0, 1)),   # +x
            ]

    def check(self):
        """Every box closed and outward: each directed edge once, its reverse once, volume > 0."""
        self.build()
        for k in range(self.boxes):
            faces = self.faces[6 * k:6 * k + 6]
            edges = {}
            for f in faces:
                for a, b in zip(f, f[1:] + f[:1]):
                    edges[(a, b)] = edges.get((a, b), 0) + 1
            if len(edges) != 24 or any(n != 1 or edges.get((b, a)) != 1 for (a, b), n in edges.items()):
                raise AssertionError(f"box {k} is not closed")
            vol6 = 0
            for f in faces:
                p0 = self.verts[f[0]]
                for i in (1, 2):
                    p1, p2 = self.verts[f[i]], self.verts[f[i + 1]]
                    vol6 += (p0[0] * (p1[1] * p2[2] - p1[2] * p2[1]) - p0[1] * (p1[0] * p2[2] - p1[2] * p2[0])
                             + p0[2] * (p1[0] * p2[1] - p1[1] * p2[0]))
            if vol6 <= 0:
                raise AssertionError(f"box {k} is not outward oriented")

    def write(self, path, comment):
        with open(path, "w") as f:
            f.write("OFF\n")
            f.write(f"# {comment}\n")
            f.write(f"{len(self.verts)} {len(self.faces)} 0\n")
            f.writelines(f"{mm(x)} {mm(y)} {mm(z)}\n" for x, y, z in self.verts)
            f.writelines(f"4 {a} {b} {c} {d}\n" for a, b, c, d in self.faces)


def mm(v):
    """Millimetres as metres with 3 decimals (exact: v is an integer)."""
    s = "-" if v < 0 else ""
    v = abs(v)
    return f"{s}{v // 1000}.{v % 1000:03d}"


def wall(mesh, axis, a, b, c, z0, z1, opening):
    """A wall segment along `axis` ('x' or 'y') from a to b, centred at c across it, from z0 to z1,
    with opening (o0, o1, zb, zt) or None: the boxes around the opening."""
    def put(u0, u1, w0, w1, level):
        if axis == "x":
            mesh.box(u0, u1, c - T // 2, c + T // 2, w0, w1, level)
        else:
            mesh.box(c - T // 2, c + T // 2, u0, u1, w0, w1, level)
    if opening is None:
        put(a, b, z0, z1, 1)
        return
    o0, o1, zb, zt = opening
    put(o0, o1, zt, z1, 0)          # lintel
    if zb > z0:
        put(o0, o1, z0, zb, 0)      # sill
    put(a, o0, z0, z1, 1)
    put(o1, b, z0, z1, 1)


def generate(nx, ny, floors):
    rng = Rng(SEED)
    mesh = Mesh()
    cam_room = (min(1, nx - 1), ny // 2)
    cam = None
    xlo, xhi, ylo, yhi = -T // 2, nx * PX + T // 2, -T // 2, ny * PY + T // 2
    entrance = rng.int(0, nx - 1)              # on the ground floor's y = 0 wall
    for k in range(floors + 1):
        mesh.box(xlo, xhi, ylo, yhi, k * H, k * H + S, level=3)
    for k in range(floors):
        z0, z1 = k * H + S, (k + 1) * H
        # openings[(axis, line, seg)] = (o0, o1) along the wall
        openings = {}
        for axis, nlines, nsegs, pitch_along in (("x", ny, nx, PX), ("y", nx, ny, PY)):
            for line in range(nlines + 1):
                for seg in range(nsegs):
                    a, b = seg * pitch_along + T // 2, (seg + 1) * pitch_along - T // 2
                    exterior = line in (0, nlines)
                    forced = (axis == "y" and k == 0 and line == cam_room[0] + 1 and seg == cam_room[1]
                              and line < nlines)
                    door_out = axis == "x" and line == 0 and k == 0 and seg == entrance
                    if exterior and not door_out:
                        mid = (a + b) // 2
                        op = (mid - WIN_W // 2, mid + WIN_W // 2, z0 + WIN_SILL, z0 + WIN_TOP)
                    elif forced or door_out or rng.chance(65):
                        # door centre at 30-40% or 60-70% of the segment: one half stays free
                        frac = 40 if forced else rng.int(30, 40)
                        if not forced and rng.chance(50):
                            frac = 100 - frac
                        mid = a + (b - a) * frac // 100
                        op = (mid - DOOR_W // 2, mid + DOOR_W // 2, z0, z0 + DOOR_H)
                        if forced:
                            cam = (line * PX, (op[0] + op[1]) // 2)
                    else:
                        op = None
                    openings[(axis, line, seg)] = op
                    wall(mesh, axis, a, b, line * (PY if axis == "x" else PX), z0, z1, op)
        for i in range(nx + 1):
            for j in range(ny + 1):
                mesh.box(i * PX - T // 2, i * PX + T // 2, j * PY - T // 2, j * PY + T // 2, z0, z1, level=1)
        for i in range(nx):
            for j in range(ny):
                furnish(mesh, rng, i, j, nx, ny, z0, openings)
    mesh.check()
    # Cameras (metres).
    i, j = cam_room
    eye = (i * PX + T // 2 + EYE_BACK, j * PY + PY // 2, S + EYE_H)
    target = (cam[0], cam[1], S + 1400) if cam else (eye[0] + PX, eye[1], S + 1400)
    lo, hi = (xlo, ylo, 0), (xhi, yhi, floors * H + S)
    c = [(lo[d] + hi[d]) / 2000 for d in range(3)]
    side = max(hi[d] - lo[d] for d in range(3)) / 1000
    ext_eye = [c[d] + side * off for d, off in enumerate((1.5, -1.75, 1.25))]
    interior = ["--eye", ",".join(f"{v / 1000:g}" for v in eye), "--target", ",".join(f"{v / 1000:g}" for v in target),
                "--fov", "60"]
    exterior = ["--eye", ",".join(f"{x:.6g}" for x in ext_eye), "--target", ",".join(f"{x:.6g}" for x in c),
                "--fov", "30"]
    return mesh, interior, exterior


def furnish(mesh, rng, i, j, nx, ny, z0, openings):
    x0, x1 = i * PX + T // 2, (i + 1) * PX - T // 2
    y0, y1 = j * PY + T // 2, (j + 1) * PY - T // 2
    cx, cy = (x0 + x1) // 2, (y0 + y1) // 2
    # Table: long side along x, near the room's centre.
    tl, tw = rng.int(120, 180) * 10, rng.int(70, 100) * 10
    th, top = 750, 40
    tx, ty = cx + rng.int(-30, 30) * 10 - tl // 2, cy + rng.int(-30, 30) * 10 - tw // 2
    leg = 50
    mesh.box(tx, tx + tl, ty, ty + tw, z0 + th - top, z0 + th, level=1)
    for lx in (tx + 30, tx + tl - 30 - leg):
        for ly in (ty + 30, ty + tw - 30 - leg):
            mesh.box(lx, lx + leg, ly, ly + leg, z0, z0 + th - top)
    # Chairs: 2 to 4, on the table's long sides, 50 mm clear of it.
    n = rng.int(2, 4)
    spots = [(side, pos) for side in (-1, 1) for pos in (1, 3)]
    if n == 3:
        del spots[rng.int(0, 3)]
    elif n == 2:
        spots = [spots[0], spots[3]] if rng.chance(50) else [spots[1], spots[2]]
    for side, pos in spots:
        s = 420
        sx = tx + tl * pos // 4 - s // 2
        sy = ty - 50 - s if side < 0 else ty + tw + 50
        seat_z, seat_t, cleg = 450, 40, 35
        mesh.box(sx, sx + s, sy, sy + s, z0 + seat_z - seat_t, z0 + seat_z, level=1)
        for lx in (sx + 10, sx + s - 10 - cleg):
            for ly in (sy + 10, sy + s - 10 - cleg):
                mesh.box(lx, lx + cleg, ly, ly + cleg, z0, z0 + seat_z - seat_t)
        by = sy if side < 0 else sy + s - 40     # the back on the side away from the table
        mesh.box(sx, sx + s, by, by + 40, z0 + seat_z, z0 + seat_z + rng.int(35, 50) * 10)
    # Shelf against an interior wall of the room, in the half of the wall its door leaves free.
    walls = []   # (axis, line, seg, inward sign, low end, high end, position across)
    if j > 0:
        walls.append(("x", j, i, +1, x0, x1, y0))
    if j < ny - 1:
        walls.append(("x", j + 1, i, -1, x0, x1, y1))
    if i > 0:
        walls.append(("y", i, j, +1, y0, y1, x0))
    if i < nx - 1:
        walls.append(("y", i + 1, j, -1, y0, y1, x1))
    if walls:
        axis, line, seg, sign, a, b, across = walls[rng.int(0, len(walls) - 1)]
        op = openings[(axis, line, seg)]
        sw, sd, sh = rng.int(80, 120) * 10, 300, rng.int(160, 200) * 10
        # 700 mm clear of the corners (the cabinet), 100 mm clear of the door, on the side of
        # the wall its door leaves free
        low_door = op is not None and (op[0] + op[1]) // 2 < (a + b) // 2
        free = (op[1] + 100, b - 700) if low_door else (a + 700, op[0] - 100 if op else b - 700)
        sw = min(sw, free[1] - free[0])
        u0 = free[1] - sw if low_door else free[0]
        gap = 10
        w0 = across + sign * gap
        w1 = w0 + sign * sd
        w0, w1 = min(w0, w1), max(w0, w1)
        side_t, board_t = 20, 20

        def put(u_lo, u_hi, z_lo, z_hi, d_lo=w0, d_hi=w1, level=0):
            if axis == "x":
                mesh.box(u_lo, u_hi, d_lo, d_hi, z_lo, z_hi, level)
            else:
                mesh.box(d_lo, d_hi, u_lo, u_hi, z_lo, z_hi, level)
        put(u0, u0 + side_t, z0, z0 + sh, level=2)
        put(u0 + sw - side_t, u0 + sw, z0, z0 + sh, level=2)
        nb = rng.int(4, 5)
        inner0, inner1 = u0 + side_t, u0 + sw - side_t
        levels = []
        for q in range(nb):
            zb = z0 + 80 + (sh - 80 - board_t) * q // (nb - 1)
            put(inner0, inner1, zb, zb + board_t, level=1)
            levels.append(zb + board_t)
        # Books on every board but the top one, standing against the back (wall side).
        for q in range(nb - 1):
            zb, room = levels[q], levels[q + 1] - board_t - levels[q]
            u = inner0 + rng.int(0, 10) * 10
            fill_to = inner0 + (inner1 - inner0) * rng.int(35, 70) // 100
            while True:
                bw = rng.int(25, 70)
                if u + bw > min(fill_to, inner1 - 5):
                    break
                bh = min(rng.int(18, 30) * 10, room - 20)
                bd = rng.int(20, 26) * 10
                if sign > 0:
                    d0, d1 = w0 + 10, w0 + 10 + bd
                else:
                    d0, d1 = w1 - 10 - bd, w1 - 10
                put(u, u + bw, zb, zb + bh, d0, d1)
                u += bw + rng.int(2, 8)
    # Cabinet in a corner.
    cw, cd, ch = rng.int(40, 60) * 10, rng.int(40, 60) * 10, rng.int(80, 120) * 10
    corner = rng.int(0, 3)
    gx, gy = 10, 10
    bx = x0 + gx if corner in (0, 3) else x1 - gx - cw
    by = y0 + gy if corner in (0, 1) else y1 - gy - cd
    mesh.box(bx, bx + cw, by, by + cd, z0, z0 + ch)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="the OFF file to write")
    ap.add_argument("--rooms", default="6,6", help="rooms along x and y (default 6,6)")
    ap.add_argument("--floors", type=int, default=2, help="floors (default 2)")
    args = ap.parse_args()
    try:
        nx, ny = (int(v) for v in args.rooms.split(","))
    except ValueError:
        ap.error("--rooms needs NX,NY")
    if nx < 1 or ny < 1 or args.floors < 1:
        ap.error("--rooms and --floors must be at least 1")
    mesh, interior, exterior = generate(nx, ny, args.floors)
    mesh.write(args.out, f"generated building, bench/gen_building.py --rooms {nx},{ny} --floors {args.floors}")
    print("interior: " + " ".join(interior))
    print("exterior: " + " ".join(exterior))
    print(f"{args.out}: {mesh.boxes} boxes, {len(mesh.verts)} vertices, {len(mesh.faces)} quads (every box closed, "
          "outward)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
