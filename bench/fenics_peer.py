#!/usr/bin/python3
"""Hertz contact (sphere on an elastic half-space, axisymmetric, penalty) in
FEniCS 2019 (legacy dolfin): the peer of edp/hertz.edp for side-by-side timing.

Install on Debian 12 (as root), see install_hint():
    apt-get update && apt-get install -y python3-dolfin python3-gmsh
Run with Debian's python (the one that sees python3-dolfin):
    /usr/bin/python3 bench/fenics_peer.py [--n 36] [--L 1820] [--kpen 1e6] [--order 2]
Prints one JSON line. Importable: run(n, L, kpen, order) -> dict.
"""
import time

T_START = time.perf_counter()  # wall_time_total counts the imports too

import argparse
import logging
import math

import numpy as np
from seed_scene import A_H, F_H, NU, P0_H, D, E, R, finish  # the seed scene, beside this script

EDGE_GAP = 1e-7 * D  # contact edge: outermost r with u_z - h > -EDGE_GAP


def install_hint():
    return "apt-get update && apt-get install -y python3-dolfin python3-gmsh"


def build_mesh(n, L):
    """Quarter disc r >= 0, z <= 0 of radius L a: size a/n within 1.5 a, then
    a/n + g (rho - 1.5 a) with g = 3.2/n, as the FreeFEM solver's first mesh."""
    import dolfin as df
    import gmsh

    # growth capped at 0.3 as in the FreeFEM mesh (it binds for n < 11)
    h0, g, rf, R0 = A_H / n, min(0.3, 3.2 / n), 1.5 * A_H, L * A_H
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        geo = gmsh.model.geo
        # the surface of the fine zone is split uniformly, with a vertex every
        # a/n (as in the FreeFEM mesh): the computed contact edge sits just past
        # the last vertex inside the contact, so a free mesher's spacing, off by
        # a fraction of an element, shifts a by up to ~0.1 a/n
        m = math.ceil(1.5 * n)
        o, q = geo.addPoint(0, 0, 0), geo.addPoint(m * h0, 0, 0)
        p1, p2 = geo.addPoint(R0, 0, 0), geo.addPoint(0, -R0, 0)
        fine = geo.addLine(o, q)
        loop = geo.addCurveLoop([fine, geo.addLine(q, p1), geo.addCircleArc(p1, o, p2), geo.addLine(p2, o)])
        geo.addPlaneSurface([loop])
        geo.mesh.setTransfiniteCurve(fine, m + 1)
        geo.synchronize()
        field = gmsh.model.mesh.field
        f = field.add("MathEval")
        rho = "sqrt(x*x+y*y)"
        # max(rho - rf, 0) as (s + |s|)/2: gmsh's expression parser has no max
        field.setString(f, "F", f"{h0!r}+{g!r}*(({rho}-{rf!r})+Abs({rho}-{rf!r}))/2")
        field.setAsBackgroundMesh(f)
        # the size field alone decides, also along the boundary
        for opt in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints", "MeshSizeFromCurvature"):
            gmsh.option.setNumber("Mesh." + opt, 0)
        gmsh.model.mesh.generate(2)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        _, tri = gmsh.model.mesh.getElementsByType(2)
    finally:
        gmsh.finalize()

    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    cells = index[tri.astype(np.int64)].reshape(-1, 3)
    xy = xyz.reshape(-1, 3)[:, :2]
    mesh = df.Mesh()
    ed = df.MeshEditor()
    ed.open(mesh, "triangle", 2, 2)
    ed.init_vertices(len(xy))
    ed.init_cells(len(cells))
    for i, p in enumerate(xy):
        ed.add_vertex(i, p)
    for i, c in enumerate(cells):
        ed.add_cell(i, c)
    ed.close()
    return mesh


def contact_radius(mesh, V, uh):
    """Outermost r with u_z - h > -EDGE_GAP. On a straight surface edge the
    gap is a quadratic in the edge parameter, so the crossing is solved exactly
    (reading it at the dofs alone would be a node spacing a/(2n) coarse)."""
    import dolfin as df

    mesh.init(1, 2)
    top = [f for f in df.facets(mesh) if f.exterior() and abs(f.midpoint().y()) < 1e-12 * A_H]
    dofmap, u = V.sub(1).dofmap(), uh.vector().get_local()
    edge = []
    for f in top:
        c = df.Cell(mesh, f.entities(2)[0])
        local = list(c.entities(1)).index(f.index())
        # P2 cell dofs: vertices 0..2, then edge midpoints; edge i is opposite vertex i
        verts = [j for j in range(3) if j != local]
        cd = dofmap.cell_dofs(c.index())
        ends = np.array(c.get_vertex_coordinates()).reshape(3, 2)[verts, 0]
        u0, u1 = u[cd[verts[0]]], u[cd[verts[1]]]
        um = u[cd[3 + local]] if len(cd) == 6 else (u0 + u1) / 2  # t = 1/2
        # gap(t) + EDGE_GAP as a t-polynomial: the P2 (or P1) trace of u_z, exact h
        r = np.polynomial.Polynomial([ends[0], ends[1] - ends[0]])
        q = np.polynomial.Polynomial([u0, 4 * um - 3 * u0 - u1, 2 * u0 + 2 * u1 - 4 * um])
        q = q - (-D + r**2 / (2 * R)) + EDGE_GAP
        ts = [t.real for t in q.roots() if abs(t.imag) < 1e-12 and 0 <= t.real <= 1] + [0.0, 1.0]
        edge += [r(t) for t in ts if q(t) >= -1e-14 * D]
    return max(edge, default=float("nan"))


def run(n=36, L=1820.0, kpen=1e6, order=2):
    import dolfin as df

    df.set_log_level(df.LogLevel.WARNING)
    logging.getLogger("FFC").setLevel(logging.WARNING)  # JIT notices went to stdout
    mesh = build_mesh(n, L)
    V = df.VectorFunctionSpace(mesh, "CG", order)
    R0 = L * A_H

    # boundaries: 1 top (z = 0), 2 axis (r = 0), 3 far arc. The arc's P2 edge
    # midpoints lie on chords inside the circle, so it is marked by its vertices.
    marks = df.MeshFunction("size_t", mesh, 1, 0)
    tol = 1e-12 * A_H
    df.CompiledSubDomain("on_boundary && near(x[1], 0, tol)", tol=tol).mark(marks, 1)
    df.CompiledSubDomain("on_boundary && near(x[0], 0, tol)", tol=tol).mark(marks, 2)
    df.CompiledSubDomain("on_boundary && x[0]*x[0] + x[1]*x[1] > R2", R2=(R0 * (1 - 1e-9))**2).mark(marks, 3, False)
    bcs = [df.DirichletBC(V, df.Constant((0.0, 0.0)), marks, 3),
           df.DirichletBC(V.sub(0), df.Constant(0.0), marks, 2)]

    mu, lmbda = E / (2 * (1 + NU)), E * NU / ((1 + NU) * (1 - 2 * NU))
    x = df.SpatialCoordinate(mesh)
    r = x[0]

    def eps(w):  # [e_rr, e_zz, e_tt, gamma_rz]
        return df.as_vector([w[0].dx(0), w[1].dx(1), w[0] / r, w[0].dx(1) + w[1].dx(0)])

    def sigma(w):  # [s_rr, s_zz, s_tt, s_rz]: sigma . eps(v) is the tensor product
        e = eps(w)
        tr = e[0] + e[1] + e[2]
        return df.as_vector([lmbda * tr + 2 * mu * e[0], lmbda * tr + 2 * mu * e[1],
                             lmbda * tr + 2 * mu * e[2], mu * e[3]])

    uh, v = df.Function(V), df.TestFunction(V)
    gap = uh[1] - (-D + r**2 / (2 * R))
    pressure = kpen * (gap + abs(gap)) / 2
    # default rules (3 Gauss points per surface edge): richer ones on the
    # bracket's kink change p0, F and a by < 1e-6 and only add Newton steps
    ds = df.Measure("ds", domain=mesh, subdomain_data=marks)
    res = df.inner(sigma(uh), eps(v)) * r * df.dx + pressure * v[1] * r * ds(1)
    jac = df.derivative(res, uh)  # d|g|/dg = sign(g): the semismooth Newton Jacobian
    # u = 0 to start: the first active set is then the Hertz zone r < a
    problem = df.NonlinearVariationalProblem(res, uh, bcs, jac)  # forms compile here
    solver = df.NonlinearVariationalSolver(problem)
    prm = solver.parameters["newton_solver"]
    prm["linear_solver"] = "mumps"
    prm["relative_tolerance"] = 1e-10
    prm["absolute_tolerance"] = 1e-13
    prm["maximum_iterations"] = 100
    prm["report"] = False
    prm["error_on_nonconvergence"] = False  # reported as "converged": false

    t0 = time.perf_counter()
    iterations, converged = solver.solve()
    t_solve = time.perf_counter() - t0

    # p0 at the surface z-dofs (vertices and edge midpoints); F from the same bracket
    zdofs = np.array(V.sub(1).dofmap().dofs())
    xd = V.tabulate_dof_coordinates()[zdofs]
    on_top = np.abs(xd[:, 1]) < tol
    rs, uz = xd[on_top, 0], uh.vector().get_local()[zdofs[on_top]]
    p0 = float(np.max(kpen * np.maximum(uz - (-D + rs**2 / (2 * R)), 0.0)))
    F = 2 * math.pi * df.assemble(pressure * r * ds(1))
    a = contact_radius(mesh, V, uh)
    return {
        "n": n, "L": L, "kpen": kpen, "order": order, "ndof": V.dim(),
        "newton_iterations": int(iterations), "converged": bool(converged),
        "p0": p0, "F": F, "a": a,
        "err_p0": p0 / P0_H - 1, "err_F": F / F_H - 1, "err_a": a / A_H - 1,
        "wall_time_solve": t_solve,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=36, help="elements per contact radius")
    ap.add_argument("--L", type=float, default=1820.0, help="domain radius in units of a")
    ap.add_argument("--kpen", type=float, default=1e6, help="penalty stiffness")
    ap.add_argument("--order", type=int, default=2, choices=(1, 2), help="Lagrange degree")
    args = ap.parse_args()
    out = run(args.n, args.L, args.kpen, args.order)
    return finish(out, T_START)


if __name__ == "__main__":
    raise SystemExit(main())
