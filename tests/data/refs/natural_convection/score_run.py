#!/usr/bin/python3
"""Scores a natural-convection run (examples/natural_convection_ra1e*.yaml) against the continuum
reference (continuum_profiles.csv, continuum_nusselt.csv) and the digitised Moukalled & Acharya
profiles (moukalled_digitised_profiles.csv), with drawert2019's metric ||f - f_ref||_2 / n.

    /usr/bin/python3 tests/data/refs/natural_convection/score_run.py FRAME.csv --ra 1e4 [--h H]
        [--average FRAME2.csv ...] [--json OUT.json]

FRAME.csv is a CSV frame written by `sadr run` (columns time,id,kind,x,y,z,vx,vy,vz,density,mass,
theta); for the stochastic variant give --molecules N (theta = copy number / N). Several frames (the positional one and --average) are averaged after interpolation.

* Centre-line profiles theta(x), v*(x) = v_y sqrt(Ra/Sc) at y = 0.5: Shepard (normalised) Lucy-kernel
  interpolation over all particles (walls hold theta at its wall value and v = 0), at the continuum
  reference's points and at the digitised points, 0.6 < x < 1. The metric ||.||_2 / n depends on
  the number of points n, so the errors comparable with drawert2019's Table 2 are those on the
  digitised points: against the digitised values (*_err_digitised) and against the continuum
  reference interpolated there (*_err_ref_at_digitised_x); *_err_ref uses the reference's 399
  points (n 4x larger: about half the value for the same pointwise error).
* Mean Nusselt number: the heat flow through circles of radius r around the cylinder,
  Q(r) = oint (v_r theta / kappa - d theta / dr) r dphi, constant in r at steady state; theta and v
  interpolated as above on 256 angles, d/dr by central differences over +-dx/2; reported as Q/2
  (one symmetric half, as continuum_nusselt.csv's Nu_half) averaged over r in [0.2, 0.4].
* Density variation max |rho/rho_0 - 1| over the fluid particles (the weak-compressibility error).
"""
import argparse
import json
import math
import os
import sys

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.spatial import cKDTree

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from compare_digitised import load, paper_metric  # noqa: E402

SC = 0.7


def read_frame(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1)
    col = {name: i for i, name in enumerate(header)}
    for need in ("x", "y", "vx", "vy", "density", "mass", "theta", "kind"):
        if need not in col:
            sys.exit("%s: no column '%s' (header: %s)" % (path, need, ",".join(header)))
    return {k: data[:, i] for k, i in col.items()}


def lucy(r, h):
    q = np.clip(r / h, 0.0, 1.0)
    return 5.0 / (math.pi * h * h) * (1 + 3 * q) * (1 - q) ** 3


class Interpolator:
    """Shepard-normalised Lucy interpolation of theta, vx, vy over all particles within h."""

    K = 64  # neighbours looked at; about pi (h/dx)^2 = 28 lie within h = 3 dx

    def __init__(self, frame, h):
        self.pos = np.column_stack((frame["x"], frame["y"]))
        self.vol = frame["mass"] / frame["density"]
        self.fields = {"theta": frame["theta"], "vx": frame["vx"], "vy": frame["vy"]}
        self.tree = cKDTree(self.pos)
        self.h = h

    def __call__(self, pts):
        dist, idx = self.tree.query(pts, k=self.K, distance_upper_bound=self.h)
        if np.any(np.isfinite(dist[:, -1])):
            i = int(np.argmax(np.isfinite(dist[:, -1])))
            sys.exit("more than %d particles within h = %.4g of (%.4f, %.4f): raise Interpolator.K"
                     % (self.K, self.h, pts[i][0], pts[i][1]))
        inside = np.isfinite(dist)
        if not np.all(inside.any(axis=1)):
            i = int(np.argmin(inside.any(axis=1)))
            sys.exit("no particle within h = %.4g of (%.4f, %.4f)" % (self.h, pts[i][0], pts[i][1]))
        idx = np.where(inside, idx, 0)
        w = np.where(inside, lucy(np.where(inside, dist, self.h), self.h) * self.vol[idx], 0.0)
        norm = w.sum(axis=1)
        return {k: np.sum(w * f[idx], axis=1) / norm for k, f in self.fields.items()}


class Case:
    """The references of one Ra: continuum profile (finest mesh), digitised points, Nu_half."""

    def __init__(self, ra):
        self.ra = int(round(ra))
        self.kappa = 1.0 / math.sqrt(ra * SC)
        self.vscale = math.sqrt(ra / SC)
        prof = load(os.path.join(HERE, "continuum_profiles.csv"))
        self.mesh = int(prof["mesh"].max())
        sel = (prof["Ra"] == self.ra) & (prof["mesh"] == self.mesh)
        if not np.any(sel):
            sys.exit("no continuum profile for Ra = %d" % self.ra)
        keep = prof["xstar"][sel] < 1.0
        self.x_ref = prof["xstar"][sel][keep]
        self.ref = {"theta": prof["theta"][sel][keep], "vstar": prof["vstar"][sel][keep]}
        dig = load(os.path.join(HERE, "moukalled_digitised_profiles.csv"))
        self.x_dig, self.dig, self.ref_at_dig = {}, {}, {}
        for q in ("theta", "vstar"):
            d = (dig["Ra"] == self.ra) & (dig["quantity"] == q) & (dig["xstar"] > 0.6) & (dig["xstar"] < 1.0)
            self.x_dig[q], self.dig[q] = dig["xstar"][d], dig["value"][d]
            self.ref_at_dig[q] = CubicSpline(self.x_ref, self.ref[q])(self.x_dig[q])
        nus = load(os.path.join(HERE, "continuum_nusselt.csv"))
        self.nu_ref = float(nus["Nu_half_cylinder"][(nus["Ra"] == self.ra) & (nus["mesh"] == self.mesh)][0])


# contours for the heat flow Q = oint (v.n theta / kappa - d theta / dn) ds (n pointing away from the
# cylinder): circles around the cylinder, and squares inset from the enclosure walls by more than h
CIRCLES_NEAR = (0.15, 0.175, 0.2)
CIRCLES_MID = tuple(np.linspace(0.2, 0.4, 5))
SQUARE_INSETS = (0.05, 0.075, 0.1)


def circle_flow(ip, kappa, r, dx, n=256):
    phi = np.linspace(0, 2 * math.pi, n, endpoint=False)
    c, s = np.cos(phi), np.sin(phi)
    v = {tag: ip(np.column_stack((0.5 + rr * c, 0.5 + rr * s)))
         for tag, rr in (("m", r - dx / 2), ("c", r), ("p", r + dx / 2))}
    vn = v["c"]["vx"] * c + v["c"]["vy"] * s
    dtdn = (v["p"]["theta"] - v["m"]["theta"]) / dx
    return float(np.mean(vn * v["c"]["theta"] / kappa - dtdn) * 2 * math.pi * r)


def square_flow(ip, kappa, inset, dx, n=64):
    """Heat flow out through the square [inset, 1 - inset]^2 (midpoint rule, n points a side)."""
    a, b = inset, 1.0 - inset
    t = a + (np.arange(n) + 0.5) * (b - a) / n
    total = 0.0
    for nx, ny in ((1, 0), (-1, 0), (0, 1), (0, -1)):
        if nx:
            base = np.column_stack((np.full(n, b if nx > 0 else a), t))
        else:
            base = np.column_stack((t, np.full(n, b if ny > 0 else a)))
        off = np.array([nx, ny]) * dx / 2
        vm, vc, vp = ip(base - off), ip(base), ip(base + off)
        vn = vc["vx"] * nx + vc["vy"] * ny
        total += np.mean(vn * vc["theta"] / kappa - (vp["theta"] - vm["theta"]) / dx) * (b - a)
    return float(total)


def measure(fr, case, h, dx):
    """Everything one frame gives (fr: columns of a CSV frame, theta already scaled to 0..1):
    centre-line profiles at the reference's and the digitised points, heat flows through the
    contours, kinetic energy and density variation of the fluid."""
    ip = Interpolator(fr, h)
    fluid = fr["kind"] == 0
    out = {"time": float(fr["time"][0])}
    line = ip(np.column_stack((case.x_ref, np.full_like(case.x_ref, 0.5))))
    out["theta_ref"], out["vstar_ref"] = line["theta"], line["vy"] * case.vscale
    for q in ("theta", "vstar"):
        v = ip(np.column_stack((case.x_dig[q], np.full_like(case.x_dig[q], 0.5))))
        out[q + "_dig"] = v["theta"] if q == "theta" else v["vy"] * case.vscale
    out["Q_near"] = np.array([circle_flow(ip, case.kappa, r, dx) for r in CIRCLES_NEAR])
    out["Q"] = np.array([circle_flow(ip, case.kappa, r, dx) for r in CIRCLES_MID])
    out["Q_enclosure"] = np.array([square_flow(ip, case.kappa, d, dx) for d in SQUARE_INSETS])
    v2 = fr["vx"][fluid] ** 2 + fr["vy"][fluid] ** 2
    out["kinetic_energy"] = float(0.5 * np.sum(fr["mass"][fluid] * v2))
    out["max_speed"] = float(np.sqrt(np.max(v2)))
    out["max_density_variation"] = float(np.max(np.abs(fr["density"][fluid] - 1.0)))
    return out


NEAR_WALL = 0.05  # width of the near-wall zones of score() [L]


def near_wall_zones(x):
    """Masks of the centre-line points x in (0.6, 1): next to the cylinder, in the bulk, next to the
    right wall."""
    return {"cylinder": x < 0.6 + NEAR_WALL, "bulk": (x >= 0.6 + NEAR_WALL) & (x <= 1.0 - NEAR_WALL),
            "wall": x > 1.0 - NEAR_WALL}


def score(avg, case):
    """The errors of (averaged) measurements `avg` (as from measure) against both references."""
    out = {"Ra": case.ra, "reference_mesh": case.mesh}
    for q in ("theta", "vstar"):
        out[q + "_err_ref"] = paper_metric(avg[q + "_ref"] - case.ref[q])
        out[q + "_maxabs_ref"] = float(np.max(np.abs(avg[q + "_ref"] - case.ref[q])))
    # where the errors sit: rms and max of f - f_ref on the reference's points within NEAR_WALL
    # of the cylinder surface (x = 0.6) and of the right wall (x = 1), and in the bulk between
    for zone, sel in near_wall_zones(case.x_ref).items():
        for q in ("theta", "vstar"):
            d = avg[q + "_ref"][sel] - case.ref[q][sel]
            out["%s_rms_%s" % (q, zone)] = float(np.sqrt(np.mean(d * d)))
            out["%s_maxabs_%s" % (q, zone)] = float(np.max(np.abs(d)))
    # the two v* peaks (near the cylinder, near the right wall) against the reference's
    for zone, sel in (("cylinder", case.x_ref < 0.8), ("wall", case.x_ref >= 0.8)):
        out["vstar_peak_%s" % zone] = float(np.max(np.abs(avg["vstar_ref"][sel])))
        out["vstar_peak_%s_reference" % zone] = float(np.max(np.abs(case.ref["vstar"][sel])))
    for q in ("theta", "vstar"):
        out[q + "_err_digitised"] = paper_metric(avg[q + "_dig"] - case.dig[q])
        # the continuum reference at the digitised points: the same n as the paper's metric
        out[q + "_err_ref_at_digitised_x"] = paper_metric(avg[q + "_dig"] - case.ref_at_dig[q])
    out["Nu_half"] = float(np.mean(avg["Q"]) / 2)
    out["Nu_half_spread_over_r"] = float((np.max(avg["Q"]) - np.min(avg["Q"])) / 2)
    out["Nu_half_near_cylinder"] = float(np.mean(avg["Q_near"]) / 2)
    out["Nu_half_enclosure"] = float(np.mean(avg["Q_enclosure"]) / 2)
    out["Nu_half_reference"] = case.nu_ref
    return out


def average(measurements):
    keys = [k for k, v in measurements[0].items() if not isinstance(v, str)]
    return {k: sum(m[k] for m in measurements) / len(measurements) for k in keys}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("frame")
    ap.add_argument("--average", nargs="*", default=[])
    ap.add_argument("--ra", type=float, required=True)
    ap.add_argument("--h", type=float, default=3.0 / 81.0, help="smoothing length (default 3/81)")
    ap.add_argument("--dx", type=float, default=1.0 / 81.0)
    ap.add_argument("--molecules", type=float, default=0.0,
                    help="stochastic variant: molecules per particle at theta = 1 (theta = count / N)")
    ap.add_argument("--json")
    args = ap.parse_args()
    case = Case(args.ra)
    ms = []
    for path in [args.frame] + args.average:
        fr = read_frame(path)
        if args.molecules > 0:
            fr["theta"] = fr["theta"] / args.molecules
        ms.append(measure(fr, case, args.h, args.dx))
    out = score(average(ms), case)
    out["frames"] = len(ms)
    out["max_density_variation"] = max(m["max_density_variation"] for m in ms)
    for k, v in out.items():
        print("%-24s %s" % (k, ("%.4g" % v) if isinstance(v, float) else v))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
