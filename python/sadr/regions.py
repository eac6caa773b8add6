# SPDX-License-Identifier: MIT
"""Regions that select particles of a frame: a box, a disk (a cylinder or
sphere in 3D), particle kinds, and their intersections (``a & b``) and
unions (``a | b``). A region is evaluated on each frame's own positions, so
it follows moving particles.

Boundaries are inclusive within the tolerance of the scene loader
(``Region::contains`` and ``SceneContext::tolerance`` in orchestrator/scene):
an absolute tolerance of 1e-9 times the largest box length, so that a
particle on a face is inside in Python as in the product. The box is the
run's (``Frame.box_extent``, set by sadr.Run from its scene); a frame read on
its own uses the extent of its particles instead.
"""
from __future__ import annotations

import numpy as np

from .frames import Frame, _kind_code

RELATIVE_TOLERANCE = 1e-9
"""Region boundaries are inclusive within this fraction of the largest box length."""


def boundary_tolerance(extent: float) -> float:
    """The absolute boundary tolerance [length] for a box whose largest length is ``extent``."""
    return RELATIVE_TOLERANCE * max(float(extent), 1e-300)


def frame_tolerance(frame: Frame) -> float:
    """The boundary tolerance for ``frame``: from its run's box when known
    (``frame.box_extent``), else from the extent of its particles."""
    extent = getattr(frame, "box_extent", None)
    if extent is None:
        p = frame.positions
        extent = float(np.max(np.ptp(p, axis=0))) if len(p) else 0.0
    return boundary_tolerance(extent)


class Region:
    """Base class: ``mask(frame)`` is a boolean array over the frame's particles."""

    def mask(self, frame: Frame) -> np.ndarray:  # pragma: no cover - interface
        raise NotImplementedError

    def __and__(self, other: Region) -> Region:
        return _Combined(self, other, np.logical_and, "&")

    def __or__(self, other: Region) -> Region:
        return _Combined(self, other, np.logical_or, "|")


class _Combined(Region):
    def __init__(self, a, b, op, symbol):
        self.a, self.b, self.op, self.symbol = a, b, op, symbol

    def mask(self, frame: Frame) -> np.ndarray:
        return self.op(self.a.mask(frame), self.b.mask(frame))

    def __repr__(self):
        return f"({self.a!r} {self.symbol} {self.b!r})"


class Everything(Region):
    """All particles."""

    def mask(self, frame: Frame) -> np.ndarray:
        return np.ones(len(frame), dtype=bool)

    def __repr__(self):
        return "Everything()"


class Box(Region):
    """lower <= x <= upper on each given axis (1 to 3 values; missing axes are unbounded)."""

    def __init__(self, lower, upper):
        self.lower = np.asarray(lower, dtype=float)
        self.upper = np.asarray(upper, dtype=float)
        if self.lower.shape != self.upper.shape or not 1 <= self.lower.size <= 3:
            raise ValueError(f"Box: lower {lower} and upper {upper} need the same 1 to 3 values")
        if np.any(self.lower > self.upper):
            raise ValueError(f"Box: lower {lower} > upper {upper} on some axis")

    def mask(self, frame: Frame) -> np.ndarray:
        d = self.lower.size
        tol = frame_tolerance(frame)
        p = frame.positions[:, :d]
        return np.all((p >= self.lower - tol) & (p <= self.upper + tol), axis=1)

    def __repr__(self):
        return f"Box({self.lower.tolist()}, {self.upper.tolist()})"


class Disk(Region):
    """|x - center| <= radius over the axes of ``center`` (2 values: a disk in
    the x-y plane, a cylinder along z in 3D; 3 values: a sphere)."""

    def __init__(self, center, radius):
        self.center = np.asarray(center, dtype=float)
        self.radius = float(radius)
        if not 1 <= self.center.size <= 3 or self.radius < 0:
            raise ValueError(f"Disk: center {center} (1-3 values) and radius {radius} >= 0")

    def mask(self, frame: Frame) -> np.ndarray:
        d = self.center.size
        r = np.sqrt(np.sum((frame.positions[:, :d] - self.center) ** 2, axis=1))
        return r <= self.radius + frame_tolerance(frame)

    def __repr__(self):
        return f"Disk({self.center.tolist()}, {self.radius})"


class Kinds(Region):
    """Particles of the given kinds: ``Kinds('fluid')``, ``Kinds('wall', 'inlet')``."""

    def __init__(self, *kinds):
        if not kinds:
            raise ValueError("Kinds: name at least one kind (fluid, wall, inlet, outlet)")
        self.codes = [_kind_code(k) for k in kinds]
        self.names = kinds

    def mask(self, frame: Frame) -> np.ndarray:
        return np.isin(frame.kinds, self.codes)

    def __repr__(self):
        return "Kinds(" + ", ".join(repr(k) for k in self.names) + ")"


def as_region(region: Region | str | None) -> Region:
    """None -> Everything(); a kind name -> Kinds(name); a Region unchanged."""
    if region is None:
        return Everything()
    if isinstance(region, str):
        return Kinds(region)
    if isinstance(region, Region):
        return region
    raise TypeError(f"not a region: {region!r} (use sadr.Box, sadr.Disk, sadr.Kinds or a kind name)")
