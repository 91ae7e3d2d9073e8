#!/usr/bin/python3
"""Independent check of a mesh written by the curvetet main command.

Usage: /usr/bin/python3 gmsh_pipeline_check.py OUT.msh INPUT.off EPSILON [SAMPLES]

Nothing here uses curvetet code; Gmsh evaluates the elements.
  1. Positivity, three ways, on every tet of every volume:
     - Gmsh's AnalyseMeshQuality plugin (its own Bezier Jacobian bounds):
       minJ/maxJ > 0 for every tet;
     - gmsh.model.mesh.getJacobians at a dense lattice of reference points
       (order 2P + 1) plus the quadrature points of a high-order rule:
       det J > 0 everywhere sampled;
     - getElementQualities "minSJ" > 0 (Gmsh >= 4.9; Debian 12 has 4.8).
  2. Distance: the curved triangles of the physical group "boundary" are
     sampled through Gmsh's element map on a lattice of SAMPLES segments per
     edge (default 16) and split into flat sub-triangles. Every input vertex
     must have a sub-triangle closer than EPSILON x the input's bbox diagonal
     (r): candidates are the sub-triangles whose bbox grown by r meets the
     vertex's cell of a uniform grid, which holds every triangle closer than
     r, so the test is exact for the sampled surface.
Prints the figures; one line per failure; exit 1 if any.
"""
import sys

import gmsh
import numpy as np

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL:", msg)


def read_off(path):
    with open(path) as f:
        tokens = [t for line in f for t in line.split("#")[0].split()]
    if tokens[0] != "OFF":
        raise SystemExit(f"{path}: not an OFF file")
    nv, nf = int(tokens[1]), int(tokens[2])
    v = np.array(tokens[4:4 + 3 * nv], dtype=float).reshape(nv, 3)
    faces, k = [], 4 + 3 * nv
    for _ in range(nf):
        n = int(tokens[k])
        faces.append([int(x) for x in tokens[k + 1:k + 1 + n]])
        k += 1 + n
    return v, faces


def lattice(dim, n):
    """Reference points i/n of the simplex of dimension dim (2 or 3)."""
    pts = []
    for i in range(n + 1):
        for j in range(n + 1 - i):
            if dim == 2:
                pts.append((i / n, j / n, 0.0))
            else:
                for k in range(n + 1 - i - j):
                    pts.append((i / n, j / n, k / n))
    return np.array(pts)


def check_positivity():
    total = 0
    for etype in gmsh.model.mesh.getElementTypes(3):
        name, dim, order, nnodes, _, _ = gmsh.model.mesh.getElementProperties(etype)
        if not name.startswith("Tetrahedron"):
            fail(f"unexpected 3D element type {name}")
            continue
        tags, _ = gmsh.model.mesh.getElementsByType(etype)
        total += len(tags)
        pts = lattice(3, 2 * order + 1)
        qpts, _ = gmsh.model.mesh.getIntegrationPoints(etype, f"Gauss{2 * order + 2}")
        pts = np.vstack([pts, np.array(qpts).reshape(-1, 3)])
        _, dets, _ = gmsh.model.mesh.getJacobians(etype, pts.flatten().tolist())
        dets = np.array(dets).reshape(len(tags), len(pts))
        bad = np.where(dets.min(axis=1) <= 0)[0]
        print(f"getJacobians: {len(tags)} tets of order {order} x {len(pts)} points, min det J {dets.min():.4g}")
        if len(bad):
            fail(f"getJacobians: {len(bad)} tets with det J <= 0 at a sample, e.g. tag {int(tags[bad[0]])}")
        if hasattr(gmsh.model.mesh, "getElementQualities"):  # Gmsh >= 4.9
            sj = np.array(gmsh.model.mesh.getElementQualities(tags, "minSJ"))
            print(f"getElementQualities minSJ: min {sj.min():.4g}")
            if (sj <= 0).any():
                fail(f"minSJ: {int((sj <= 0).sum())} tets with minSJ <= 0")
    if total == 0:
        fail("no tetrahedra")

    gmsh.plugin.setNumber("AnalyseMeshQuality", "JacobianDeterminant", 1)
    gmsh.plugin.setNumber("AnalyseMeshQuality", "CreateView", 1)
    gmsh.plugin.run("AnalyseMeshQuality")
    seen = 0
    for v in gmsh.view.getTags():
        name = gmsh.option.getString(f"View[{gmsh.view.getIndex(v)}].Name")
        if "minJ/maxJ" not in name or "3D" not in name:
            continue
        _, etags, data, _, _ = gmsh.view.getModelData(v, 0)
        ratios = np.array([float(d[0]) for d in data])
        seen += len(etags)
        print(f"AnalyseMeshQuality: {len(etags)} tets, min minJ/maxJ {ratios.min():.4g}")
        if (ratios <= 0).any():
            fail(f"AnalyseMeshQuality: {int((ratios <= 0).sum())} tets with minJ/maxJ <= 0")
    if seen != total:
        fail(f"AnalyseMeshQuality analysed {seen} tets of {total}")


def boundary_samples(segments):
    """Points and flat sub-triangles of the curved "boundary" triangles."""
    group = [t for d, t in gmsh.model.getPhysicalGroups(2) if gmsh.model.getPhysicalName(d, t) == "boundary"]
    if len(group) != 1:
        fail(f"expected one physical group 'boundary', found {len(group)}")
        return None, None
    entities = gmsh.model.getEntitiesForPhysicalGroup(2, group[0])
    uv = lattice(2, segments)
    index = {}
    for k, (i, j, _) in enumerate(uv):
        index[(round(i * segments), round(j * segments))] = k
    sub = []
    n = segments
    for i in range(n):
        for j in range(n - i):
            sub.append((index[(i, j)], index[(i + 1, j)], index[(i, j + 1)]))
            if i + j < n - 1:
                sub.append((index[(i + 1, j)], index[(i + 1, j + 1)], index[(i, j + 1)]))
    sub = np.array(sub)
    points, tris = [], []
    for e in entities:
        for etype in gmsh.model.mesh.getElementTypes(2, e):
            tags, _ = gmsh.model.mesh.getElementsByType(etype, e)
            _, _, coords = gmsh.model.mesh.getJacobians(etype, uv.flatten().tolist(), e)
            coords = np.array(coords).reshape(len(tags), len(uv), 3)
            for c in coords:
                tris.append(sub + sum(len(p) for p in points))
                points.append(c)
    return np.vstack(points), np.vstack(tris)


def point_triangle_distance(p, a, b, c):
    """Euclidean distance from points p[i] to triangles (a[i], b[i], c[i])."""
    ab, ac, ap = b - a, c - a, p - a
    n = np.cross(ab, ac)
    nn = np.einsum("ij,ij->i", n, n)
    # Barycentric coordinates of the projection onto the plane.
    v = np.einsum("ij,ij->i", np.cross(ap, ac), n) / nn
    w = np.einsum("ij,ij->i", np.cross(ab, ap), n) / nn
    inside = (v >= 0) & (w >= 0) & (v + w <= 1)
    plane = np.abs(np.einsum("ij,ij->i", ap, n)) / np.sqrt(nn)

    def segment(x, y):
        d = y - x
        t = np.clip(np.einsum("ij,ij->i", p - x, d) / np.einsum("ij,ij->i", d, d), 0, 1)
        return np.linalg.norm(p - (x + t[:, None] * d), axis=1)

    edges = np.minimum(np.minimum(segment(a, b), segment(b, c)), segment(c, a))
    return np.where(inside, plane, edges)


def candidate_pairs(verts, points, tris, r):
    """(vertex, sub-triangle) pairs covering every pair closer than r."""
    corners = points[tris]  # (n, 3, 3)
    # Grid step: r, or most triangles' extent if larger: few cells per
    # triangle, and a few long triangles do not make every cell hold all.
    step = max(r, np.percentile((corners.max(axis=1) - corners.min(axis=1)).max(axis=1), 95))
    lo = np.floor((corners.min(axis=1) - r) / step).astype(np.int64)
    hi = np.floor((corners.max(axis=1) + r) / step).astype(np.int64)
    base = min(lo.min(), np.floor(verts.min() / step).astype(np.int64)) - 1

    def key(cells):
        c = cells - base
        return (c[:, 0] << 42) | (c[:, 1] << 21) | c[:, 2]

    keys, owners = [], []
    span = (hi - lo).max(axis=0)
    for dx in range(span[0] + 1):
        for dy in range(span[1] + 1):
            for dz in range(span[2] + 1):
                cells = lo + np.array([dx, dy, dz])
                ok = (cells <= hi).all(axis=1)
                keys.append(key(cells[ok]))
                owners.append(np.nonzero(ok)[0])
    keys, owners = np.concatenate(keys), np.concatenate(owners)
    order = np.argsort(keys, kind="stable")
    keys, owners = keys[order], owners[order]
    vkeys = key(np.floor(verts / step).astype(np.int64))
    start, end = np.searchsorted(keys, vkeys, "left"), np.searchsorted(keys, vkeys, "right")
    counts = end - start
    rows = np.repeat(np.arange(len(verts)), counts)
    within = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    return rows, owners[np.repeat(start, counts) + within]


def check_distance(input_path, epsilon, segments):
    verts, faces = read_off(input_path)
    used = sorted({v for f in faces for v in f})
    verts = verts[used]
    diag = np.linalg.norm(verts.max(axis=0) - verts.min(axis=0))
    points, tris = boundary_samples(segments)
    if points is None:
        return
    rows, cands = candidate_pairs(verts, points, tris, epsilon * diag)
    best = np.full(len(verts), np.inf)
    chunk = 1 << 22  # pairs evaluated at once (bounded memory)
    for k in range(0, len(rows), chunk):
        r, c = rows[k:k + chunk], cands[k:k + chunk]
        d = point_triangle_distance(verts[r], points[tris[c, 0]], points[tris[c, 1]], points[tris[c, 2]])
        np.minimum.at(best, r, d)
    worst = best.max() / diag
    print(f"distance: {len(verts)} input vertices, {len(tris)} boundary sub-triangles, {len(rows)} pairs; "
          f"max {worst:.4g}, mean {best[np.isfinite(best)].mean() / diag:.4g} (x bbox diagonal), epsilon {epsilon}")
    if not worst < epsilon:
        far = int(np.argmax(best))
        fail(f"input vertex {used[far]} is {best[far] / diag:.4g} x diagonal from the boundary (epsilon {epsilon})")


def main():
    if len(sys.argv) < 4:
        raise SystemExit(__doc__)
    msh, input_path, epsilon = sys.argv[1], sys.argv[2], float(sys.argv[3])
    segments = int(sys.argv[4]) if len(sys.argv) > 4 else 16
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        gmsh.open(msh)
        check_positivity()
        check_distance(input_path, epsilon, segments)
    finally:
        gmsh.finalize()
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
