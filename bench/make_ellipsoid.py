#!/usr/bin/env python3
"""Write a closed ellipsoid triangle mesh as OFF (outward, watertight).

usage: make_ellipsoid.py LEVELS OUT.off [RX RY RZ]

An octahedron subdivided LEVELS times (8 * 4^LEVELS faces), pushed to the
unit sphere, then scaled to radii RX, RY, RZ (default 1, 0.7, 0.5: the same
ellipsoid as tests/map/map_fixture.hpp). Plain Python, no dependencies.
"""
import math
import sys


def octahedral_sphere(levels):
    vertices = [(1, 0, 0), (0, 1, 0), (-1, 0, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    faces = []
    for i in range(4):  # outward: counter-clockwise seen from outside
        a, b = i, (i + 1) % 4
        faces += [(a, b, 4), (b, a, 5)]
    for _ in range(levels):
        midpoints = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoints:
                p = [0.5 * (x + y) for x, y in zip(vertices[a], vertices[b])]
                n = math.sqrt(sum(c * c for c in p))
                vertices.append(tuple(c / n for c in p))
                midpoints[key] = len(vertices) - 1
            return midpoints[key]

        refined = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            refined += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        faces = refined
    return vertices, faces


def main():
    if len(sys.argv) not in (3, 6):
        sys.exit(__doc__)
    levels = int(sys.argv[1])
    radii = [float(r) for r in sys.argv[3:6]] if len(sys.argv) == 6 else [1.0, 0.7, 0.5]
    vertices, faces = octahedral_sphere(levels)
    with open(sys.argv[2], "w") as out:
        out.write(f"OFF\n{len(vertices)} {len(faces)} 0\n")
        for v in vertices:
            out.write(" ".join(repr(c * r) for c, r in zip(v, radii)) + "\n")
        for f in faces:
            out.write(f"3 {f[0]} {f[1]} {f[2]}\n")


if __name__ == "__main__":
    main()
