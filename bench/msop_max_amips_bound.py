#!/usr/bin/python3
"""Lower bound on the max AMIPS of any tetrahedralization of cad_freecad_MSOP_10.

Why: issue #6 asks `curvetet tetrahedralize` for a max AMIPS lower than
`tetgen -pYq`'s on every good mesh. On this model both tools end with the same
worst tet, T* = (2085, 239, 9568, 2111). This script shows that every
tetrahedralization whose boundary faces are exactly the input triangles
(interior Steiner points allowed, none on the surface) contains T* or a tet of
higher energy: no mesher can go below T*'s energy on this model.

The argument, around two input edges (A, B, C = 2085, 239, 2111):
1. Edge (C, 241) has two input faces, G = (C, B, 241) and R = (C, 241, 9568),
   with a thin wedge of material between them (5.17 degrees). The tets around
   the edge fill that wedge: either one tet, K = (B, C, 241, 9568), or a first
   tet on G and a last tet on R whose dihedral angles at the edge sum to at
   most the wedge's angle.
2. With K, its face (B, C, 9568) is in the mesh. Edge (B, C) has the input
   faces F = (A, B, C) and G, coplanar (180 degrees of material); K takes all
   of it but 6.31 degrees, between F and (B, C, 9568). That is filled by one
   tet, (A, B, C, 9568) = T*, or by a first tet on F and a last tet on
   (B, C, 9568) whose dihedral angles at (B, C) sum to at most 6.31 degrees.
3. least(f, e, theta): the least energy of a tet on face f whose dihedral
   angle at f's edge e is theta (its apex anywhere on the half-plane through e
   at that angle from f; in closed form, see least()). It decreases as theta
   grows (checked at 2000 angles), so two end tets sharing an angle Theta
   have the worse of them at least the value where least(f1, e, theta) and
   least(f2, e, Theta - theta) cross (bisection).
If both crossings are above T*'s energy, T* is in every mesh whose worst tet
is not worse than T*.

usage: bench/msop_max_amips_bound.py [MESH.off]   (exit 0: bound proved)
"""
import sys
from fractions import Fraction

import numpy as np

from compare_tetgen import W_INV  # the comparison table's AMIPS: the same reference tet
A, B, C, D_ROOF, E_FLOOR = 2085, 239, 2111, 9568, 241


def read_off(path):
    tokens = open(path).read().split()
    nv, nf = int(tokens[1]), int(tokens[2])
    coords = tokens[4:4 + 3 * nv]
    exact = [[Fraction(coords[3 * i + k]) for k in range(3)] for i in range(nv)]
    at = 4 + 3 * nv
    faces = []
    for _ in range(nf):
        n = int(tokens[at])
        faces.append(tuple(int(x) for x in tokens[at + 1:at + 1 + n]))
        at += 1 + n
    return np.array(exact, dtype=float), exact, faces


def amips(a, b, c, d):
    """Conformal AMIPS energy of tet (a, b, c, d); inf when not positive."""
    j = np.column_stack([b - a, c - a, d - a]) @ W_INV
    det = np.linalg.det(j)
    return np.trace(j.T @ j) / (3 * np.cbrt(det * det)) if det > 0 else np.inf


def orient_exact(p, q, r, s):
    u = [q[i] - p[i] for i in range(3)]
    v = [r[i] - p[i] for i in range(3)]
    w = [s[i] - p[i] for i in range(3)]
    det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])
    return (det > 0) - (det < 0)


def edge_frame(e0, e1, p):
    """Unit vector k along edge (e0, e1); p's coordinate s_p along it, its
    distance h from the edge's line and the unit vector u from that line
    toward p."""
    k = (e1 - e0) / np.linalg.norm(e1 - e0)
    s_p = k @ (p - e0)
    u = p - e0 - k * s_p
    h = np.linalg.norm(u)
    return k, s_p, h, u / h


def dihedral(e0, e1, p, q):
    """Angle at edge (e0, e1) between the half-planes through p and q."""
    u, w = edge_frame(e0, e1, p)[3], edge_frame(e0, e1, q)[3]
    return np.arccos(np.clip(u @ w, -1, 1))


def least(e0, e1, p, toward, theta):
    """Least energy of a tet on face (e0, e1, p) whose apex lies on the
    half-plane through (e0, e1) at angle theta from p's, turned toward
    `toward`. In the edge's frame (e0 at the origin, e1 = (l, 0, 0),
    p = (s_p, h, 0)), the apex (s, r cos(theta), r sin(theta)) gives a tet
    of volume l h r sin(theta) / 6 and squared edge lengths summing to
    const + 3 s^2 - 2 s (l + s_p) + 3 r^2 - 2 h r cos(theta). AMIPS is that
    sum over 6 (6 sqrt(2) volume)^(2/3), so the best apex has s = (l + s_p) / 3
    and r the one positive root of 12 r^2 - 2 h r cos(theta) - 2 const = 0:
    a single minimum, evaluated here with the same amips() as everything else."""
    length = np.linalg.norm(e1 - e0)
    k, s_p, h, u = edge_frame(e0, e1, p)
    w = np.cross(k, u)
    if w @ (toward - e0) < 0:
        w = -w
    direction = np.cos(theta) * u + np.sin(theta) * w
    s = (length + s_p) / 3
    # The sum's terms without r, at that s: the face's edges, then l^2 + s_p^2 + h^2 - 3 s^2.
    const = length ** 2 + (s_p ** 2 + h ** 2) + ((s_p - length) ** 2 + h ** 2) + length ** 2 + s_p ** 2 + h ** 2 - 3 * s * s
    r = (h * np.cos(theta) + np.sqrt((h * np.cos(theta)) ** 2 + 24 * const)) / 12
    apex = e0 + s * k + r * direction
    return min(amips(e0, e1, p, apex), amips(e1, e0, p, apex))


def crossing(f1, f2, total):
    """min over theta in (0, total) of max(least(f1, theta), least(f2, total -
    theta)), for least decreasing in its angle; also checks that it does."""
    one = lambda th: least(*f1, th)
    two = lambda th: least(*f2, total - th)
    samples = np.linspace(0.0005, 0.9995, 2000) * total
    ones, twos = [one(th) for th in samples], [two(th) for th in samples]
    if not (np.all(np.diff(ones) < 0) and np.all(np.diff(twos) > 0)):
        sys.exit("least() is not monotone in its angle here: the argument does not apply")
    lo, hi = 1e-9 * total, (1 - 1e-9) * total
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if one(mid) > two(mid):
            lo = mid
        else:
            hi = mid
    return max(one(lo), two(lo)), lo


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "../shared/data/good/cad_freecad_MSOP_10.off"
    v, exact, faces = read_off(path)
    key = frozenset
    face_set = {key(f) for f in faces}
    for f in ((A, B, C), (C, B, E_FLOOR), (C, E_FLOOR, D_ROOF)):
        if key(f) not in face_set:
            sys.exit(f"input face {f} not found: not the expected model")
    for edge, expected in (((C, E_FLOOR), {key((C, B, E_FLOOR)), key((C, E_FLOOR, D_ROOF))}),
                           ((B, C), {key((A, B, C)), key((C, B, E_FLOOR))})):
        around = {key(f) for f in faces if set(edge) <= set(f)}
        if around != expected:
            sys.exit(f"edge {edge} is not on exactly the two expected faces")
    if orient_exact(exact[A], exact[B], exact[C], exact[E_FLOOR]) != 0:
        sys.exit("F and G are not coplanar")
    # The material is on the side of the tets T* and K (both positive in
    # one orientation): check that the surface's outward side is the other.
    volume = sum(np.linalg.det(v[list(f)]) for f in faces)  # 6 x enclosed volume, > 0 when outward
    outward = 1 if volume > 0 else -1
    for f, inside in (((A, B, C), D_ROOF), ((C, B, E_FLOOR), D_ROOF), ((C, E_FLOOR, D_ROOF), B)):
        if orient_exact(*(exact[x] for x in f), exact[inside]) * outward >= 0:
            sys.exit(f"vertex {inside} is not inside face {f}")

    a, b, c, d, e = (v[x] for x in (A, B, C, D_ROOF, E_FLOOR))
    star = min(amips(a, b, c, d), amips(a, c, b, d))
    k = min(amips(b, c, e, d), amips(c, b, e, d))
    wedge = dihedral(c, e, b, d)
    rest = dihedral(b, c, a, d)
    print(f"T* = ({A}, {B}, {D_ROOF}, {C}): AMIPS {star!r}")
    print(f"K  = ({B}, {C}, {E_FLOOR}, {D_ROOF}): AMIPS {k:.4f}")
    print(f"wedge at edge ({C}, {E_FLOOR}): {np.degrees(wedge):.4f} deg; "
          f"left between F and K at edge ({B}, {C}): {np.degrees(rest):.4f} deg")
    bound_wedge, th1 = crossing((c, e, b, d), (c, e, d, b), wedge)
    print(f"two or more tets at ({C}, {E_FLOOR}): the worse end tet >= {bound_wedge:.4f} "
          f"(curves cross at {np.degrees(th1):.4f} deg)")
    bound_rest, th2 = crossing((b, c, d, a), (b, c, a, d), rest)
    print(f"two or more tets between F and K at ({B}, {C}): the worse end tet >= {bound_rest:.4f} "
          f"(curves cross at {np.degrees(th2):.4f} deg)")
    proved = bound_wedge > star and bound_rest > star
    print("every tetrahedralization with these boundary faces has max AMIPS >= T*'s:", "proved" if proved else "NOT proved")
    return 0 if proved else 1


if __name__ == "__main__":
    sys.exit(main())
