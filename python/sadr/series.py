# SPDX-License-Identifier: MIT
"""Per-frame observables over a region, and ensemble confidence bands.

``observe(frame, species, region, stat)`` reduces one frame to a number:

* ``total``: sum over the region's particles (copy numbers: molecules);
* ``mean``: arithmetic mean over the region's particles (per particle);
* ``concentration``: total / total voxel volume (sum of m_i / rho_i).

An empty region gives NaN for mean and concentration (0 for total) — never a
silent 0 for an average.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .frames import Frame
from .regions import Region, as_region

if TYPE_CHECKING:
    import pandas as pd

STATS = ("total", "mean", "concentration")


def observe(frame: Frame, species: str, region: Region | str | None = None,
            stat: str = "total") -> float:
    """One number for one frame (see module doc)."""
    if stat not in STATS:
        raise ValueError(f"stat '{stat}' (allowed: {', '.join(STATS)})")
    m = as_region(region).mask(frame)
    values = frame.field(species)[m]
    if stat == "total":
        return float(np.sum(values))
    if not m.any():
        return float("nan")
    if stat == "mean":
        return float(np.mean(values))
    return float(np.sum(values) / np.sum(frame.volume[m]))


def t_quantile(p: float, dof: int) -> float:
    """The Student t quantile t_{p, dof} (scipy.stats.t.ppf), the one quantile
    of every band and interval of this package. scipy is required: without
    it this raises ImportError (no other distribution stands in)."""
    try:
        from scipy import stats
    except ImportError as e:
        raise ImportError("sadr: confidence bands need scipy's Student t quantile (scipy.stats.t); "
                          "install python3-scipy (Debian) or scipy") from e
    return float(stats.t.ppf(p, dof))


def band(values: np.ndarray, times, confidence: float = 0.95) -> pd.DataFrame:
    """Confidence band of the ensemble mean from a (realizations x times) array.

    Returns a pandas DataFrame indexed by time with columns n, mean, std
    (unbiased), sem, lower, upper (mean -+ t_{(1+c)/2, n-1} sem)."""
    import pandas as pd

    values = np.asarray(values, dtype=float)
    if values.ndim != 2:
        raise ValueError("band: values must be (realizations, times)")
    n = values.shape[0]
    mean = values.mean(axis=0)
    std = values.std(axis=0, ddof=1) if n > 1 else np.full(values.shape[1], math.nan)
    sem = std / math.sqrt(n)
    half = t_quantile(0.5 + confidence / 2, n - 1) * sem if n > 1 else sem
    return pd.DataFrame({"n": n, "mean": mean, "std": std, "sem": sem,
                         "lower": mean - half, "upper": mean + half},
                        index=pd.Index(np.asarray(times, dtype=float), name="time"))
