#!/usr/bin/python3
"""Continuum reference for natural convection past a hot cylinder in a cold square enclosure.

Steady Boussinesq Navier-Stokes, free-fall scaling (rho = 1, g beta dC = 1, eta = sqrt(Sc/Ra),
kappa = 1/sqrt(Ra Sc), Sc = 0.7), unit square enclosure, concentric cylinder of radius 0.1.
theta = 1 on the cylinder, 0 on the enclosure, no slip everywhere, gravity along -y:

    (u . grad) u = -grad p + eta lap u + theta e_y,   div u = 0,   u . grad theta = kappa lap theta.

Discretisation: body-fitted gmsh triangles with quadratic (curved) geometry, refined towards both
walls; Taylor-Hood P2/P1 velocity-pressure and P2 temperature in one mixed space; Newton (MUMPS LU)
with continuation in Ra (1e4 -> 1e6 through intermediate values); pressure pinned at one corner.

Observables, per mesh and Ra:
* centre-line profiles theta(x) and v*(x) = v_y sqrt(Ra/Sc) along y = 0.5 from the cylinder
  surface (x = 0.6) to the right wall (x = 1), on a fixed set of points for every mesh;
* mean Nusselt numbers on the cylinder and on the enclosure, computed from the weak residual
  of the energy equation (variationally consistent flux, converges faster than grad theta . n):
      Q_wall = (1/kappa) int (u . grad theta) phi + kappa grad theta . grad phi dx,
  phi = 1 on the wall's boundary dofs and 0 elsewhere; Q is the dimensionless heat flow per unit
  depth, -oint d theta/dn ds (out of the cylinder, into the enclosure).  Nu_half = Q / 2 is the heat
  flow through one symmetric half (see docs/natural-convection.md for why that is the definition
  the tabulated values of Moukalled & Acharya appear to use).

Run (from the repository root; about 10 minutes on one core for the default three meshes):
    /usr/bin/python3 tests/data/refs/natural_convection/continuum_reference.py
Needs Debian bookworm's python3-dolfinx (0.5.2) and python3-gmsh (4.8.4).  Writes, next to this
script, continuum_profiles.csv, continuum_nusselt.csv and continuum_convergence.csv.
"""
import argparse
import csv
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SC = 0.7
RADIUS = 0.1
CENTRE = (0.5, 0.5)
TAG_FLUID, TAG_CYL, TAG_BOX = 1, 2, 3


def build_mesh(lc, wall_ratio, order):
    """Unit square minus the disk; element size lc in the bulk, lc/wall_ratio at both walls."""
    import gmsh
    from mpi4py import MPI
    from dolfinx.io import gmshio

    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("nc")
    occ = gmsh.model.occ
    box = occ.addRectangle(0, 0, 0, 1, 1)
    disk = occ.addDisk(CENTRE[0], CENTRE[1], 0, RADIUS, RADIUS)
    fluid, _ = occ.cut([(2, box)], [(2, disk)])
    occ.synchronize()
    surf = fluid[0][1]
    curves = [c[1] for c in gmsh.model.getBoundary([(2, surf)], oriented=False)]
    cyl, outer = [], []
    for c in curves:
        x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(1, c)
        (cyl if max(x1 - x0, y1 - y0) < 2.5 * RADIUS and x0 > 0.01 else outer).append(c)
    gmsh.model.addPhysicalGroup(2, [surf], TAG_FLUID)
    gmsh.model.addPhysicalGroup(1, cyl, TAG_CYL)
    gmsh.model.addPhysicalGroup(1, outer, TAG_BOX)
    # size field: lc/wall_ratio at the walls, growing linearly to lc over 0.15 (boundary layers at
    # Ra = 1e6 are about 0.03 thick)
    fd = gmsh.model.mesh.field
    dist = fd.add("Distance")
    fd.setNumbers(dist, "CurvesList", cyl + outer)
    fd.setNumber(dist, "NumPointsPerCurve", 400)
    thr = fd.add("Threshold")
    fd.setNumber(thr, "InField", dist)
    fd.setNumber(thr, "SizeMin", lc / wall_ratio)
    fd.setNumber(thr, "SizeMax", lc)
    fd.setNumber(thr, "DistMin", 0.0)
    fd.setNumber(thr, "DistMax", 0.15)
    fd.setAsBackgroundMesh(thr)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.model.mesh.generate(2)
    if order > 1:
        gmsh.model.mesh.setOrder(order)
    mesh, _, facet_tags = gmshio.model_to_mesh(gmsh.model, MPI.COMM_WORLD, 0, gdim=2)
    gmsh.finalize()
    return mesh, facet_tags


class Solver:
    def __init__(self, mesh, facet_tags):
        import ufl
        from dolfinx import fem
        from dolfinx.fem.petsc import NonlinearProblem
        from dolfinx.nls.petsc import NewtonSolver
        from mpi4py import MPI
        from petsc4py import PETSc

        self.mesh = mesh
        cell = mesh.ufl_cell()
        el_u = ufl.VectorElement("Lagrange", cell, 2)
        el_p = ufl.FiniteElement("Lagrange", cell, 1)
        el_t = ufl.FiniteElement("Lagrange", cell, 2)
        W = fem.FunctionSpace(mesh, ufl.MixedElement([el_u, el_p, el_t]))
        self.W = W
        fdim = mesh.topology.dim - 1
        cyl = facet_tags.find(TAG_CYL)
        box = facet_tags.find(TAG_BOX)
        if len(cyl) == 0 or len(box) == 0:
            sys.exit("mesh: no cylinder (%d) or enclosure (%d) facets tagged" % (len(cyl), len(box)))
        V, _ = W.sub(0).collapse()
        Q, _ = W.sub(1).collapse()
        T, _ = W.sub(2).collapse()
        self.T = T
        u0 = fem.Function(V)
        bcs = []
        for facets in (cyl, box):
            dofs = fem.locate_dofs_topological((W.sub(0), V), fdim, facets)
            bcs.append(fem.dirichletbc(u0, dofs, W.sub(0)))
        self.phi = {}
        for name, facets, value in (("cylinder", cyl, 1.0), ("enclosure", box, 0.0)):
            # through the facets, so the P2 edge dofs of the curved wall are included
            dofs = fem.locate_dofs_topological((W.sub(2), T), fdim, facets)
            g = fem.Function(T)
            g.x.array[:] = value
            bcs.append(fem.dirichletbc(g, dofs, W.sub(2)))
            phi = fem.Function(T)
            phi.x.array[dofs[1]] = 1.0
            self.phi[name] = phi
        corner = fem.locate_dofs_geometrical(
            (W.sub(1), Q), lambda x: np.isclose(x[0], 0.0) & np.isclose(x[1], 0.0))
        p0 = fem.Function(Q)
        bcs.append(fem.dirichletbc(p0, corner, W.sub(1)))

        self.eta = fem.Constant(mesh, PETSc.ScalarType(1.0))
        self.kappa = fem.Constant(mesh, PETSc.ScalarType(1.0))
        w = fem.Function(W)
        self.w = w
        u, p, th = ufl.split(w)
        v, q, s = ufl.TestFunctions(W)
        ey = ufl.as_vector((0.0, 1.0))
        F = (ufl.inner(ufl.grad(u) * u, v) + self.eta * ufl.inner(ufl.grad(u), ufl.grad(v))
             - p * ufl.div(v) - q * ufl.div(u) - th * ufl.inner(ey, v)
             + ufl.inner(u, ufl.grad(th)) * s + self.kappa * ufl.inner(ufl.grad(th), ufl.grad(s))) * ufl.dx
        problem = NonlinearProblem(F, w, bcs)
        newton = NewtonSolver(MPI.COMM_WORLD, problem)
        newton.convergence_criterion = "incremental"
        newton.rtol = 1e-11
        newton.atol = 1e-12
        newton.max_it = 30
        ksp = newton.krylov_solver
        opts = PETSc.Options()
        prefix = ksp.getOptionsPrefix()
        opts[prefix + "ksp_type"] = "preonly"
        opts[prefix + "pc_type"] = "lu"
        opts[prefix + "pc_factor_mat_solver_type"] = "mumps"
        ksp.setFromOptions()
        self.newton = newton
        # flux forms: residual of the energy equation against phi
        self.flux_forms = {}
        for name, phi in self.phi.items():
            r = (ufl.inner(u, ufl.grad(th)) * phi
                 + self.kappa * ufl.inner(ufl.grad(th), ufl.grad(phi))) * ufl.dx
            self.flux_forms[name] = fem.form(r)

    def solve(self, ra):
        self.eta.value = np.sqrt(SC / ra)
        self.kappa.value = 1.0 / np.sqrt(ra * SC)
        its, converged = self.newton.solve(self.w)
        if not converged:
            sys.exit("Newton did not converge at Ra = %g" % ra)
        self.w.x.scatter_forward()
        return its

    def nusselt(self):
        from dolfinx import fem
        k = float(self.kappa.value)
        q_cyl = fem.assemble_scalar(self.flux_forms["cylinder"]) / k
        # on the enclosure, the residual gives kappa * (d theta/dn outward) integrated: heat leaving is -that
        q_box = -fem.assemble_scalar(self.flux_forms["enclosure"]) / k
        return q_cyl, q_box

    def evaluate(self, xs, y=0.5):
        """theta and v_y at the points (x, y); every point must be found in the mesh."""
        from dolfinx import geometry

        pts = np.zeros((len(xs), 3))
        pts[:, 0] = xs
        pts[:, 1] = y
        tree = geometry.BoundingBoxTree(self.mesh, self.mesh.topology.dim)
        cand = geometry.compute_collisions(tree, pts)
        coll = geometry.compute_colliding_cells(self.mesh, cand, pts)
        cells = []
        for i in range(len(xs)):
            links = coll.links(i)
            if len(links) == 0:
                sys.exit("evaluate: point (%.6f, %.6f) outside the mesh" % (xs[i], y))
            cells.append(links[0])
        u = self.w.sub(0).collapse()
        th = self.w.sub(2).collapse()
        vy = u.eval(pts, np.array(cells, dtype=np.int32))[:, 1]
        tv = th.eval(pts, np.array(cells, dtype=np.int32))[:, 0]
        return tv, vy


def profile_points(n):
    # x in (0.6, 1]: the first point just off the (curved, P2-approximated) cylinder surface
    return np.linspace(0.6, 1.0, n + 1)[1:]


def write_csv(path, columns, rows, lines):
    with open(path, "w", newline="") as f:
        for line in lines:
            f.write("# " + line + "\n")
        w = csv.writer(f, lineterminator="\n")
        w.writerow(columns)
        for r in rows:
            w.writerow([("%.10g" % v) if isinstance(v, float) else v for v in r])


def observed_order(f, r):
    """Observed order from three values on meshes refined by the factor r each (coarse first)."""
    d1, d2 = f[0] - f[1], f[1] - f[2]
    if d1 == 0 or d2 == 0 or d1 / d2 <= 0:
        return float("nan")
    return np.log(d1 / d2) / np.log(r)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lc", default="0.04,0.02,0.01", help="bulk element sizes, coarse first (ratio constant)")
    ap.add_argument("--wall-ratio", type=float, default=4.0, help="bulk size / wall size")
    ap.add_argument("--order", type=int, default=2, help="geometry order (2 = curved cylinder)")
    ap.add_argument("--ra", default="1e4,3e4,1e5,3e5,1e6", help="continuation sequence")
    ap.add_argument("--report", default="1e4,1e5,1e6", help="Ra values written out")
    ap.add_argument("--points", type=int, default=400, help="profile points in (0.6, 1]")
    ap.add_argument("--out", default=HERE)
    args = ap.parse_args()
    import dolfinx
    import gmsh
    import petsc4py

    lcs = [float(s) for s in args.lc.split(",")]
    ras = [float(s) for s in args.ra.split(",")]
    report = [float(s) for s in args.report.split(",")]
    xs = profile_points(args.points)
    prov = [
        "generated by tests/data/refs/natural_convection/continuum_reference.py on %s UTC"
        % time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime()),
        "command: /usr/bin/python3 " + " ".join(sys.argv),
        "dolfinx %s, gmsh %s, petsc4py %s, python %s" % (dolfinx.__version__, gmsh.__version__,
                                                         petsc4py.__version__, sys.version.split()[0]),
        "steady Boussinesq NS, free-fall scaling, Sc = %g, unit square, concentric cylinder R = %g;" % (SC, RADIUS),
        "Taylor-Hood P2/P1 + P2 temperature, quadratic geometry order %d, Newton + Ra continuation %s" % (
            args.order, args.ra),
    ]
    prof_rows, nu_rows, meshes = [], [], []
    profiles = {}  # (mesh index, Ra) -> (theta, vstar)
    nus = {}
    for im, lc in enumerate(lcs):
        t0 = time.time()
        mesh, tags = build_mesh(lc, args.wall_ratio, args.order)
        ncells = mesh.topology.index_map(2).size_local
        s = Solver(mesh, tags)
        ndofs = s.W.dofmap.index_map.size_local * s.W.dofmap.index_map_bs
        meshes.append((lc, lc / args.wall_ratio, ncells, ndofs))
        print("mesh %d: lc %.4g (wall %.4g), %d triangles, %d dofs" % (im, lc, lc / args.wall_ratio, ncells, ndofs),
              flush=True)
        for ra in ras:
            its = s.solve(ra)
            q_cyl, q_box = s.nusselt()
            print("  Ra %.0e: %d Newton its, Q_cyl %.6f Q_box %.6f (%.0f s)" % (ra, its, q_cyl, q_box,
                                                                                time.time() - t0), flush=True)
            if ra not in report:
                continue
            th, vy = s.evaluate(xs)
            vstar = vy * np.sqrt(ra / SC)
            profiles[(im, ra)] = (th, vstar)
            nus[(im, ra)] = (q_cyl, q_box)
            nu_rows.append([int(round(ra)), im, lc, ncells, q_cyl, q_box, q_cyl / 2, q_box / 2])
            for x, t, v in zip(xs, th, vstar):
                prof_rows.append([int(round(ra)), im, float(x), float(t), float(v)])
        write_outputs(args, prov, meshes, prof_rows, nu_rows, profiles, nus, lcs[: im + 1], report)


def write_outputs(args, prov, meshes, prof_rows, nu_rows, profiles, nus, lcs, report):
    """Writes the CSVs for the meshes done so far (rewritten after every mesh)."""
    mesh_lines = ["mesh %d: bulk size %.4g, wall size %.4g, %d triangles, %d dofs" % ((i,) + m)
                  for i, m in enumerate(meshes)]
    write_csv(os.path.join(args.out, "continuum_profiles.csv"), ["Ra", "mesh", "xstar", "theta", "vstar"],
              prof_rows, prov + mesh_lines + [
                  "centre line y = 0.5; xstar from the left wall; vstar = v_y sqrt(Ra/Sc) (= v_y L / nu)"])
    write_csv(os.path.join(args.out, "continuum_nusselt.csv"),
              ["Ra", "mesh", "lc", "triangles", "Q_cylinder", "Q_enclosure", "Nu_half_cylinder",
               "Nu_half_enclosure"], nu_rows, prov + mesh_lines + [
                  "Q = -oint dtheta/dn ds (heat flow per unit depth / (k dT)), from the energy residual;",
                  "Nu_half = Q/2 (one symmetric half)"])
    # convergence: differences between successive meshes and observed order (needs >= 3 meshes)
    conv = []
    if len(lcs) >= 3:
        r = lcs[0] / lcs[1]
        for ra in report:
            n = len(lcs)
            for name, getter in (
                    ("Q_cylinder", lambda i: np.array([nus[(i, ra)][0]])),
                    ("Q_enclosure", lambda i: np.array([nus[(i, ra)][1]])),
                    ("theta_profile", lambda i: profiles[(i, ra)][0]),
                    ("vstar_profile", lambda i: profiles[(i, ra)][1])):
                vals = [getter(i) for i in range(n)]
                for i in range(n - 2):
                    e1 = float(np.max(np.abs(vals[i] - vals[i + 1])))
                    e2 = float(np.max(np.abs(vals[i + 1] - vals[i + 2])))
                    p = np.log(e1 / e2) / np.log(r) if e1 > 0 and e2 > 0 else float("nan")
                    # Richardson estimate of the finest mesh's error
                    err = e2 / (r ** p - 1) if np.isfinite(p) and p > 0 else float("nan")
                    conv.append([int(round(ra)), name, i, i + 1, i + 2, e1, e2, float(p), float(err)])
                    print("Ra %.0e %-14s meshes %d-%d-%d: max diff %.3e, %.3e; order %.2f; finest err ~ %.2e"
                          % (ra, name, i, i + 1, i + 2, e1, e2, p, err))
        write_csv(os.path.join(args.out, "continuum_convergence.csv"),
                  ["Ra", "quantity", "mesh_a", "mesh_b", "mesh_c", "maxdiff_ab", "maxdiff_bc", "observed_order",
                   "richardson_error_c"], conv, prov + mesh_lines + [
                      "maxdiff = max over the profile points (or the scalar) of |f_a - f_b|;",
                      "observed_order = ln(maxdiff_ab / maxdiff_bc) / ln(lc_a / lc_b);",
                      "richardson_error_c = maxdiff_bc / (r^order - 1), the estimated error of the finest mesh"])


if __name__ == "__main__":
    main()
