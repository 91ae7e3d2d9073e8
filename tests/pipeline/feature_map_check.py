#!/usr/bin/python3
"""Independent check that a curvetet mesh preserves the input's features.

Usage: /usr/bin/python3 feature_map_check.py OUT.msh OUT.map FEATURES.json

OUT.msh and OUT.map come from `curvetet INPUT -o OUT.msh --map OUT.map
--features FEATURES.json`; the map may be binary or JSON (docs/map_format.md).
Nothing here uses curvetet code: Gmsh reads the mesh, the map is parsed here.

The input surface is the one stored in the map (input vertices bit for bit,
ids of the features file unchanged). Checks, one FAIL line per violation:
  1. Corners: every corner of the features file is a node of the output
     mesh at the bitwise identical position, that node ends a line of the
     physical group "features", and φ(corner) from the map is exactly
     (u, v in {0, 1}) that corner of its boundary triangle.
  2. Edges: for every feature edge (a, b) of the file, φ(a) and φ(b) lie
     on an edge of their boundary triangles that carries a "features" line
     (the opposite barycentric coordinate is 0 up to ROUNDING = 1e-12: the
     map's coordinates are computed in double; any real departure from the
     curve is orders of magnitude larger at epsilon = 1e-2), and some line
     carries both, or two lines sharing an end carry them (an output vertex
     inside the input edge, from an isolation split): the input edge maps
     onto the output feature curves.
     For the vertices off every curve it prints how far off they are (the
     largest opposite coordinate to a feature edge of their triangle).
     (φ is piecewise linear in the map's barycentric charts, so the segment
     between two points of one line's edge stays on it.)
  3. Coverage: every "features" line receives the image of at least one
     input feature edge (no output feature curve without input feature).
Prints the figures; exit 1 on any failure.
"""
import json
import struct
import sys

import gmsh
import numpy as np

failures = []
ROUNDING = 1e-12


def fail(msg, limit=20):
    failures.append(msg)
    if len(failures) <= limit:
        print("FAIL:", msg)


def read_map(path):
    """The map file as a dict: order, input_vertices, nodes, node_ids,
    triangles (Nb x per), v2b (Nv x (tri, u, v))."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] == b"CTETMAP\0":
        off = 8
        version, order = struct.unpack_from("<Ii", data, off)
        off += 8
        if version != 1:
            raise SystemExit(f"{path}: map version {version}")

        def count():
            nonlocal off
            (n,) = struct.unpack_from("<Q", data, off)
            off += 8
            return n

        nv = count()
        verts = np.frombuffer(data, "<f8", 3 * nv, off).reshape(nv, 3)
        off += 24 * nv
        nf = count()
        off += 12 * nf
        nn = count()
        rec = np.dtype([("x", "<f8", 3), ("id", "<i4")])
        nodes = np.frombuffer(data, rec, nn, off)
        off += 28 * nn
        nb = count()
        per = (order + 1) * (order + 2) // 2
        tris = np.frombuffer(data, "<i4", nb * per, off).reshape(nb, per)
        off += 4 * nb * per
        prec = np.dtype([("t", "<i4"), ("u", "<f8"), ("v", "<f8")])
        v2b = np.frombuffer(data, prec, nv, off)
        return {"order": order, "input_vertices": np.array(verts), "nodes": np.array(nodes["x"]),
                "node_ids": np.array(nodes["id"]), "triangles": np.array(tris),
                "v2b": [(int(r["t"]), float(r["u"]), float(r["v"])) for r in v2b]}
    j = json.loads(data)
    return {"order": j["order"], "input_vertices": np.array(j["input"]["vertices"], dtype=float),
            "nodes": np.array(j["boundary"]["nodes"], dtype=float),
            "node_ids": np.array(j["boundary"]["node_ids"]), "triangles": np.array(j["boundary"]["triangles"]),
            "v2b": [(int(t), float(u), float(v)) for t, u, v in j["vertex_to_boundary"]]}


def feature_lines():
    """The lines of physical group "features": list of (end0, end1) mesh
    node ids (0-based) and the mesh nodes {id: (x, y, z)}."""
    tags, coords, _ = gmsh.model.mesh.getNodes()
    nodes = {int(t) - 1: tuple(coords[3 * i:3 * i + 3]) for i, t in enumerate(tags)}
    group = [t for d, t in gmsh.model.getPhysicalGroups(1) if gmsh.model.getPhysicalName(d, t) == "features"]
    lines = []
    for g in group:
        for e in gmsh.model.getEntitiesForPhysicalGroup(1, g):
            types, _, enodes = gmsh.model.mesh.getElements(1, e)
            for etype, en in zip(types, enodes):
                n = gmsh.model.mesh.getElementProperties(etype)[3]
                for k in range(0, len(en), n):
                    lines.append((int(en[k]) - 1, int(en[k + 1]) - 1))
    return lines, nodes


def on_edges(m, point):
    """Mesh-node pairs (sorted) of the boundary-triangle edges that the map
    point lies on exactly; the corner node too when it is a corner."""
    t, u, v = point
    tri = m["triangles"][t]
    ids = [int(m["node_ids"][tri[k]]) for k in range(3)]
    lam = [1.0 - u - v, u, v]
    corner = None
    for k in range(3):
        if lam[k] == 1.0 and lam[(k + 1) % 3] == 0.0 and lam[(k + 2) % 3] == 0.0:
            corner = ids[k]
    edges = set()
    for e in range(3):  # edge e: corners e, e+1; opposite corner e+2
        if abs(lam[(e + 2) % 3]) <= ROUNDING:
            edges.add(tuple(sorted((ids[e], ids[(e + 1) % 3]))))
    return edges, corner


def main():
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    msh, map_path, features_path = sys.argv[1:]
    m = read_map(map_path)
    feats = json.load(open(features_path))
    edges_in = [tuple(e) for e in feats["edges"]]
    corners = [int(c) for c in feats.get("corners", [])]
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        gmsh.open(msh)
        lines, nodes = feature_lines()
    finally:
        gmsh.finalize()
    line_keys = {tuple(sorted(l)) for l in lines}
    line_ends = {n for l in lines for n in l}
    at = {}
    for i, p in nodes.items():
        at.setdefault(p, []).append(i)
    X = m["input_vertices"]
    print(f"input: {len(X)} vertices, {len(edges_in)} feature edges, {len(corners)} corners; "
          f"output: {len(nodes)} nodes, {len(lines)} feature lines of order {m['order']}")

    # 1. Corners.
    bad_corners = set()
    for c in corners:
        p = tuple(float(x) for x in X[c])
        here = at.get(p, [])
        if not here:
            fail(f"corner {c} at {p} is not an output node (bitwise)")
            bad_corners.add(c)
            continue
        if not any(n in line_ends for n in here):
            fail(f"corner {c}: output node {here[0] + 1} ends no feature line")
            bad_corners.add(c)
        _, corner = on_edges(m, m["v2b"][c])
        if corner is None or corner not in here:
            fail(f"corner {c}: φ = {m['v2b'][c]} is not the output corner node at its position")
            bad_corners.add(c)

    # 2. Edges.
    incident = {}
    for key in line_keys:
        for n in key:
            incident.setdefault(n, set()).add(key)

    def lines_through(v):
        edges, corner = on_edges(m, m["v2b"][v])
        if corner is not None:
            return set(incident.get(corner, ()))
        return {e for e in edges if e in line_keys}

    covered = set()
    off_curve = set()
    bad_edges = set()
    for a, b in edges_in:
        ea, eb = lines_through(a), lines_through(b)
        for v, ev in ((a, ea), (b, eb)):
            if not ev:
                off_curve.add(v)
                bad_edges.add((a, b))
        common = ea & eb
        if not common:
            # An isolation split leaves an output vertex inside an input edge:
            # its ends then lie on two lines sharing that vertex.
            joined = {(x, y) for x in ea for y in eb if set(x) & set(y)}
            if ea and eb and not joined:
                bad_edges.add((a, b))
                fail(f"feature edge ({a}, {b}): its ends lie on feature lines that do not meet")
            for x, y in joined:
                covered |= {x, y}
            continue
        covered |= common
    def how_far(v):
        t, u, w = m["v2b"][v]
        tri = m["triangles"][t]
        ids = [int(m["node_ids"][tri[k]]) for k in range(3)]
        lam = [1.0 - u - w, u, w]
        off = [abs(lam[(e + 2) % 3]) for e in range(3) if tuple(sorted((ids[e], ids[(e + 1) % 3]))) in line_keys]
        return min(off) if off else float("inf")

    far = [how_far(v) for v in off_curve]
    finite = [x for x in far if x != float("inf")]
    if off_curve:
        print(f"off-curve feature vertices: {len(finite)} in a triangle with a feature edge (largest opposite "
              f"coordinate {max(finite) if finite else 0:.3g}), {len(far) - len(finite)} in a triangle without one")
    for v in sorted(off_curve)[:20]:
        fail(f"input feature vertex {v}: φ = {m['v2b'][v]} lies on no feature line")
    if len(off_curve) > 20:
        fail(f"... {len(off_curve)} input feature vertices in all lie on no feature line")

    # 3. Coverage.
    missing = line_keys - covered
    if missing:
        fail(f"{len(missing)} of {len(line_keys)} feature lines receive no input feature edge")
    nfv = len({v for e in edges_in for v in e})
    print(f"corners: {len(corners) - len(bad_corners)} of {len(corners)} ok; "
          f"feature vertices off the output curves: {len(off_curve)} of {nfv}; feature edges off the curves: {len(bad_edges)} of {len(edges_in)}; "
          f"feature lines covered: {len(line_keys & covered)} of {len(line_keys)}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
