#!/usr/bin/python3
"""Cross-checks curvetet's MSH/VTU output with Gmsh itself and meshio.

Usage: /usr/bin/python3 gmsh_crosscheck.py SAMPLES.json
SAMPLES.json (written by test_gmsh_crosscheck.cpp) holds the element order,
reference points, and for every tet (by MSH element tag) curvetet's own
evaluation of the element map at those points and its certificate verdict,
plus the files to check. For each MSH file, Gmsh must
  - place every tet's points where curvetet does (same node ordering),
  - agree on validity: Gmsh's AnalyseMeshQuality minJ/maxJ > 0 exactly for
    the tets curvetet certifies positive, and its det J at the points is
    positive for them,
  - see the physical groups "boundary" (2D) and "domain" (3D).
meshio must read every file with the right point and cell counts.
Prints one line per failure and exits 1 if any.
"""
import json
import sys

import gmsh
import meshio
import numpy as np

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL:", msg)


def check_msh(path, s):
    order = s["order"]
    points = np.array(s["points"], dtype=float)
    tets = {int(k): v for k, v in s["tets"].items()}
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        gmsh.open(path)
        etype = gmsh.model.mesh.getElementType("Tetrahedron", order)
        tags, _ = gmsh.model.mesh.getElementsByType(etype)
        if sorted(int(t) for t in tags) != sorted(tets):
            fail(f"{path}: Gmsh sees tets {len(tags)}, expected {len(tets)}")
            return
        _, dets, coords = gmsh.model.mesh.getJacobians(etype, points.flatten().tolist())
        coords = np.array(coords).reshape(len(tags), len(points), 3)
        dets = np.array(dets).reshape(len(tags), len(points))
        scale = max(1.0, float(np.abs(coords).max()))
        worst = 0.0
        for i, tag in enumerate(tags):
            ours = np.array(tets[int(tag)]["coords"])
            worst = max(worst, float(np.abs(ours - coords[i]).max()))
            if tets[int(tag)]["valid"] and dets[i].min() <= 0:
                fail(f"{path}: tet {tag} certified positive but Gmsh finds det J = {dets[i].min()} at a sample")
        if worst > 1e-9 * scale:
            fail(f"{path}: element map differs from Gmsh's by {worst} (node ordering?)")
        # Gmsh's own Jacobian analysis (Bezier-based minJ/maxJ per element).
        gmsh.plugin.setNumber("AnalyseMeshQuality", "JacobianDeterminant", 1)
        gmsh.plugin.setNumber("AnalyseMeshQuality", "CreateView", 1)
        gmsh.plugin.run("AnalyseMeshQuality")
        found = False
        for v in gmsh.view.getTags():
            name = gmsh.option.getString(f"View[{gmsh.view.getIndex(v)}].Name")
            if "minJ/maxJ" not in name or "3D" not in name:
                continue
            found = True
            _, etags, data, _, _ = gmsh.view.getModelData(v, 0)
            for t, d in zip(etags, data):
                ratio = float(d[0])
                ours = tets[int(t)]["valid"]
                if ours != (ratio > 0):
                    fail(f"{path}: tet {t}: curvetet says {'valid' if ours else 'invalid'}, Gmsh minJ/maxJ = {ratio}")
        if not found:
            fail(f"{path}: AnalyseMeshQuality produced no minJ/maxJ view")
        groups = {(d, t): gmsh.model.getPhysicalName(d, t) for d, t in gmsh.model.getPhysicalGroups()}
        if groups.get((2, 1)) != "boundary" or groups.get((3, 2)) != "domain":
            fail(f"{path}: physical groups {groups}")
        print(f"{path}: {len(tags)} tets, max |x_gmsh - x_curvetet| = {worst:.3g}")
    finally:
        gmsh.finalize()


def check_meshio(path, s):
    m = meshio.read(path)
    if len(m.points) != s["num_nodes"]:
        fail(f"meshio {path}: {len(m.points)} points, expected {s['num_nodes']}")
    counts = {}
    for block in m.cells:
        counts[block.type] = counts.get(block.type, 0) + len(block.data)
    order = s["order"]
    ntet = (order + 1) * (order + 2) * (order + 3) // 6
    tet_cells = sum(len(b.data) for b in m.cells if b.data.shape[1] == ntet and ("tetra" in b.type.lower()))
    if tet_cells != len(s["tets"]):
        fail(f"meshio {path}: {tet_cells} tets of {ntet} nodes, expected {len(s['tets'])} (cells {counts})")
    else:
        print(f"meshio {path}: ok ({counts})")


def main():
    with open(sys.argv[1]) as f:
        s = json.load(f)
    for path in s["msh"]:
        check_msh(path, s)
        check_meshio(path, s)
    for path in s["vtu"]:
        check_meshio(path, s)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
