#!/usr/bin/python3
"""A scene that starts from one frame of a natural-convection run (docs/natural-convection.md,
"Realizations against frames"): the frame's particles (positions, velocities, densities, masses,
kinds and theta) as a particle file, everything else from the run's scene.

    /usr/bin/python3 bench/natural_convection/restart_scene.py FRAME.csv SCENE.yaml OUTDIR \\
        [--end T] [--every DT]

Writes OUTDIR/particles.csv and OUTDIR/scene.yaml (time from 0 to T, frames every DT). For a
stochastic scene the frame's theta column (copy numbers) becomes the initial count of every particle
(`count_column`); the held wall values stay the scene's `boundaries` (a `count` as the
concentration count / dx^d, the frame's wall particles having slightly unequal volumes). Used to run an ensemble
(`sadr run OUTDIR/scene.yaml -r R`) of realizations that start from one steady state, so that
each realization costs the averaging window alone and not the transient. The flow state is the
same in every realization at t = 0: only the part of the noise that decorrelates within the window
(the copy-number noise, in about dx^2 / kappa) is independent between them.
"""
import argparse
import os
import sys

import numpy as np
import yaml


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("frame")
    ap.add_argument("scene")
    ap.add_argument("outdir")
    ap.add_argument("--end", type=float, default=10.0)
    ap.add_argument("--every", type=float, default=1.0)
    args = ap.parse_args()
    with open(args.frame) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(args.frame, delimiter=",", skiprows=1)
    col = {n: i for i, n in enumerate(header)}
    for need in ("x", "y", "vx", "vy", "density", "mass", "theta", "kind"):
        if need not in col:
            sys.exit("%s: no column '%s'" % (args.frame, need))
    with open(args.scene) as f:
        scene = yaml.safe_load(f)
    spacing = scene["particles"]["spacing"]
    sp = [s for s in scene["species"] if s["name"] == "theta"][0]
    stochastic = bool(sp.get("stochastic", False))
    os.makedirs(args.outdir, exist_ok=True)
    kinds = {0: "fluid", 1: "wall", 2: "inlet", 3: "outlet"}
    with open(os.path.join(args.outdir, "particles.csv"), "w") as f:
        f.write("x,y,z,mass,density,kind,vx,vy,vz,theta0\n")
        for row in data:
            k = row[col["kind"]]
            kind = kinds[int(round(k))]
            th = row[col["theta"]]
            if stochastic:
                th = round(th)
            f.write("%.17g,%.17g,0,%.17g,%.17g,%s,%.17g,%.17g,0,%.17g\n"
                    % (row[col["x"]], row[col["y"]], row[col["mass"]], row[col["density"]], kind,
                       row[col["vx"]] if kind == "fluid" else 0.0, row[col["vy"]] if kind == "fluid" else 0.0,
                       th))
    scene["particles"] = {"file": "particles.csv", "spacing": spacing}
    sp["initial"] = [{"count_column" if stochastic else "concentration_column": "theta0"}]
    # the held values and the wall surfaces belong to wall particles, but fluid particles move into
    # the geometric regions (across the staircase cylinder r = 0.1, past the planes x, y = 0, 1):
    # those regions become the wall particles they held, by id (row order of the particle file)
    kind = data[:, col["kind"]]
    x, y = data[:, col["x"]], data[:, col["y"]]
    regions = {r["name"]: r for r in scene["regions"]}
    used = {b["region"] for b in sp.get("boundaries", [])} | {w["region"] for w in scene["fluid"].get("wall_planes", [])}
    for name in sorted(used):
        r = regions[name]
        if r["shape"] == "disk":
            inside = np.hypot(x - r["center"][0], y - r["center"][1]) <= r["radius"]
        elif r["shape"] == "box":
            inside = (x >= r["lower"][0]) & (x <= r["upper"][0]) & (y >= r["lower"][1]) & (y <= r["upper"][1])
        elif r["shape"] == "channel":
            v = x if r["axis"] == "x" else y
            inside = (v >= r["lower"]) & (v <= r["upper"])
        else:
            sys.exit("region %s: shape %s not handled" % (name, r["shape"]))
        ids = [int(i) for i in np.nonzero(inside & (kind == 1))[0]]
        scene["regions"].append({"name": name + "_walls", "shape": "ids", "ids": ids})
    for b in sp.get("boundaries", []) + scene["fluid"].get("wall_planes", []):
        b["region"] = b["region"] + "_walls"
    # the wall densities of a frame differ by a few 1e-3, and a `count` boundary needs equal particle
    # volumes: hold the same copy number as the concentration count / dx^d instead (the SSA rounds
    # C V_i to the nearest whole number, the same count while |V_i / dx^d - 1| < 0.5 / count)
    for b in sp.get("boundaries", []):
        if "count" in b:
            b["value"] = b.pop("count") / spacing ** scene["dimension"]
    scene["name"] = scene["name"] + "_restart"
    scene["description"] = "%s, restarted from %s" % (scene.get("description", ""), os.path.abspath(args.frame))
    scene["time"]["end"] = args.end
    scene["output"]["every"] = args.every
    scene["output"]["checkpoint_every"] = 0
    with open(os.path.join(args.outdir, "scene.yaml"), "w") as f:
        f.write("# written by bench/natural_convection/restart_scene.py %s %s\n" % (args.frame, args.scene))
        yaml.safe_dump(scene, f, sort_keys=False, default_flow_style=None)


if __name__ == "__main__":
    main()
