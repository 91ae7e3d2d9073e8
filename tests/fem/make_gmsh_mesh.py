#!/usr/bin/python3
"""Writes a Gmsh tet mesh of the unit cube [0,1]^3 or the unit ball for the
fem tests: make_gmsh_mesh.py (cube|ball) H ORDER OUT.msh.

Mesh size H, element order ORDER (Gmsh places the high-order boundary nodes
on the curved surface, so an order-2 ball is curved; the cube stays
straight). MSH 4.1 with physical groups "boundary" (2D) and "domain" (3D),
as DOLFINx's gmshio needs. Deterministic (one thread, fixed algorithm)."""
import sys

import gmsh


def main():
    shape, h, order, out = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    gmsh.model.add(shape)
    if shape == "cube":
        volume = gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    elif shape == "ball":
        volume = gmsh.model.occ.addSphere(0, 0, 0, 1)
    else:
        raise SystemExit(f"unknown shape {shape}")
    gmsh.model.occ.synchronize()
    surfaces = [tag for dim, tag in gmsh.model.getBoundary([(3, volume)], oriented=False)]
    gmsh.model.addPhysicalGroup(2, surfaces, 1)
    gmsh.model.setPhysicalName(2, 1, "boundary")
    gmsh.model.addPhysicalGroup(3, [volume], 2)
    gmsh.model.setPhysicalName(3, 2, "domain")
    gmsh.option.setNumber("Mesh.MeshSizeMin", h)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.model.mesh.generate(3)
    if order > 1:
        gmsh.model.mesh.setOrder(order)
    gmsh.write(out)
    gmsh.finalize()


if __name__ == "__main__":
    main()
