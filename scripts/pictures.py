#!/usr/bin/python3
"""Renders the README pictures headlessly (matplotlib, Agg) from the outputs
of `curvetet MESH -o X.msh --vtu X.vtu --map X.map.json` and the images of
the input vertices on the curved boundary (`curvetet transfer` of the node
coordinates, see scripts/pictures.sh).

  input.png     the input surface
  output.png    the curved output boundary (each order-P triangle drawn as
                its P^2 lattice sub-triangles, element edges in black),
                coloured by the min scaled Jacobian of the tet under it
  map.png       the input's edges drawn at their images on the output
  deform.png    (with --deformed DENSE.off COARSE.off) the coarse boundary
                twisted and the dense input carried along through the map

Usage: pictures.py MAP.json MESH.vtu IMAGES.csv OUTDIR [--elev DEG --azim DEG --up AXIS]
"""
import argparse
import base64
import json
import re
import struct
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402

VTK_TRIANGLE_LATTICE_CACHE = {}


def vtu_arrays(path):
    """Name -> numpy array of every binary DataArray (UInt64 byte count + raw)."""
    text = open(path).read()
    kinds = {"Float64": "<f8", "Int64": "<i8", "Int32": "<i4", "UInt8": "u1"}
    out = {}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)"[^>]*format="binary">\s*([A-Za-z0-9+/=]+)\s*</DataArray>', text):
        raw = base64.b64decode(m.group(3))
        (size,) = struct.unpack("<Q", raw[:8])
        out[m.group(2)] = np.frombuffer(raw[8:8 + size], dtype=kinds[m.group(1)])
    return out


def tet_quality_by_face(vtu):
    """Sorted corner triple -> min scaled Jacobian of the tet owning it."""
    conn, offsets, types = vtu["connectivity"], vtu["offsets"], vtu["types"]
    sj = vtu["min_scaled_jacobian"]
    faces = {}
    start = 0
    for c, end in enumerate(offsets):
        if types[c] == 71:  # VTK_LAGRANGE_TETRAHEDRON: corners first
            a, b, cc, d = conn[start:start + 4]
            for tri in ((a, b, cc), (a, b, d), (a, cc, d), (b, cc, d)):
                faces[tuple(sorted(int(x) for x in tri))] = sj[c]
        start = end
    return faces


def lattice(order):
    """Gmsh/internal order of a triangle's nodes as integer (i, j) lattice
    points: corners, edges 0-1, 1-2, 2-0, then the interior recursively."""
    if order in VTK_TRIANGLE_LATTICE_CACHE:
        return VTK_TRIANGLE_LATTICE_CACHE[order]

    def build(p, shift):
        if p < 0:
            return []
        if p == 0:
            return [(shift, shift)]
        corners = [(0, 0), (p, 0), (0, p)]
        pts = list(corners)
        pts += [(k, 0) for k in range(1, p)]
        pts += [(p - k, k) for k in range(1, p)]
        pts += [(0, p - k) for k in range(1, p)]
        pts = [(i + shift, j + shift) for i, j in pts]
        return pts + build(p - 3, shift + 1)

    table = {pt: k for k, pt in enumerate(build(order, 0))}
    VTK_TRIANGLE_LATTICE_CACHE[order] = table
    return table


def sub_triangles(tri, order):
    """Lattice sub-triangles of one order-P triangle (node ids)."""
    at = lattice(order)
    out = []
    for b in range(order):
        for a in range(order - b):
            out.append((tri[at[(a, b)]], tri[at[(a + 1, b)]], tri[at[(a, b + 1)]]))
            if a + b + 1 < order:
                out.append((tri[at[(a + 1, b)]], tri[at[(a + 1, b + 1)]], tri[at[(a, b + 1)]]))
    return out


def element_edges(tri, order):
    """The three curved edges of an order-P triangle as node polylines."""
    at = lattice(order)
    e01 = [tri[at[(k, 0)]] for k in range(order + 1)]
    e12 = [tri[at[(order - k, k)]] for k in range(order + 1)]
    e20 = [tri[at[(0, order - k)]] for k in range(order + 1)]
    return [e01, e12, e20]


class View:
    """Orthographic camera: rotation from elevation/azimuth, depth = towards viewer."""

    def __init__(self, points, elev, azim, up="z"):
        e, a = np.radians(elev), np.radians(azim)
        rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
        rx = np.array([[1, 0, 0], [0, np.cos(e), -np.sin(e)], [0, np.sin(e), np.cos(e)]])
        # Screen x, screen y, depth (larger = nearer): look along -y after rz.
        to_z_up = {"z": np.eye(3), "y": np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]]),
                   "x": np.array([[0, 1, 0], [0, 0, 1], [1, 0, 0]])}[up]
        self.r = np.array([[1, 0, 0], [0, 0, 1], [0, -1, 0]]) @ rx @ rz @ to_z_up
        self.centre = points.mean(axis=0)
        self.light = np.array([0.3, 0.5, 1.0]) / np.linalg.norm([0.3, 0.5, 1.0])

    def project(self, p):
        return (p - self.centre) @ self.r.T


def shade(normals, base):
    """Lambert shading of per-face colours (N x 4 RGBA) by screen-space normals."""
    lam = np.clip(normals @ np.array([0.3, 0.5, 1.0]) / np.linalg.norm([0.3, 0.5, 1.0]), 0, 1)
    out = base.copy()
    out[:, :3] *= (0.35 + 0.65 * lam)[:, None]
    return out


def draw(ax, scr, tris, colours, lines=(), line_colour="k", line_width=0.3, bins=40):
    """Painter's algorithm over depth bins: back-facing triangles culled,
    each bin's triangles then its lines, so near surface hides far lines."""
    p = scr[tris]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    norm = np.linalg.norm(n, axis=1)
    norm[norm == 0] = 1
    n /= norm[:, None]
    front = n[:, 2] > 0
    depth = p[:, :, 2].mean(axis=1)
    lo, hi = depth.min(), depth.max() + 1e-12
    shaded = shade(n, colours)
    tri_bin = np.minimum(((depth - lo) / (hi - lo) * bins).astype(int), bins - 1)
    line_bin = []
    for seg in lines:
        d = scr[list(seg), 2].mean()
        line_bin.append(min(int((d - lo) / (hi - lo) * bins), bins - 1) if hi > lo else 0)
    line_bin = np.array(line_bin, dtype=int)
    for k in range(bins):
        sel = np.where(front & (tri_bin == k))[0]
        if len(sel):
            ax.add_collection(PolyCollection(p[sel][:, :, :2], facecolors=shaded[sel], edgecolors=shaded[sel],
                                             linewidths=0.2, zorder=2 * k))
        if len(lines):
            idx = np.where(line_bin == k)[0]
            if len(idx):
                ls = [scr[list(lines[i]), :2] for i in idx]
                cs = [line_colour[i] for i in idx] if isinstance(line_colour, list) else line_colour
                ws = [line_width[i] for i in idx] if isinstance(line_width, list) else line_width
                ax.add_collection(LineCollection(ls, colors=cs, linewidths=ws, zorder=2 * k + 1))
    ax.set_xlim(scr[:, 0].min() * 1.05, scr[:, 0].max() * 1.05)
    ax.set_ylim(scr[:, 1].min() * 1.05, scr[:, 1].max() * 1.05)
    ax.set_aspect("equal")
    ax.axis("off")


def read_off(path):
    tokens = open(path).read().split()
    assert tokens[0] == "OFF"
    nv, nf = int(tokens[1]), int(tokens[2])
    v = np.array(tokens[4:4 + 3 * nv], float).reshape(nv, 3)
    f = np.array(tokens[4 + 3 * nv:4 + 3 * nv + 4 * nf], int).reshape(nf, 4)[:, 1:]
    return v, f


def visible_input_edges(faces, scr):
    """Edges of front-facing input faces (each once), in the given screen
    coordinates (the input's own, or its image on the output)."""
    p = scr[faces]
    front = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])[:, 2] > 0
    edges = set()
    for f in faces[front]:
        for k in range(3):
            a, b = int(f[k]), int(f[(k + 1) % 3])
            edges.add((min(a, b), max(a, b)))
    return sorted(edges)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("map")
    ap.add_argument("vtu")
    ap.add_argument("images")
    ap.add_argument("outdir")
    ap.add_argument("--elev", type=float, default=15)
    ap.add_argument("--azim", type=float, default=-30)
    ap.add_argument("--deformed", nargs=2, metavar=("DENSE_OFF", "COARSE_OFF"))
    ap.add_argument("--up", choices=["x", "y", "z"], default="y", help="the model's up axis")
    args = ap.parse_args()

    m = json.load(open(args.map))
    order = m["order"]
    vin = np.array(m["input"]["vertices"], float)
    fin = np.array(m["input"]["faces"], int)
    nodes = np.array(m["boundary"]["nodes"], float)
    node_ids = m["boundary"]["node_ids"]
    tris = m["boundary"]["triangles"]
    img = np.loadtxt(args.images, delimiter=",", skiprows=1)[:, 3:6]  # columns x,y,z,px,py,pz

    view = View(vin, args.elev, args.azim, args.up)
    dpi, size = 110, (5, 5)

    # Input surface.
    fig, ax = plt.subplots(figsize=size, dpi=dpi)
    grey = np.tile([0.78, 0.80, 0.85, 1.0], (len(fin), 1))
    s_in = view.project(vin)
    draw(ax, s_in, fin, grey, visible_input_edges(fin, s_in), line_colour=(0.2, 0.2, 0.2), line_width=0.1)
    ax.set_title(f"input: {len(vin)} vertices, {len(fin)} triangles", fontsize=9)
    fig.savefig(f"{args.outdir}/input.png", bbox_inches="tight")
    plt.close(fig)

    # Output boundary coloured by the min scaled Jacobian of the tet below.
    quality = tet_quality_by_face(vtu_arrays(args.vtu))
    sub, colour_value, edges = [], [], []
    for tri in tris:
        key = tuple(sorted(node_ids[tri[k]] for k in range(3)))
        q = quality.get(key, np.nan)
        for s in sub_triangles(tri, order):
            sub.append(s)
            colour_value.append(q)
        for e in element_edges(tri, order):
            edges += [(e[k], e[k + 1]) for k in range(order)]
    sub = np.array(sub, int)
    colour_value = np.array(colour_value)
    cmap = plt.get_cmap("viridis")
    vmax = max(1e-3, np.nanmax(colour_value))
    colours = cmap(np.nan_to_num(colour_value, nan=0.0) / vmax)
    s_out = view.project(nodes)
    fig, ax = plt.subplots(figsize=size, dpi=dpi)
    draw(ax, s_out, sub, colours, edges, line_colour="k", line_width=0.4)
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(0, vmax))
    fig.colorbar(sm, ax=ax, shrink=0.6, label="min scaled Jacobian of the boundary tet")
    ax.set_title(f"output boundary: {len(tris)} curved triangles of order {order}, "
                 f"min SJ {np.nanmin(colour_value):.3f}", fontsize=9)
    fig.savefig(f"{args.outdir}/output.png", bbox_inches="tight")
    plt.close(fig)

    # The map: input edges at their images on the output boundary.
    fig, ax = plt.subplots(figsize=size, dpi=dpi)
    light = np.tile([0.93, 0.93, 0.95, 1.0], (len(sub), 1))
    all_pts = np.vstack([nodes, img])
    s_all = view.project(all_pts)
    off = len(nodes)
    in_edges = [(a + off, b + off) for a, b in visible_input_edges(fin, s_all[off:])]
    # Mapped input edges (red) and the curved element edges (blue).
    lines = in_edges + edges
    line_colours = [(0.85, 0.1, 0.1, 1.0)] * len(in_edges) + [(0.1, 0.2, 0.8, 1.0)] * len(edges)
    line_widths = [0.15] * len(in_edges) + [0.6] * len(edges)
    draw(ax, s_all, sub, light, lines, line_colour=line_colours, line_width=line_widths)
    ax.set_title("the map: input edges (red) on the curved output boundary", fontsize=9)
    fig.savefig(f"{args.outdir}/map.png", bbox_inches="tight")
    plt.close(fig)
    written = ["input.png", "output.png", "map.png"]

    if args.deformed:
        dense_v, dense_f = read_off(args.deformed[0])
        coarse_v, coarse_f = read_off(args.deformed[1])
        fig, axes = plt.subplots(1, 2, figsize=(8, 4.5), dpi=dpi)
        s_c = view.project(coarse_v)
        draw(axes[0], s_c, coarse_f, np.tile([0.55, 0.75, 0.95, 1.0], (len(coarse_f), 1)))
        axes[0].set_title(f"coarse boundary, twisted ({len(tris)} curved triangles)", fontsize=9)
        s_d = view.project(dense_v)
        draw(axes[1], s_d, dense_f, np.tile([0.78, 0.80, 0.85, 1.0], (len(dense_f), 1)),
             visible_input_edges(dense_f, s_d), line_colour=(0.2, 0.2, 0.2), line_width=0.1)
        axes[1].set_title(f"dense input carried through the map ({len(dense_v)} vertices)", fontsize=9)
        fig.savefig(f"{args.outdir}/deform.png", bbox_inches="tight")
        plt.close(fig)
        written.append("deform.png")
    print(f"wrote {', '.join(args.outdir + '/' + w for w in written)}")


if __name__ == "__main__":
    sys.exit(main())
