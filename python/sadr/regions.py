# SPDX-License-Identifier: MIT
"""Regions that select particles of a frame: a box, a disk (a cylinder or
sphere in 3D), particle kinds, and their intersections (``a & b``) and
unions (``a | b``). A region is evaluated on each frame's own positions, so
it follows moving particles."""
from __future__ import annotations

import numpy as np

from .frames import Frame, _kind_code


class Region:
    """Base class: ``mask(frame)`` is a boolean array over the frame's particles."""

    def mask(self, frame: Frame) -> np.ndarray:  # pragma: no cover - interface
        raise NotImplementedError

    def __and__(self, other):
        return _Combined(self, other, np.logical_and, "&")

    def __or__(self, other):
        return _Combined(self, other, np.logical_or, "|")


class _Combined(Region):
    def __init__(self, a, b, op, symbol):
        self.a, self.b, self.op, self.symbol = a, b, op, symbol

    def mask(self, frame):
        return self.op(self.a.mask(frame), self.b.mask(frame))

    def __repr__(self):
        return f"({self.a!r} {self.symbol} {self.b!r})"


class Everything(Region):
    """All particles."""

    def mask(self, frame):
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

    def mask(self, frame):
        d = self.lower.size
        p = frame.positions[:, :d]
        return np.all((p >= self.lower) & (p <= self.upper), axis=1)

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

    def mask(self, frame):
        d = self.center.size
        r2 = np.sum((frame.positions[:, :d] - self.center) ** 2, axis=1)
        return r2 <= self.radius**2

    def __repr__(self):
        return f"Disk({self.center.tolist()}, {self.radius})"


class Kinds(Region):
    """Particles of the given kinds: ``Kinds('fluid')``, ``Kinds('wall', 'inlet')``."""

    def __init__(self, *kinds):
        if not kinds:
            raise ValueError("Kinds: name at least one kind (fluid, wall, inlet, outlet)")
        self.codes = [_kind_code(k) for k in kinds]
        self.names = kinds

    def mask(self, frame):
        return np.isin(frame.kinds, self.codes)

    def __repr__(self):
        return "Kinds(" + ", ".join(repr(k) for k in self.names) + ")"


def as_region(region) -> Region:
    """None -> Everything(); a kind name -> Kinds(name); a Region unchanged."""
    if region is None:
        return Everything()
    if isinstance(region, str):
        return Kinds(region)
    if isinstance(region, Region):
        return region
    raise TypeError(f"not a region: {region!r} (use sadr.Box, sadr.Disk, sadr.Kinds or a kind name)")
