#!/usr/bin/env python3
"""Writes examples/data/yeast_cell_particles.csv for examples/yeast_cell_channel.yaml.

drawert2019 sec. 4.3 at the paper's resolution: a 2 x 1 channel (units of
H = 100 um) filled with a 50 x 25 lattice of fluid particles (dx = 0.04, the
paper's N = 1250), three layers of wall particles below y = 0 and above y = 1,
and a yeast cell of diameter 0.05 centred at (0.25, 0.5): one interior
particle plus a ring of 6 membrane particles at radius 0.025, after removing
the lattice particles closer than 0.045 to the centre (a lattice cannot
resolve a cell 1.25 dx wide). All particles have mass rho dx^2 and density
rho = 1, so every voxel volume is V = m / rho = dx^2 = 0.0016.

The fluid particles are displaced by up to +-0.1 dx per axis (fixed seed).
Without it the lattice row y = 0.5 lies exactly on the cell's stagnation
streamline: by symmetry those particles never turn aside (vy = 0 to the last
bit), so they queue up in front of the cell, a blockage that grows with every
pass through the periodic channel (measured: the centre-line speed fell from
1.06 to 0.96 between t = 0.1 and 0.5).

Usage: python3 examples/data/make_yeast_cell_particles.py > examples/data/yeast_cell_particles.csv
"""
import math
import random
import sys

DX = 0.04
RHO = 1.0
LENGTH, HEIGHT = 2.0, 1.0
CELL = (0.25, 0.5)
CELL_RADIUS = 0.025
CLEARANCE = 0.045
WALL_LAYERS = 3
JITTER = 0.1  # of dx, fluid particles only


def main(out):
    mass = RHO * DX * DX
    rng = random.Random(2019)
    rows = []
    nx, ny = round(LENGTH / DX), round(HEIGHT / DX)
    for i in range(nx):
        x = (i + 0.5) * DX
        for j in range(-WALL_LAYERS, ny + WALL_LAYERS):
            y = (j + 0.5) * DX
            if 0 <= j < ny:
                if math.hypot(x - CELL[0], y - CELL[1]) < CLEARANCE:
                    continue
                jx, jy = (rng.uniform(-JITTER, JITTER) * DX for _ in range(2))
                rows.append((x + jx, y + jy, "fluid"))
            else:
                rows.append((x, y, "wall"))
    rows.append((CELL[0], CELL[1], "wall"))
    for k in range(6):
        a = 2 * math.pi * k / 6
        rows.append((CELL[0] + CELL_RADIUS * math.cos(a), CELL[1] + CELL_RADIUS * math.sin(a), "wall"))
    out.write("x,y,z,mass,density,kind\n")
    for x, y, kind in rows:
        out.write(f"{x:.17g},{y:.17g},0,{mass:.17g},{RHO:.17g},{kind}\n")


if __name__ == "__main__":
    main(sys.stdout)
