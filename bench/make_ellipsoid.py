#!/usr/bin/env python3
"""Write a closed ellipsoid triangle mesh as OFF (outward, watertight).

usage: make_ellipsoid.py [--base octahedron|icosahedron] LEVELS OUT.off [RX RY RZ]

A base polyhedron subdivided LEVELS times (each level splits every triangle
in four), pushed to the unit sphere, then scaled to radii RX, RY, RZ
(default 1, 0.7, 0.5: the same ellipsoid as tests/map/map_fixture.hpp).
  --base octahedron   (default) 8 * 4^LEVELS faces
  --base icosahedron  20 * 4^LEVELS faces
Together they give about two sizes per decade (2048, 5120, 8192, 20480,
32768, 81920, 131072, 327680, 524288, 1310720, ...). Plain Python, no
dependencies; importable (write_ellipsoid, face_count).
"""
import argparse
import math
import sys

BASES = ("octahedron", "icosahedron")


def base_polyhedron(base):
    """Unit-sphere vertices and outward (counter-clockwise from outside) faces."""
    if base == "octahedron":
        vertices = [(1, 0, 0), (0, 1, 0), (-1, 0, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
        faces = []
        for i in range(4):
            a, b = i, (i + 1) % 4
            faces += [(a, b, 4), (b, a, 5)]
        return vertices, faces
    if base == "icosahedron":
        t = (1 + math.sqrt(5)) / 2
        raw = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
               (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
               (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
        n = math.sqrt(1 + t * t)
        vertices = [tuple(c / n for c in v) for v in raw]
        faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
                 (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
                 (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
                 (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
        return vertices, faces
    raise ValueError(f"unknown base {base!r} (expected one of {BASES})")


def face_count(levels, base="octahedron"):
    return len(base_polyhedron(base)[1]) * 4 ** levels


def subdivided_sphere(levels, base="octahedron"):
    vertices, faces = base_polyhedron(base)
    vertices = list(vertices)
    for _ in range(levels):
        midpoints = {}

        def midpoint(a, b):
            key = (a, b) if a < b else (b, a)
            m = midpoints.get(key)
            if m is None:
                p = [0.5 * (x + y) for x, y in zip(vertices[a], vertices[b])]
                n = math.sqrt(sum(c * c for c in p))
                vertices.append(tuple(c / n for c in p))
                m = midpoints[key] = len(vertices) - 1
            return m

        refined = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            refined += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        faces = refined
    return vertices, faces


def octahedral_sphere(levels):  # kept for callers of the old name
    return subdivided_sphere(levels, "octahedron")


def write_ellipsoid(levels, path, radii=(1.0, 0.7, 0.5), base="octahedron"):
    vertices, faces = subdivided_sphere(levels, base)
    with open(path, "w") as out:
        out.write(f"OFF\n{len(vertices)} {len(faces)} 0\n")
        out.writelines(" ".join(repr(c * r) for c, r in zip(v, radii)) + "\n" for v in vertices)
        out.writelines(f"3 {f[0]} {f[1]} {f[2]}\n" for f in faces)
    return len(faces)


def main():
    parser = argparse.ArgumentParser(usage=__doc__.split("\n\n")[1].split("\n")[0][len("usage: "):],
                                     description=__doc__)
    parser.add_argument("--base", choices=BASES, default="octahedron")
    parser.add_argument("levels", type=int)
    parser.add_argument("out")
    parser.add_argument("radii", type=float, nargs="*")
    args = parser.parse_args()
    if len(args.radii) not in (0, 3) or args.levels < 0:
        sys.exit(__doc__)
    write_ellipsoid(args.levels, args.out, args.radii or (1.0, 0.7, 0.5), args.base)


if __name__ == "__main__":
    main()
