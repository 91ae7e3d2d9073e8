#!/usr/bin/python3
"""Peer benchmark: Gmsh's own curved tet meshing of a dense surface.

The pipeline a Gmsh user would run on a scanned surface: classify the
triangles into patches, create a discrete geometry, mesh the volume, raise to
order P, optionally run the high-order optimizer, then count the elements
whose Jacobian is not positive (Gmsh's own min/max Jacobian per element).

Prints one JSON line: model, order, seconds, tets, boundary triangles,
invalid elements, finished (false when the time limit stopped it).
Usage: bench/gmsh_curving.py MESH.off [--order 4] [--optimize] [--size-frac 0.05] [--timeout 600]
"""
import argparse
import json
import math
import multiprocessing as mp
import os
import sys
import tempfile
import time


def read_off(path):
    with open(path) as f:
        words = [w for line in f for w in line.split("#", 1)[0].split()]
    assert words[0].endswith("OFF")
    nv, nf = int(words[1]), int(words[2])
    pos = 4
    verts = [tuple(float(x) for x in words[pos + 3 * i: pos + 3 * i + 3]) for i in range(nv)]
    pos += 3 * nv
    faces = []
    for _ in range(nf):
        n = int(words[pos])
        faces.append(tuple(int(x) for x in words[pos + 1: pos + 1 + n]))
        pos += 1 + n
    return verts, faces


def write_msh22(path, verts, faces):
    """Triangles as an MSH 2.2 file: exact connectivity (STL would be re-welded)."""
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(verts))
        for i, v in enumerate(verts):
            f.write("%d %.17g %.17g %.17g\n" % ((i + 1,) + v))
        f.write("$EndNodes\n$Elements\n%d\n" % len(faces))
        for i, (a, b, c) in enumerate(faces):
            f.write("%d 2 2 1 1 %d %d %d\n" % (i + 1, a + 1, b + 1, c + 1))
        f.write("$EndElements\n")


def run(args, out):
    import gmsh
    import numpy as np

    verts, faces = read_off(args.mesh)
    lo, hi = np.min(verts, axis=0), np.max(verts, axis=0)
    diag = float(np.linalg.norm(hi - lo))
    with tempfile.TemporaryDirectory() as tmp:
        surface = os.path.join(tmp, "in.msh")
        write_msh22(surface, verts, faces)
        gmsh.initialize()
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", args.threads)
        t0 = time.time()
        # Patches must be parametrizable; on some scans only a wider
        # classification angle gives that, so try angles in turn.
        for angle in (40, 60, 80, 120):
            gmsh.clear()
            gmsh.merge(surface)
            try:
                gmsh.model.mesh.classifySurfaces(math.radians(angle), True, True, math.pi)
                gmsh.model.mesh.createGeometry()
                break
            except Exception:
                continue
        else:
            raise RuntimeError("Gmsh could not build a parametrizable geometry")
        out["classify_angle"] = angle
        surfaces = gmsh.model.getEntities(2)
        loop = gmsh.model.geo.addSurfaceLoop([s[1] for s in surfaces])
        gmsh.model.geo.addVolume([loop])
        gmsh.model.geo.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMax", args.size_frac * diag)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0)
        gmsh.model.mesh.generate(3)
        gmsh.model.mesh.setOrder(args.order)
        if args.optimize:
            gmsh.option.setNumber("Mesh.HighOrderOptimize", 2)
            gmsh.model.mesh.optimize("HighOrder")
        seconds = time.time() - t0
        types, tags, _ = gmsh.model.mesh.getElements(3)
        tets = sum(len(t) for t in tags)
        tri_types, tri_tags, _ = gmsh.model.mesh.getElements(2)
        tris = sum(len(t) for t in tri_tags)
        # Gmsh's own Jacobian analysis: per element min J / max J, invalid <= 0.
        gmsh.plugin.setNumber("AnalyseMeshQuality", "JacobianDeterminant", 1)
        gmsh.plugin.setNumber("AnalyseMeshQuality", "CreateView", 1)
        gmsh.plugin.setNumber("AnalyseMeshQuality", "DimensionOfElements", 3)
        gmsh.plugin.run("AnalyseMeshQuality")
        view = gmsh.view.getTags()[-1]
        _, _, data, _, _ = gmsh.view.getModelData(view, 0)
        invalid = int(np.sum(np.array([d[0] for d in data]) <= 0))
        gmsh.finalize()
    out.update(model=os.path.basename(args.mesh), order=args.order, optimize=args.optimize,
               seconds=round(seconds, 2), tets=tets, boundary_triangles=tris, invalid=invalid, finished=True)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("mesh")
    p.add_argument("--order", type=int, default=4)
    p.add_argument("--optimize", action="store_true")
    p.add_argument("--size-frac", type=float, default=0.05, help="max element size / bbox diagonal")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--timeout", type=float, default=600)
    args = p.parse_args()
    with mp.Manager() as m:
        out = m.dict(model=os.path.basename(args.mesh), order=args.order, optimize=args.optimize, finished=False)
        proc = mp.Process(target=run, args=(args, out))
        t0 = time.time()
        proc.start()
        proc.join(args.timeout)
        if proc.is_alive():
            proc.terminate()
            out["seconds"] = round(time.time() - t0, 2)
        print(json.dumps(dict(out)))


if __name__ == "__main__":
    sys.exit(main())
