#!/usr/bin/env python3
"""Writes slotted_block.stl: a block 50 x 40 x 30 mm (x, y, z from 0) with a slot 12 mm wide and 6 mm deep across
its top along x, and a slot 8 mm high and 5 mm deep across its -Y side along x (the two-sided part of
config/jobs/slotted_block_xyzac.yaml). Both slots run through, so a flat end mill reaches every edge of them.

The solid is a set of cells of a grid whose lines are the block's and the slots' faces; the surface is every cell
face between a solid and an empty cell, two triangles each, so neighbouring faces share their corners and the mesh
is closed with no edge ending on another's middle.
    python3 slotted_block.py slotted_block.stl
"""
import struct
import sys

XS = [0.0, 50.0]
YS = [0.0, 5.0, 14.0, 26.0, 40.0]
ZS = [0.0, 10.0, 18.0, 24.0, 30.0]


def solid(i, j, k):
    """Whether cell (i, j, k) of the grid is material."""
    if not (0 <= i < len(XS) - 1 and 0 <= j < len(YS) - 1 and 0 <= k < len(ZS) - 1):
        return False
    y = 0.5 * (YS[j] + YS[j + 1])
    z = 0.5 * (ZS[k] + ZS[k + 1])
    top_slot = 14 < y < 26 and z > 24
    side_slot = y < 5 and 10 < z < 18
    return not (top_slot or side_slot)


def corner(axis, i, j, k):
    return (XS[i], YS[j], ZS[k])


def faces():
    """Quads (4 corners, counter-clockwise seen from outside) between solid and empty cells."""
    n = (len(XS) - 1, len(YS) - 1, len(ZS) - 1)
    grids = (XS, YS, ZS)
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for plane in range(len(grids[axis])):
            for a in range(n[u]):
                for b in range(n[v]):
                    below = [0, 0, 0]
                    below[axis], below[u], below[v] = plane - 1, a, b
                    above = list(below)
                    above[axis] = plane
                    s0, s1 = solid(*below), solid(*above)
                    if s0 == s1:
                        continue
                    quad = []
                    for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = [0.0, 0.0, 0.0]
                        p[axis] = grids[axis][plane]
                        p[u] = grids[u][a + du]
                        p[v] = grids[v][b + dv]
                        quad.append(tuple(p))
                    normal = [0.0, 0.0, 0.0]
                    # u, v, axis is a right-handed turn: the quad's order faces +axis; material below faces +axis.
                    normal[axis] = 1.0 if s0 else -1.0
                    if not s0:
                        quad.reverse()
                    yield tuple(normal), quad


def main(path):
    triangles = []
    for normal, q in faces():
        triangles.append((normal, (q[0], q[1], q[2])))
        triangles.append((normal, (q[0], q[2], q[3])))
    with open(path, "wb") as f:
        f.write(b"slotted block 50x40x30 mm, slots on top and on -Y (rosmill)".ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for normal, tri in triangles:
            f.write(struct.pack("<3f", *normal))
            for p in tri:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "slotted_block.stl")
