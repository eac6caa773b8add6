#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""li2015 Figs. 9 and 10 from a coagulation channel run (examples/coagulation_cascade*.yaml).

  /usr/bin/python3 bench/coagulation/plot_cascade.py RUN_DIR [--prefix docs/images/coagulation]
      [--reference channel_reference.csv ...]

Writes PREFIX_timeseries.png (Fig. 10: thrombin IIa, fibrin Ia, antithrombin ATIII and APC at
the centre of the injury, the mean over the fluid particles with 14 <= x <= 16 in the injury
layer, height y < 0.7 (the first fluid row at spacing 1, the first two at 0.625), all z; with
--reference, the probe series of bench/coagulation/channel_reference.py as lines)
and PREFIX_fibrin.png (Fig. 9: fibrin averaged over the depth z on 1 x 1 bins of the x-y plane at six
times, 0 <= x <= 50 and y <= 8 shown, the 3 uM = 3000 nM clot threshold as a white line), and prints the qualitative features
li2015 reports (thrombin burst then drop, fibrin rising then levelling, antithrombin dropping,
APC rising) as numbers.
"""
import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
import sadr  # noqa: E402

PROBE = ((14.0, 16.0), (0.0, 0.7))  # x range, y (height) range: the injury centre at the wall
SHOWN = [("IIa", "thrombin"), ("Ia", "fibrin"), ("ATIII", "antithrombin III"), ("APC", "APC")]
THRESHOLD = 3000.0  # nM, li2015's clot threshold for fibrin
VIEW = ((0.0, 50.0), (-1.2, 8.0))  # Fig. 9 panels: the injury and downstream, near the wall


def probe_series(run):
    t, rows = [], []
    for k in range(len(run)):
        f = run.frame(k)
        x, z = f.positions[:, 0], f.positions[:, 1]
        m = ((f.kinds == 0) & (x >= PROBE[0][0]) & (x <= PROBE[0][1]) & (z >= PROBE[1][0]) &
             (z < PROBE[1][1]))
        if not m.any():
            raise SystemExit(f"frame {k}: no fluid particle in the probe {PROBE}")
        t.append(f.time)
        rows.append([float(np.mean(f.species[s][m])) for s, _ in SHOWN])
    return np.array(t), np.array(rows)


def features(t, y):
    iia, ia, at, apc = y.T
    k = int(np.argmax(iia))
    lines = [
        f"thrombin: {iia[0]:.4g} at t = 0, max {iia[k]:.4g} at t = {t[k]:g}, {iia[-1]:.4g} at "
        f"t = {t[-1]:g} (burst then drop: {'yes' if 0 < k < len(t) - 1 and iia[-1] < iia[k] else 'no'})",
        f"fibrin: {ia[0]:.4g} -> {ia[-1]:.4g}; last 20 % of the run changes by "
        f"{(ia[-1] - ia[int(0.8 * (len(t) - 1))]) / max(ia[-1], 1e-300):+.1%}",
        f"antithrombin: {at[0]:.5g} -> min {at.min():.5g} -> {at[-1]:.5g}",
        f"APC: {apc[0]:.4g} -> max {apc.max():.4g} -> {apc[-1]:.4g}",
    ]
    return "\n".join(lines)


def read_reference(path):
    lines = [ln for ln in Path(path).read_text().splitlines() if not ln.startswith("#")]
    names = lines[0].split(",")
    data = np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]])
    col = {n: data[:, k] for k, n in enumerate(names)}
    return col["t"], {s: col[s] for s, _ in SHOWN}


def plot_series(t, y, path, title, references=()):
    fig, axes = plt.subplots(2, 2, figsize=(9, 6), sharex=True)
    for ax, (s, label), col in zip(axes.flat, SHOWN, y.T):
        ax.plot(t, col, "o", ms=3, label="sadr (particles)")
        for name, (tr, cols) in references:
            ax.plot(tr, cols[s], "-", lw=1.2, label=name)
        if references:
            ax.legend(fontsize=7)
        ax.set_title(f"{label} ({s})")
        ax.set_ylabel("nM")
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("t [tDPD units; 432.9 = 1 min of accelerated chemistry]")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_fibrin(run, path, title, nframes=6):
    idx = np.unique(np.linspace(0, len(run) - 1, nframes).round().astype(int))
    fig, axes = plt.subplots(len(idx), 1, figsize=(9, 1.3 * len(idx)), sharex=True)
    axes = np.atleast_1d(axes)
    xe = np.arange(0.0, 100.0 + 1e-9, 1.0)
    ze = np.arange(-0.5, 20.5 + 1e-9, 1.0)  # never empty on the 0.625 and 1.0 lattices
    vmax = None
    fields = []
    for k in idx:
        f = run.frame(int(k))
        m = f.kinds == 0
        x, z = f.positions[m, 0], f.positions[m, 1]
        c = f.species["Ia"][m]
        s, _, _ = np.histogram2d(x, z, bins=(xe, ze), weights=c)
        n, _, _ = np.histogram2d(x, z, bins=(xe, ze))
        fields.append((f.time, np.where(n > 0, s / np.maximum(n, 1), np.nan)))
        vmax = max(vmax or 0.0, float(np.nanmax(fields[-1][1])))
    xc, zc = 0.5 * (xe[1:] + xe[:-1]), 0.5 * (ze[1:] + ze[:-1])
    for ax, (t, field) in zip(axes, fields):
        im = ax.pcolormesh(xe, ze, field.T, vmin=0, vmax=vmax, cmap="viridis", shading="flat")
        if np.nanmax(field) >= THRESHOLD:
            ax.contour(xc, zc, field.T, levels=[THRESHOLD], colors="w", linewidths=1)
        ax.plot([10, 20], [-0.9, -0.9], "r", lw=3)  # the injury, below the first fluid row
        ax.set_xlim(*VIEW[0])
        ax.set_ylim(*VIEW[1])
        ax.set_ylabel("y (height)")
        ax.text(1, 5.5, f"t = {t:g}", color="k", bbox={"facecolor": "w", "alpha": 0.7})
    axes[-1].set_xlabel("x (injury: red, 10 < x < 20)")
    fig.colorbar(im, ax=axes, label="fibrin Ia [nM] (3D: depth average)")
    fig.suptitle(title)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run")
    ap.add_argument("--prefix", default="docs/images/coagulation")
    ap.add_argument("--title", default="")
    ap.add_argument("--reference", action="append", default=[],
                    help="LABEL=CSV of channel_reference.py, drawn as a line (repeatable)")
    args = ap.parse_args()
    refs = []
    for item in args.reference:
        label, _, path = item.rpartition("=")
        refs.append((label or path, read_reference(path)))
    run = sadr.Run(args.run)
    t, y = probe_series(run)
    title = args.title or f"{run.path.name}: injury centre (14 <= x <= 16, y < 0.7)"
    plot_series(t, y, f"{args.prefix}_timeseries.png", title, refs)
    plot_fibrin(run, f"{args.prefix}_fibrin.png", f"{args.title or run.path.name}: fibrin (Fig. 9)")
    print(features(t, y))
    print(f"wrote {args.prefix}_timeseries.png, {args.prefix}_fibrin.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
