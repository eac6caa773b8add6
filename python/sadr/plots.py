# SPDX-License-Identifier: MIT
"""One-line plots returning a matplotlib Figure (the Agg backend unless one was
chosen with MPLBACKEND or by importing pyplot first, so they work without a display):

    sadr.plot_particles(frame, color="T")          # particles coloured by a field
    sadr.plot_profile(frame, "vx", [0.5, 0], [0.5, 1])
    sadr.plot_series(ensemble.band("T"))           # mean and confidence band
    sadr.plot_sweep(table, "diffusivity", "T")     # observable against a parameter
    sadr.plot_overview(run)                        # one figure of a run (overview)

Each takes ``ax=`` to draw into existing axes and returns that axes' figure.
"""
from __future__ import annotations

import os
import sys

import matplotlib

# Agg (no display needed) unless the user chose a backend: MPLBACKEND (Jupyter
# sets it to its inline backend) or pyplot imported before this module.
if "MPLBACKEND" not in os.environ and "matplotlib.pyplot" not in sys.modules:
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from pathlib import Path  # noqa: E402

from .frames import KIND_NAMES, Frame  # noqa: E402
from .regions import as_region  # noqa: E402

_MARKERS = {0: "o", 1: "s", 2: ">", 3: "<"}


def _axes(ax, figsize=(6, 4)):
    if ax is not None:
        return ax.figure, ax
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    return fig, ax


def plot_particles(frame: Frame, color: str = "speed", *, region=None, axes=(0, 1),
                   size: float | None = None, cmap="viridis", walls: bool = True, arrows: bool = False,
                   ax=None, title: str | None = None) -> Figure:
    """Particles of ``frame`` in the plane of ``axes`` (default x-y), coloured by
    ``color`` (a species, 'speed', 'density', any Frame.field name). Wall
    particles are drawn grey and uncoloured when ``walls``; ``arrows`` adds the
    velocity field. Returns the Figure."""
    fig, ax = _axes(ax)
    m = as_region(region).mask(frame)
    wall = frame.kinds == KIND_NAMES.index("wall")
    pos = frame.positions[:, list(axes)]
    values = frame.field(color)
    s = size if size is not None else max(2.0, 4000.0 / max(1, len(frame)))
    if walls and np.any(m & wall):
        ax.scatter(*pos[m & wall].T, s=s, c="0.75", marker="s", linewidths=0, label="wall")
    shown = m & ~wall if walls else m
    sc = ax.scatter(*pos[shown].T, s=s, c=values[shown], cmap=cmap, linewidths=0)
    fig.colorbar(sc, ax=ax, label=color)
    if arrows:
        v = frame.velocity[:, list(axes)]
        ax.quiver(*pos[shown].T, *v[shown].T, color="k", alpha=0.6, width=0.002)
    ax.set_aspect("equal")
    ax.set_xlabel("xyz"[axes[0]])
    ax.set_ylabel("xyz"[axes[1]])
    ax.set_title(title if title is not None else f"{color} at t = {frame.time:g}")
    return fig


def profile(frame: Frame, field: str, start, end, *, width: float | None = None, bins: int = 20,
            region=None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mean of ``field`` along the segment start -> end: particles within
    ``width`` of the segment (default: 1/bins of its length) are binned by their
    projection onto it. Returns (s, mean, count): bin centres (distance from
    start), the bin means (NaN where empty) and counts."""
    start = np.asarray(start, dtype=float)
    end = np.asarray(end, dtype=float)
    d = start.size
    seg = end - start
    length = float(np.linalg.norm(seg))
    if length == 0:
        raise ValueError("profile: start and end are the same point")
    width = length / bins if width is None else float(width)
    p = frame.positions[:, :d] - start
    s = p @ seg / length
    dist = np.linalg.norm(p - np.outer(s, seg / length), axis=1)
    m = as_region(region).mask(frame) & (s >= 0) & (s <= length) & (dist <= width)
    edges = np.linspace(0, length, bins + 1)
    idx = np.clip(np.digitize(s[m], edges) - 1, 0, bins - 1)
    values = frame.field(field)[m]
    count = np.bincount(idx, minlength=bins)
    total = np.bincount(idx, weights=values, minlength=bins)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.where(count > 0, total / np.maximum(count, 1), np.nan)
    return 0.5 * (edges[1:] + edges[:-1]), mean, count


def plot_profile(frame, field: str, start, end, *, width=None, bins: int = 20, region=None,
                 reference=None, reference_label="reference", ax=None, label=None) -> Figure:
    """Profile of ``field`` along start -> end (see :func:`profile`); ``reference``
    is an optional callable s -> value drawn as a dashed line. Returns the Figure."""
    fig, ax = _axes(ax)
    s, mean, _ = profile(frame, field, start, end, width=width, bins=bins, region=region)
    ax.plot(s, mean, "o-", ms=4, label=label or f"{field} (t = {frame.time:g})")
    if reference is not None:
        fine = np.linspace(s[0], s[-1], 200)
        ax.plot(fine, [reference(x) for x in fine], "k--", lw=1, label=reference_label)
    ax.set_xlabel(f"distance along {np.round(start, 3).tolist()} -> {np.round(end, 3).tolist()}")
    ax.set_ylabel(field)
    ax.legend()
    return fig


def plot_series(data, *, ax=None, label: str | None = None, ylabel: str | None = None,
                title: str | None = None) -> Figure:
    """Time series: a band DataFrame (Ensemble.band: mean with its lower/upper
    band shaded), or a DataFrame/Series of plain columns (Run.series,
    Ensemble.series), one line each. Returns the Figure."""
    fig, ax = _axes(ax)
    if hasattr(data, "columns") and {"mean", "lower", "upper"} <= set(data.columns):
        t = data.index.to_numpy()
        line, = ax.plot(t, data["mean"], label=label or "ensemble mean")
        n = int(data["n"].iloc[0]) if "n" in data else None
        ax.fill_between(t, data["lower"], data["upper"], color=line.get_color(), alpha=0.25,
                        label="confidence band" + (f" ({n} realizations)" if n else ""))
    else:
        frame = data.to_frame() if not hasattr(data, "columns") else data
        many = frame.shape[1] > 8
        for c in frame.columns:
            ax.plot(frame.index, frame[c], lw=0.8 if many else 1.5, alpha=0.5 if many else 1,
                    label=None if many else str(c))
    ax.set_xlabel("time")
    if ylabel:
        ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)
    if ax.get_legend_handles_labels()[0]:
        ax.legend()
    return fig


def sweep_summary(table, parameter: str, observable: str, *, time=None,
                  confidence: float = 0.95) -> pd.DataFrame:
    """Per value of ``parameter`` in a tidy table (Sweep.table): the mean over
    realizations of ``observable`` at ``time`` (default: the last time), the
    ``confidence`` interval mean -+ t(0.5 + confidence / 2, n - 1) sem (NaN for
    n = 1) and n. Returns a DataFrame with columns ``parameter``,
    '<observable>_mean', 'ci_lo', 'ci_hi', 'realizations', sorted by parameter."""
    from .series import t_quantile

    if time is None:
        time = table["time"].max()
    at = table[np.isclose(table["time"], time, rtol=0, atol=1e-12 * max(1.0, abs(time)))]
    if at.empty:
        raise ValueError(f"sweep_summary: no rows at time {time}")
    g = at.groupby(parameter)[observable]
    mean, std, n = g.mean(), g.std(ddof=1), g.count()
    t = np.array([t_quantile(0.5 + confidence / 2, k - 1) if k > 1 else np.nan for k in n])
    half = t * std.to_numpy() / np.sqrt(n.to_numpy())
    return pd.DataFrame({parameter: mean.index.to_numpy(dtype=float),
                         f"{observable}_mean": mean.to_numpy(),
                         "ci_lo": mean.to_numpy() - half, "ci_hi": mean.to_numpy() + half,
                         "realizations": n.to_numpy()})


def plot_sweep(table, parameter: str, observable: str, *, time=None, confidence: float = 0.95,
               ax=None) -> Figure:
    """A sweep observable against its parameter from a tidy table (columns
    ``parameter``, 'realization', 'time', ``observable``; Sweep.table): the mean
    over realizations at ``time`` (default: the last time) with its t band
    (sweep_summary). Returns the Figure."""
    fig, ax = _axes(ax)
    if time is None:
        time = table["time"].max()
    s = sweep_summary(table, parameter, observable, time=time, confidence=confidence)
    mean = s[f"{observable}_mean"].to_numpy()
    n = s["realizations"]
    ax.errorbar(s[parameter].to_numpy(), mean, yerr=s["ci_hi"].to_numpy() - mean, fmt="o-",
                capsize=3,
                label=f"mean, {confidence:.0%} band (n = {int(n.min())}..{int(n.max())})")
    ax.set_xlabel(parameter)
    ax.set_ylabel(f"{observable} at t = {time:g}")
    ax.legend()
    return fig


def overview(run, species: str | None = None) -> Figure:
    """A one-figure look at a run: ``species`` (default: the first) at the first
    and at the last frame, the speed at the last frame, and the x-velocity
    profile across the fluid at the last frame (2D/3D runs); for a 1D run, the
    species along x at both frames. Returns the Figure."""
    first, last = run.frame(0), run.frame(-1)
    species = species or next(iter(last.species), None)
    extent = np.ptp(last.positions, axis=0) if len(last) else np.zeros(3)
    name = run.manifest.get("scene_path", "")
    title = f"{Path(name).stem or run.path.name}: t = {first.time:g} -> {last.time:g}"
    if np.count_nonzero(extent > 0) < 2:
        fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
        for f in (first, last):
            order = np.argsort(f.positions[:, 0])
            ax.plot(f.positions[order, 0], f.field(species)[order], ".-", label=f"t = {f.time:g}")
        ax.set_xlabel("x")
        ax.set_ylabel(species)
        ax.legend()
        fig.suptitle(title)
        return fig
    fig, axes = plt.subplots(2, 2, figsize=(10, 8), layout="constrained")
    if species:
        plot_particles(first, color=species, ax=axes[0, 0])
        plot_particles(last, color=species, ax=axes[0, 1])
    plot_particles(last, color="speed", arrows=True, ax=axes[1, 0])
    fluid = last.kinds == KIND_NAMES.index("fluid")
    p = last.positions[fluid] if fluid.any() else last.positions
    lo, hi = p.min(axis=0), p.max(axis=0)
    mid = 0.5 * (lo[0] + hi[0])
    rows = max(2, int(round(np.sqrt(max(1, fluid.sum())))))
    plot_profile(last, "vx", [mid, lo[1]], [mid, hi[1]], width=0.5 * (hi[0] - lo[0]) + 1e-12,
                 bins=min(20, rows), region="fluid", ax=axes[1, 1])
    axes[1, 1].set_title(f"x-velocity across the fluid, mean over x (t = {last.time:g})")
    fig.suptitle(title)
    return fig


plot_overview = overview


def geometry_labels(particles: pd.DataFrame, color: str = "kind") -> np.ndarray:
    """The category each particle of `sadr geometry`'s table is drawn in:
    ``kind`` (fluid, wall, ...), ``regions`` (the smallest region holding it,
    so a membrane shows over its cell; ``all`` left out; in none: "KIND, no
    region") or a region's name (that region against the rest)."""
    n = len(particles)
    kinds = np.array([KIND_NAMES[k] if k < len(KIND_NAMES) else str(k)
                      for k in particles["kind"].to_numpy().astype(int)], dtype=object)
    if color == "kind":
        return kinds
    columns = [c for c in particles.columns if c.startswith("region_") and c != "region_all"]
    if color == "regions":
        labels = np.array([f"{k}, no region" for k in kinds], dtype=object)
        size = np.full(n, np.inf)
        for c in columns:
            member = particles[c].to_numpy() == 1
            count = member.sum()
            pick = member & (count < size)
            labels[pick] = c[len("region_"):]
            size[pick] = count
        return labels
    column = f"region_{color}"
    if column not in particles.columns:
        names = ", ".join(["kind", "regions"] + [c[len("region_"):] for c in columns])
        raise ValueError(f"color '{color}': allowed: {names}")
    member = particles[column].to_numpy() == 1
    return np.where(member, color, "other").astype(object)


def plot_geometry(particles, color: str = "kind", *, size: float | None = None,
                  title: str | None = None) -> Figure:
    """The particles `sadr geometry` made (a DataFrame of sadr.geometry.read_particles,
    a sadr.geometry.GeometryBuild, or a folder or particles.csv), one colour per
    category of ``color`` (geometry_labels: ``kind``, ``regions`` or a region's
    name). 2D: one scatter; 3D: three slices through the centre of the particles
    (x-y, x-z, y-z), each the particles within half a spacing of a lattice
    plane. Returns the Figure."""
    from .geometry import GeometryBuild, read_particles

    if isinstance(particles, GeometryBuild):
        particles = particles.particles
    elif not isinstance(particles, pd.DataFrame):
        particles = read_particles(particles)
    labels = geometry_labels(particles, color)
    pos = particles[["x", "y", "z"]].to_numpy()
    categories = list(dict.fromkeys(labels))
    palette = plt.get_cmap("tab10")
    three_d = len(pos) > 0 and np.ptp(pos[:, 2]) > 0
    if not three_d:
        fig, ax = plt.subplots(figsize=(7, 5), layout="constrained")
        panels = [(ax, (0, 1), np.ones(len(pos), dtype=bool), "")]
    else:
        fig, axes = plt.subplots(1, 3, figsize=(15, 5), layout="constrained")
        if "volume" in particles.columns and len(particles):
            dx = float(np.median(particles["volume"].to_numpy())) ** (1.0 / 3.0)
        else:
            dx = float(np.min(np.diff(np.unique(pos[:, 0])), initial=1.0))
        panels = []
        for ax, normal, plane in zip(axes, (2, 1, 0), ((0, 1), (0, 2), (1, 2))):
            coord = pos[:, normal]
            centre = 0.5 * (coord.min() + coord.max())
            at = coord[np.argmin(np.abs(coord - centre))]
            keep = np.abs(coord - at) < 0.5 * dx
            panels.append((ax, plane, keep, f"{'xyz'[normal]} = {at:.4g}"))
    for ax, plane, keep, where in panels:
        s = size if size is not None else max(2.0, 6000.0 / max(1, keep.sum()))
        for k, name in enumerate(categories):
            pick = keep & (labels == name)
            if pick.any():
                ax.scatter(pos[pick, plane[0]], pos[pick, plane[1]], s=s, color=palette(k % 10),
                           linewidths=0, label=f"{name} ({int(pick.sum())})")
        ax.set_aspect("equal")
        ax.set_xlabel("xyz"[plane[0]])
        ax.set_ylabel("xyz"[plane[1]])
        ax.set_title(f"slice {where}" if where else title or f"{len(pos)} particles by {color}")
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=3, fontsize="small", markerscale=2)
    if three_d:
        fig.suptitle(title if title is not None else f"{len(pos)} particles by {color}")
    return fig
