#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Writes the mesh files of examples/pipe_stl_3d.yaml, examples/channel_obstacle_gmsh_2d.yaml and
the geometry Morris-wall validations (tests/orchestrator/validation/geometry_morris/):

  pipe.stl                ASCII STL: a closed circular cylinder (the pipe's fluid body) of
                          radius R = 0.5 along z from z = -0.5 to z = 1.0, 192 sides, written
                          from numpy (no STL library needed)
  pipe.msh                the same cylinder from gmsh 4.8 (python3-gmsh, built-in kernel: a
                          192-point circle extruded in one layer, caps meshed by gmsh), .msh v4,
                          physical surface "pipe" (the whole closed surface)
  channel_obstacle_2d.msh gmsh 2D: the channel [-0.5, 4.5] x [0, 1] with a disk obstacle of
                          radius 0.2 at (1.2, 0.5); physical surfaces "inlet" (x < 0.5),
                          "outlet" (x > 3.5) and "fluid" (all of it, the disk included: its
                          closed boundary is the rectangle), physical curve "obstacle" (the
                          disk's outline: a solid body carves it out of the fluid)

Both pipe polygons put their vertices at R_v = R sqrt(2 pi / (N sin(2 pi / N))), so that the
polygon's area is pi R^2 (the cross-section of the exact pipe). Run from anywhere:
/usr/bin/python3 examples/data/meshes/make_meshes.py (needs numpy; gmsh for the .msh files).
"""
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
R, Z0, Z1, N = 0.5, -0.5, 1.0, 192
RV = R * math.sqrt(2 * math.pi / (N * math.sin(2 * math.pi / N)))


def pipe_triangles():
    a = 2 * np.pi * np.arange(N) / N
    ring = np.stack([RV * np.cos(a), RV * np.sin(a)], axis=1)
    tris = []
    for k in range(N):
        p, q = ring[k], ring[(k + 1) % N]
        b0, b1 = [p[0], p[1], Z0], [q[0], q[1], Z0]
        t0, t1 = [p[0], p[1], Z1], [q[0], q[1], Z1]
        tris += [(b0, b1, t1), (b0, t1, t0)]  # side, outward
        tris += [((0, 0, Z0), b1, b0), ((0, 0, Z1), t0, t1)]  # caps: -z and +z outward
    return np.array(tris, dtype=float)


def write_stl(path, tris):
    with open(path, "w") as f:
        f.write("solid pipe\n")
        for t in tris:
            n = np.cross(t[1] - t[0], t[2] - t[0])
            n /= np.linalg.norm(n)
            f.write("facet normal %.6g %.6g %.6g\n outer loop\n" % tuple(n))
            for v in t:
                f.write("  vertex %.9g %.9g %.9g\n" % tuple(v))
            f.write(" endloop\nendfacet\n")
        f.write("endsolid pipe\n")


def write_pipe_msh(gmsh, path):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("pipe")
    geo = gmsh.model.geo
    c = geo.addPoint(0, 0, Z0)
    pts = [geo.addPoint(RV * math.cos(2 * math.pi * k / 4), RV * math.sin(2 * math.pi * k / 4),
                        Z0, 0.2) for k in range(4)]
    arcs = [geo.addCircleArc(pts[k], c, pts[(k + 1) % 4]) for k in range(4)]
    loop = geo.addCurveLoop(arcs)
    cap = geo.addPlaneSurface([loop])
    out = geo.extrude([(2, cap)], 0, 0, Z1 - Z0, numElements=[1])
    geo.synchronize()
    for a in arcs:  # 48 segments per quarter: the 192-gon (gmsh's arcs are uniform in angle)
        gmsh.model.mesh.setTransfiniteCurve(a, N // 4 + 1)
    surfaces = [cap] + [t for (d, t) in out if d == 2]
    gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, surfaces), "pipe")
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.2)  # the caps: coarse inside
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(path)
    gmsh.finalize()


def write_channel_msh(gmsh, path):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("channel_obstacle")
    geo = gmsh.model.geo
    lc = 0.08
    xs = [-0.5, 0.5, 3.5, 4.5]
    bottom = [geo.addPoint(x, 0, 0, lc) for x in xs]
    top = [geo.addPoint(x, 1, 0, lc) for x in xs]
    lo = [geo.addLine(bottom[k], bottom[k + 1]) for k in range(3)]
    hi = [geo.addLine(top[k + 1], top[k]) for k in range(3)]
    cuts = [geo.addLine(bottom[k], top[k]) for k in range(4)]
    cx, cy, r = 1.2, 0.5, 0.2
    c = geo.addPoint(cx, cy, 0, lc)
    ring = [geo.addPoint(cx + r * math.cos(k * math.pi / 2), cy + r * math.sin(k * math.pi / 2), 0,
                         lc / 2) for k in range(4)]
    arcs = [geo.addCircleArc(ring[k], c, ring[(k + 1) % 4]) for k in range(4)]
    hole = geo.addCurveLoop(arcs)
    inlet = geo.addPlaneSurface([geo.addCurveLoop([lo[0], cuts[1], hi[0], -cuts[0]])])
    middle = geo.addPlaneSurface([geo.addCurveLoop([lo[1], cuts[2], hi[1], -cuts[1]]), hole])
    outlet = geo.addPlaneSurface([geo.addCurveLoop([lo[2], cuts[3], hi[2], -cuts[2]])])
    disk = geo.addPlaneSurface([hole])
    geo.synchronize()
    for dim, tags, name in [(2, [inlet], "inlet"), (2, [outlet], "outlet"),
                            (2, [inlet, middle, outlet, disk], "fluid"), (1, arcs, "obstacle")]:
        g = gmsh.model.addPhysicalGroup(dim, tags)
        gmsh.model.setPhysicalName(dim, g, name)
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(path)
    gmsh.finalize()


def main():
    write_stl(os.path.join(HERE, "pipe.stl"), pipe_triangles())
    try:
        import gmsh
    except ImportError:
        sys.exit("gmsh (python3-gmsh) is needed for the .msh files")
    write_pipe_msh(gmsh, os.path.join(HERE, "pipe.msh"))
    write_channel_msh(gmsh, os.path.join(HERE, "channel_obstacle_2d.msh"))


if __name__ == "__main__":
    main()
