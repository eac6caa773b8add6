#!/usr/bin/python3
"""The scorer's own smoothing: score_run.py's measure applied to the continuum solution sampled at
particle positions (docs/natural-convection.md, "Why the velocity peaks are low").

    /usr/bin/python3 bench/natural_convection/scorer_bias.py --ra 1e4,1e5,1e6 --lattice 41,81,121
        [--frame FRAME.csv --frame-lattice N] [--lc 0.04] [--json OUT.json]

Solves the steady continuum problem (continuum_reference.py's Solver, one mesh of bulk size --lc,
Ra continuation up to --ra), then for every lattice N (dx = 1/N, h = 3 dx) builds the scene's
particles (the lattice points (i + 1/2) dx inside the enclosure, fluid where r > 0.1, wall inside the
cylinder's disk and in 5 layers outside the enclosure), gives the fluid particles the continuum theta
and velocity at their positions and the walls v = 0 and their held theta, and measures that frame
with score_run.measure / score exactly as a run's frame. The result is what the scorer reports for
the exact solution: its peaks and errors are the interpolation's bias at h = 3 dx, not the run's.
--frame uses the positions (and kinds) of a run's frame instead of a lattice.
Needs python3-dolfinx and python3-gmsh (as continuum_reference.py).
"""
import argparse
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REFS = os.path.join(HERE, "..", "..", "tests", "data", "refs", "natural_convection")
sys.path.insert(0, REFS)
from continuum_reference import Solver, build_mesh  # noqa: E402
from score_run import Case, measure, read_frame, score  # noqa: E402

SC = 0.7


def evaluate_points(solver, pts):
    """theta, v_x, v_y of the continuum at 2D points; NaN where a point is outside the mesh."""
    from dolfinx import geometry

    p3 = np.zeros((len(pts), 3))
    p3[:, :2] = pts
    tree = geometry.BoundingBoxTree(solver.mesh, solver.mesh.topology.dim)
    cand = geometry.compute_collisions(tree, p3)
    coll = geometry.compute_colliding_cells(solver.mesh, cand, p3)
    found = np.array([len(coll.links(i)) > 0 for i in range(len(pts))])
    cells = np.array([coll.links(i)[0] for i in range(len(pts)) if found[i]], dtype=np.int32)
    u = solver.w.sub(0).collapse()
    th = solver.w.sub(2).collapse()
    out = np.full((len(pts), 3), np.nan)
    if found.any():
        out[found, 0] = th.eval(p3[found], cells)[:, 0]
        out[found, 1:] = u.eval(p3[found], cells)[:, :2]
    return out


def lattice_frame(n, layers=5):
    dx = 1.0 / n
    k = np.arange(-layers, n + layers) + 0.5
    X, Y = np.meshgrid(k * dx, k * dx)
    x, y = X.ravel(), Y.ravel()
    inside = (x > 0) & (x < 1) & (y > 0) & (y < 1)
    cyl = np.hypot(x - 0.5, y - 0.5) <= 0.1
    kind = np.where(inside & ~cyl, 0, 1)
    return {"x": x, "y": y, "kind": kind, "mass": np.full_like(x, dx * dx), "density": np.ones_like(x)}


def fill(frame, solver, ra):
    x, y = frame["x"], frame["y"]
    r = np.hypot(x - 0.5, y - 0.5)
    fluid = frame["kind"] == 0
    vals = np.zeros((len(x), 3))
    vals[fluid] = evaluate_points(solver, np.column_stack((x[fluid], y[fluid])))
    # fluid points outside the (curved P2) mesh by round-off: take the wall values
    bad = fluid & ~np.isfinite(vals[:, 0])
    vals[bad] = 0.0
    theta = np.where(r <= 0.1 + 1e-12, 1.0, 0.0)  # walls: held values
    theta[fluid & ~bad] = vals[fluid & ~bad, 0]
    theta[bad] = np.where(r[bad] < 0.3, 1.0, 0.0)
    out = dict(frame)
    out.update({"theta": theta, "vx": np.where(fluid, vals[:, 1], 0.0), "vy": np.where(fluid, vals[:, 2], 0.0),
                "time": np.zeros_like(x)})
    return out, int(bad.sum())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ra", default="1e4", help="Ra values, comma separated (continuation 1e4 ... 1e6)")
    ap.add_argument("--lattice", default="41,81,121")
    ap.add_argument("--frame", action="append", default=[])
    ap.add_argument("--frame-lattice", type=int, action="append", default=[],
                    help="N of each --frame (h = 3/N, dx = 1/N)")
    ap.add_argument("--lc", type=float, default=0.04, help="bulk element size of the continuum mesh")
    ap.add_argument("--json")
    args = ap.parse_args()
    mesh, tags = build_mesh(args.lc, 4.0, 2)
    s = Solver(mesh, tags)
    wanted = [float(r) for r in args.ra.split(",")]
    jobs = [("lattice %d^2" % int(n), lattice_frame(int(n)), int(n)) for n in args.lattice.split(",") if n]
    for path, n in zip(args.frame, args.frame_lattice):
        fr = read_frame(path)
        jobs.append(("frame %s (%d^2)" % (path, n), {k: fr[k] for k in ("x", "y", "kind", "mass", "density")}, n))
    res = {"lc": args.lc, "results": []}
    for ra in (1e4, 3e4, 1e5, 3e5, 1e6):
        if ra > max(wanted) * (1 + 1e-9):
            break
        s.solve(ra)
        if ra in wanted:
            score_all(s, ra, jobs, args.lc, res)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(res, fh, indent=1)


def score_all(s, ra, jobs, lc, res):
    case = Case(ra)
    print("continuum sampled at particle positions, scored by score_run (Ra = %g, mesh lc = %g)" % (ra, lc))
    print("%-40s %9s %9s %8s %8s %8s %8s %8s" % ("positions", "theta_err", "v*_err", "pk_cyl", "pk_wall",
                                                "pkc %", "pkw %", "Nu %"))
    for name, fr, n in jobs:
        f, bad = fill(fr, s, ra)
        m = measure(f, case, 3.0 / n, 1.0 / n)
        sc = score(m, case)
        pc, pw = sc["vstar_peak_cylinder"], sc["vstar_peak_wall"]
        rc, rw = sc["vstar_peak_cylinder_reference"], sc["vstar_peak_wall_reference"]
        row = {"Ra": ra, "positions": name, "outside_mesh": bad, **sc}
        res["results"].append(row)
        print("%-40s %9.3e %9.4f %8.2f %8.2f %+8.2f %+8.2f %+8.2f" % (
            name, sc["theta_err_ref"], sc["vstar_err_ref"], pc, pw, 100 * (pc / rc - 1), 100 * (pw / rw - 1),
            100 * (sc["Nu_half"] / sc["Nu_half_reference"] - 1)))


if __name__ == "__main__":
    main()
