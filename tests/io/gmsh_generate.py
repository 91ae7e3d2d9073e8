#!/usr/bin/python3
"""Writes a curved tet mesh made by Gmsh itself, for curvetet's reader tests.

Usage: /usr/bin/python3 gmsh_generate.py OUT_DIR ORDER [BROKEN]
Meshes a sphere of radius 1 (OCC) with tets of the given order, curved onto
the sphere, pushes the first high-order node of every 50th tet 0.3 away
(toward the tet's first corner's opposite side) for BROKEN > 0 such tets,
and writes OUT_DIR/gmsh_v41.msh (ASCII), gmsh_v41b.msh (binary),
gmsh_v22.msh and gmsh.json: the node and tet counts and, in Gmsh's element
order, Gmsh's AnalyseMeshQuality minJ/maxJ per tet.
"""
import json
import os
import sys

import gmsh

out, order = sys.argv[1], int(sys.argv[2])
broken = int(sys.argv[3]) if len(sys.argv) > 3 else 0
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.model.occ.addSphere(0, 0, 0, 1)
gmsh.model.occ.synchronize()
gmsh.option.setNumber("Mesh.MeshSizeMax", 0.6)
gmsh.model.addPhysicalGroup(3, [1], 2)
gmsh.model.setPhysicalName(3, 2, "domain")
surfaces = [t for _, t in gmsh.model.getEntities(2)]
gmsh.model.addPhysicalGroup(2, surfaces, 1)
gmsh.model.setPhysicalName(2, 1, "boundary")
gmsh.model.mesh.generate(3)
gmsh.model.mesh.setOrder(order)
etype = gmsh.model.mesh.getElementType("Tetrahedron", order)
tags, enodes = gmsh.model.mesh.getElementsByType(etype)
per = len(enodes) // len(tags)
for k in range(broken):
    t = 50 * k
    first_edge_node = int(enodes[per * t + 4])
    corner = int(enodes[per * t + 3])
    x = gmsh.model.mesh.getNode(first_edge_node)[0]
    c = gmsh.model.mesh.getNode(corner)[0]
    # Move the edge-0-1 node past corner 3: the tet folds over.
    gmsh.model.mesh.setNode(first_edge_node, [c[i] + 0.6 * (c[i] - x[i]) for i in range(3)], [])
gmsh.plugin.setNumber("AnalyseMeshQuality", "JacobianDeterminant", 1)
gmsh.plugin.setNumber("AnalyseMeshQuality", "CreateView", 1)
gmsh.plugin.run("AnalyseMeshQuality")
ratio = {}
for v in gmsh.view.getTags():
    if "minJ/maxJ 3D" in gmsh.option.getString(f"View[{gmsh.view.getIndex(v)}].Name"):
        _, etags, data, _, _ = gmsh.view.getModelData(v, 0)
        ratio = {int(t): float(d[0]) for t, d in zip(etags, data)}
node_tags, _, _ = gmsh.model.mesh.getNodes()
gmsh.option.setNumber("Mesh.SaveAll", 0)
gmsh.option.setNumber("Mesh.Binary", 0)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.write(os.path.join(out, "gmsh_v41.msh"))
gmsh.option.setNumber("Mesh.Binary", 1)
gmsh.write(os.path.join(out, "gmsh_v41b.msh"))
gmsh.option.setNumber("Mesh.Binary", 0)
gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
gmsh.write(os.path.join(out, "gmsh_v22.msh"))
with open(os.path.join(out, "gmsh.json"), "w") as f:
    json.dump({"nodes": len(node_tags), "tets": len(tags), "ratio": [ratio[int(t)] for t in tags]}, f)
gmsh.finalize()
