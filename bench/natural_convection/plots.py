#!/usr/bin/python3
"""Pictures of the natural-convection runs (docs/natural-convection.md), to compare with
drawert2019 Fig. 5 (centre-line profiles) and with the flow pattern of Moukalled & Acharya.

    /usr/bin/python3 bench/natural_convection/plots.py --analysis A4.json A5.json A6.json \\
        --frames F4.csv F5.csv F6.csv [--molecules N ...] [--out docs/images]

A*.json are written by analyse.py --json (the window-averaged profiles); F*.csv one frame of each
run (a steady one) for the fields. Writes
* natural_convection_profiles.png: theta(x) and v*(x) on y = 0.5, x = 0.6-1, for each Ra: the
  window-averaged run, the continuum reference (tests/data/refs/natural_convection/) and the
  digitised Moukalled & Acharya points;
* natural_convection_series.png: kinetic energy, Nu near the cylinder and on the enclosure, and
  the steady-state criterion's largest relative rate against time;
* natural_convection_fields.png: for each Ra, theta (colour) with stream-function contours, and the
  speed |v| sqrt(Ra/Sc) (colour) with velocity arrows, from the frame interpolated on a 121^2 grid
  (Shepard-normalised Lucy kernel, as the scorer). The stream function psi is integrated from the
  interpolated u = d psi / dy upward from psi = 0 on the bottom wall.
"""
import argparse
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tests", "data", "refs", "natural_convection"))
from score_run import SC, Case, Interpolator, read_frame  # noqa: E402

COLOURS = {10000: "tab:blue", 100000: "tab:orange", 1000000: "tab:green"}


def label(ra):
    return "Ra = 1e%d" % round(math.log10(ra))


def profiles(analyses, out):
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for a in analyses:
        case = Case(a["Ra"])
        c = COLOURS.get(case.ra, "k")
        p = a["profiles"]
        tag = "sadr (%s, t = %g-%g, %d frames)" % ("SSA N=%g" % a["molecules"] if a["molecules"] else "SDPD",
                                                   a["window"][0], a["window"][1], a["frames_averaged"])
        if not a["steady"]:
            tag += ", NOT steady"
        for k, q in enumerate(("theta", "vstar")):
            ax[k].plot(p["x_ref"], p[q + "_ref"], "-", color=c, lw=1.6, label="%s: %s" % (label(case.ra), tag))
            ax[k].plot(case.x_ref, case.ref[q], "--", color="k", lw=0.8,
                       label="continuum reference (FEniCS)" if case.ra == analyses[0]["Ra"] else None)
            ax[k].plot(case.x_dig[q], case.dig[q], "o", mfc="none", color=c, ms=3.5,
                       label="Moukalled & Acharya (digitised)" if case.ra == analyses[0]["Ra"] else None)
    ax[0].set_ylabel("theta (= C*)")
    ax[1].set_ylabel("v* = v_y sqrt(Ra/Sc)")
    for k in range(2):
        ax[k].set_xlabel("x* on y = 0.5")
        ax[k].set_xlim(0.6, 1.0)
        ax[k].grid(alpha=0.3)
    ax[1].axhline(0, color="grey", lw=0.5)
    ax[0].legend(fontsize=7, loc="upper right")
    fig.suptitle("Natural convection past a hot cylinder: centre-line profiles (cf. drawert2019 Fig. 5)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "natural_convection_profiles.png"), dpi=110)
    plt.close(fig)


def series(analyses, out):
    fig, ax = plt.subplots(1, 3, figsize=(13, 3.8))
    for a in analyses:
        c = COLOURS.get(a["Ra"], "k")
        for s, ts in zip(a["series"], a["t_steady"]):
            t = np.array(s["time"])
            ax[0].plot(t, s["kinetic_energy"], color=c, label=label(a["Ra"]))
            ax[1].plot(t, s["Nu_near_cylinder"], color=c, label="%s cylinder" % label(a["Ra"]))
            ax[1].plot(t, s["Nu_enclosure"], ":", color=c, label="%s enclosure" % label(a["Ra"]))
            worst = [max([v for v in vals if v is not None] or [np.nan])
                     for vals in zip(*[s["rate_" + n] for n in ("kinetic_energy", "Nu_near_cylinder",
                                                                "Nu_enclosure")])]
            ax[2].semilogy(t, worst, color=c, label="%s (over %g)" % (label(a["Ra"]), a["rate_window"]))
            if ts is not None:
                for k in range(3):
                    ax[k].axvline(ts, color=c, lw=0.6, ls="--")
        ax[1].axhline(Case(a["Ra"]).nu_ref, color=c, lw=0.6)
    ax[2].axhline(analyses[0]["threshold_per_time"], color="k", lw=0.8)
    ax[0].set_ylabel("kinetic energy of the fluid")
    ax[1].set_ylabel("Nu_half (line: continuum)")
    ax[2].set_ylabel("largest |dX/dt| / |X| (slope window in the legend)")
    for k in range(3):
        ax[k].set_xlabel("t")
        ax[k].grid(alpha=0.3)
        ax[k].legend(fontsize=7)
    fig.suptitle("Approach to steady state (dashed: t_steady by analyse.py's criterion)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "natural_convection_series.png"), dpi=100)
    plt.close(fig)


def fields(frames, ras, molecules, out, n=121):
    fig, ax = plt.subplots(2, len(frames), figsize=(4.2 * len(frames), 8.2), squeeze=False)
    g = (np.arange(n) + 0.5) / n
    X, Y = np.meshgrid(g, g)
    inside = (X - 0.5) ** 2 + (Y - 0.5) ** 2 < 0.1 ** 2
    for k, (path, ra, mol) in enumerate(zip(frames, ras, molecules)):
        fr = read_frame(path)
        if mol > 0:
            fr["theta"] = fr["theta"] / mol
        v = Interpolator(fr, 3.0 / 81.0)(np.column_stack((X.ravel(), Y.ravel())))
        th, u, w = (v[q].reshape(X.shape) for q in ("theta", "vx", "vy"))
        psi = np.cumsum(u, axis=0) / n  # psi(x, y) = int_0^y u dy'
        psi -= 0.5 * u / n
        for a in (th, psi, u, w):
            a[inside] = np.nan
        scale = math.sqrt(ra / SC)
        t = float(fr["time"][0])
        a = ax[0][k]
        im = a.pcolormesh(X, Y, th, cmap="inferno", vmin=0, vmax=1, shading="auto")
        a.contour(X, Y, psi * scale, levels=14, colors="w", linewidths=0.6)
        fig.colorbar(im, ax=a, fraction=0.046, label="theta")
        a.set_title("%s, t = %g: theta, stream lines" % (label(ra), t), fontsize=9)
        a = ax[1][k]
        sp = np.hypot(u, w) * scale
        im = a.pcolormesh(X, Y, sp, cmap="viridis", shading="auto")
        s = slice(3, None, 8)
        a.quiver(X[s, s], Y[s, s], u[s, s], w[s, s], color="w", scale_units="xy", angles="xy",
                 scale=np.nanmax(np.hypot(u, w)) / 0.06)
        fig.colorbar(im, ax=a, fraction=0.046, label="|v| sqrt(Ra/Sc)")
        a.set_title("%s: speed" % label(ra), fontsize=9)
        for a in (ax[0][k], ax[1][k]):
            a.add_patch(plt.Circle((0.5, 0.5), 0.1, color="lightgrey"))
            a.set_aspect("equal")
            a.set_xlim(0, 1)
            a.set_ylim(0, 1)
            a.set_xticks([0, 0.5, 1])
            a.set_yticks([0, 0.5, 1])
    fig.tight_layout()
    fig.savefig(os.path.join(out, "natural_convection_fields.png"), dpi=100)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--analysis", nargs="+", required=True, help="analyse.py --json outputs")
    ap.add_argument("--frames", nargs="*", default=[], help="one frame per analysis, same order")
    ap.add_argument("--out", default=os.path.join(HERE, "..", "..", "docs", "images"))
    args = ap.parse_args()
    analyses = []
    for p in args.analysis:
        with open(p) as f:
            analyses.append(json.load(f))
        if "profiles" not in analyses[-1]:
            sys.exit("%s: the run was not steady by analyse.py's criterion (and no --from); nothing averaged" % p)
    profiles(analyses, args.out)
    series(analyses, args.out)
    if args.frames:
        if len(args.frames) != len(analyses):
            sys.exit("give one frame per analysis (%d analyses, %d frames)" % (len(analyses), len(args.frames)))
        fields(args.frames, [a["Ra"] for a in analyses], [a["molecules"] for a in analyses], args.out)


if __name__ == "__main__":
    main()
