#!/usr/bin/python3
"""DOLFINx 0.5 reference for curvetet's Poisson solver (src/curvetet/fem).

dolfinx_poisson.py MESH.msh [DEGREE]

Reads a Gmsh tet mesh (order 1 or 2; DOLFINx 0.5 reads no higher order)
with gmsh + dolfinx.io.gmshio.model_to_mesh, solves -Δu = f, u = g on the boundary with
continuous Lagrange elements of order DEGREE (default 2), where u is the
paper's §6.4 Franke solution evaluated at x_hat = (x - origin) / scale
(origin = lowest corner of the bounding box of the geometry nodes, scale =
its longest side) - the same problem as fem::franke_solution(
fem::tet_bounding_box(mesh)). f = -Δu symbolically (UFL), g interpolated at
the dofs, Dirichlet on all exterior facets, direct LU solve. Prints one JSON
line: dofs, l2_error, l2_exact."""
import json
import sys

import gmsh
import numpy as np
import ufl
from dolfinx import fem, mesh as dmesh
from dolfinx.io import gmshio
from dolfinx.fem.petsc import LinearProblem
from mpi4py import MPI


def franke(t):
    e = ufl.exp
    return (0.75 * e(-((9 * t[0] - 2) ** 2 + (9 * t[1] - 2) ** 2 + (9 * t[2] - 2) ** 2) / 4)
            + 0.75 * e(-(9 * t[0] + 1) ** 2 / 49 - (9 * t[1] + 1) / 10 - (9 * t[2] + 1) / 10)
            + 0.5 * e(-((9 * t[0] - 7) ** 2 + (9 * t[1] - 3) ** 2 + (9 * t[2] - 5) ** 2) / 4)
            - 0.2 * e(-(9 * t[0] - 4) ** 2 - (9 * t[1] - 7) ** 2 - (9 * t[2] - 5) ** 2))


def main():
    path = sys.argv[1]
    degree = int(sys.argv[2]) if len(sys.argv) > 2 else 2
    # Debian's 0.5.2 gmshio.read_from_msh is broken (returns an undefined
    # name), so load the file into a Gmsh model and convert that.
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.merge(path)
    domain, _, _ = gmshio.model_to_mesh(gmsh.model, MPI.COMM_WORLD, 0, gdim=3)
    gmsh.finalize()
    geometry_order = domain.geometry.cmap.degree
    x = domain.geometry.x
    origin = x.min(axis=0)
    scale = float((x.max(axis=0) - origin).max())

    X = ufl.SpatialCoordinate(domain)
    t = ufl.as_vector([(X[i] - float(origin[i])) / scale for i in range(3)])
    u_exact = franke(t)
    f = -ufl.div(ufl.grad(u_exact))

    V = fem.FunctionSpace(domain, ("Lagrange", degree))
    g = fem.Function(V)
    g.interpolate(fem.Expression(u_exact, V.element.interpolation_points()))
    tdim = domain.topology.dim
    domain.topology.create_connectivity(tdim - 1, tdim)
    facets = dmesh.exterior_facet_indices(domain.topology)
    bc = fem.dirichletbc(g, fem.locate_dofs_topological(V, tdim - 1, facets))

    # Same quadrature degree as curvetet's default (fem/poisson.hpp).
    qdeg = 2 * degree + 2 + 3 * (geometry_order - 1)
    dx = ufl.Measure("dx", domain=domain, metadata={"quadrature_degree": qdeg})
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    a = ufl.inner(ufl.grad(u), ufl.grad(v)) * dx
    L = f * v * dx
    problem = LinearProblem(a, L, bcs=[bc], petsc_options={"ksp_type": "preonly", "pc_type": "lu"})
    uh = problem.solve()

    dx_err = ufl.Measure("dx", domain=domain, metadata={"quadrature_degree": qdeg + 2})
    error2 = fem.assemble_scalar(fem.form((uh - u_exact) ** 2 * dx_err))
    exact2 = fem.assemble_scalar(fem.form(u_exact ** 2 * dx_err))
    print(json.dumps({"geometry_order": int(geometry_order), "degree": degree,
                      "dofs": int(V.dofmap.index_map.size_global), "l2_error": float(np.sqrt(error2)),
                      "l2_exact": float(np.sqrt(exact2))}))


if __name__ == "__main__":
    main()
