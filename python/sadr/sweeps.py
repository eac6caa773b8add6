# SPDX-License-Identifier: MIT
"""Sweep directories of `sadr sweep` (layout: docs/sweeps.md): the manifest,
the points and their parameter values, the runs, one tidy pandas table of
(point parameters, realization, time, observable), and xarray datasets of
the per-point aggregate fields."""
from __future__ import annotations

import json
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import yaml

from .frames import read_columns
from .runs import Run
from .series import observe

if TYPE_CHECKING:
    import pandas as pd
    import xarray as xr


def is_sweep(path) -> bool:
    return (Path(path) / "sweep.json").is_file()


def _value(text):
    """A parameter value as the sweep file wrote it (YAML scalar): 0.1 -> 0.1."""
    try:
        return yaml.safe_load(text) if isinstance(text, str) else text
    except yaml.YAMLError:
        return text


class Sweep:
    """`sadr sweep` output directory (``sweep.json``, ``runs/``, ``points/``)."""

    def __init__(self, path):
        self.path = Path(path)
        manifest = self.path / "sweep.json"
        if not manifest.is_file():
            raise FileNotFoundError(f"{self.path}: no sweep.json (not a sadr sweep directory)")
        with open(manifest, encoding="utf-8") as f:
            self.manifest = json.load(f)
        if self.manifest.get("format") != "sadr-sweep":
            raise ValueError(f"{manifest}: format '{self.manifest.get('format')}', expected 'sadr-sweep'")

    def __repr__(self):
        return (f"sadr.Sweep('{self.path}', {len(self.manifest['points'])} points x "
                f"{self.manifest.get('realizations', 1)} realizations, parameters {self.parameters})")

    @property
    def parameters(self) -> list:
        """The swept paths (``--set`` syntax), in the sweep file's order."""
        return list(self.manifest.get("parameters", []))

    @cached_property
    def points(self) -> pd.DataFrame:
        """pandas DataFrame indexed by point: one column per parameter (values
        parsed as YAML scalars), plus seed, aggregate state and directory."""
        import pandas as pd

        aggregates = self.manifest.get("aggregates", {})
        rows = []
        for p in self.manifest["points"]:
            row = {k: _value(p["values"].get(k)) for k in self.parameters}
            agg = aggregates.get(str(p["index"]), {})
            row.update(seed=p.get("seed"), state=agg.get("state", "pending"),
                       aggregate_dir=self.path / p["aggregate_dir"])
            rows.append((p["index"], row))
        return pd.DataFrame([r for _, r in rows], index=pd.Index([i for i, _ in rows], name="point"))

    @cached_property
    def runs(self) -> pd.DataFrame:
        """pandas DataFrame of the runs (index: array index): point,
        realization, state, exit_code, reason, dir."""
        import pandas as pd

        rows = [{k: r.get(k) for k in ("index", "point", "realization", "state", "exit_code",
                                       "reason", "kept")} | {"dir": self.path / r["dir"]}
                for r in self.manifest["runs"]]
        return pd.DataFrame(rows).set_index("index")

    def run(self, point: int, realization: int = 0) -> Run:
        """One run of the sweep as a sadr.Run (its frames may have been deleted
        by ``keep: aggregates`` for realizations >= 1)."""
        sel = self.runs[(self.runs["point"] == point) & (self.runs["realization"] == realization)]
        if sel.empty:
            raise KeyError(f"{self.path}: no run of point {point}, realization {realization}")
        return Run(sel["dir"].iloc[0])

    def table(self, region=None, stat: str = "total", species: str | list[str] | None = None) -> pd.DataFrame:
        """The tidy table: one row per (point, realization, frame), columns
        point, <parameters...>, realization, frame, time, then one column per
        species holding ``stat`` over ``region``.

        With no region and stat 'total' it comes from ``observables.csv``
        (works whatever ``keep`` deleted); otherwise from every run's frames,
        which needs ``keep: all`` (a missing frame raises, naming the run)."""
        import pandas as pd

        if region is None and stat == "total":
            obs = pd.read_csv(self.path / "observables.csv", float_precision="round_trip")
            wide = obs.pivot_table(index=["point", "realization", "frame", "time"], columns="species",
                                   values="total", aggfunc="first").reset_index()
            wide.columns.name = None
            names = [c for c in wide.columns if c not in ("point", "realization", "frame", "time")]
            if species is not None:
                names = [species] if isinstance(species, str) else list(species)
            out = wide[["point", "realization", "frame", "time"] + names]
        else:
            rows = []
            for _, r in self.runs.sort_index().iterrows():
                if r["state"] != "ok":
                    continue
                run = Run(r["dir"])
                if not run.files or any("csv" not in f and "vtu" not in f for f in run.files):
                    raise FileNotFoundError(f"{r['dir']}: frames missing (kept: {r['kept']}); "
                                            "regions need every run's frames: keep: all")
                names = run._names(species)
                for k, frame in enumerate(run.frames()):
                    rows.append({"point": r["point"], "realization": r["realization"], "frame": k,
                                 "time": frame.time,
                                 **{s: observe(frame, s, region, stat) for s in names}})
            out = pd.DataFrame(rows)
        params = self.points[self.parameters]
        out = out.merge(params, left_on="point", right_index=True, how="left")
        cols = ["point"] + self.parameters + ["realization", "frame", "time"]
        return out[cols + [c for c in out.columns if c not in cols]].reset_index(drop=True)

    def fields(self, point: int) -> xr.Dataset:
        """xarray Dataset of point ``point``'s aggregate frames
        (points/pPPPP/frame_NNNNNN.csv): dims (time, particle); coordinates
        id and realization 0's x, y, z; variables S_mean, S_var, S_sem,
        S_ci95_lo, S_ci95_hi per species (and vx/vy/vz/density when
        aggregated), with the point's parameter values as attributes."""
        import xarray as xr

        row = self.points.loc[point]
        if row["state"] != "done":
            raise ValueError(f"{self.path}: point {point} is not aggregated (state {row['state']})")
        files = sorted(Path(row["aggregate_dir"]).glob("frame_*.csv"))
        if not files:
            raise FileNotFoundError(f"{row['aggregate_dir']}: no frame_NNNNNN.csv")
        tables = [read_columns(f)[1] for f in files]
        names = [n for n in tables[0] if n not in ("time", "id", "realizations", "x", "y", "z")]
        ids = tables[0]["id"]
        for f, t in zip(files, tables):
            if not np.array_equal(t["id"], ids):
                raise ValueError(f"{f}: particle ids differ from {files[0]}")
        stack = {n: np.stack([t[n] for t in tables]) for n in names + ["x", "y", "z"]}
        times = np.array([t["time"][0] for t in tables])
        ds = xr.Dataset(
            {n: (("time", "particle"), stack[n]) for n in names},
            coords={"time": times, "id": ("particle", ids),
                    **{a: (("time", "particle"), stack[a]) for a in ("x", "y", "z")}},
            attrs={"point": int(point), "realizations": int(tables[0]["realizations"][0]),
                   **{k: row[k] for k in self.parameters}},
        )
        return ds

    def all_fields(self) -> xr.Dataset:
        """The aggregated points' fields along a ``point`` dimension, with each
        parameter as a coordinate on it (the particles must be the same)."""
        import xarray as xr

        done = [p for p in self.points.index if self.points.loc[p, "state"] == "done"]
        if not done:
            raise ValueError(f"{self.path}: no aggregated point")
        sets = [self.fields(p).drop_vars(["x", "y", "z"]) for p in done]
        ds = xr.concat(sets, dim="point", combine_attrs="drop")
        ds = ds.assign_coords(point=done)
        for k in self.parameters:
            ds = ds.assign_coords({k: ("point", [self.points.loc[p, k] for p in done])})
        return ds
