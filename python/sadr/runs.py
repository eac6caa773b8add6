# SPDX-License-Identifier: MIT
"""Output directories of `sadr run`: one run (``run.json`` + ``frames/``) and
an ensemble (``realization_NNNN/`` folders + ``ensemble/``)."""
from __future__ import annotations

import json
import os
import re
from collections.abc import Iterator
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import yaml

from .frames import Frame, read_ensemble_frame, read_frame, read_pvd
from .series import band, observe

if TYPE_CHECKING:
    import pandas as pd

    from .sweeps import Sweep

_FRAME_NAME = re.compile(r"frame_(\d{6})\.(csv|vtu|vtp)$")


class Run:
    """One realization's output directory (what `sadr run SCENE -o DIR` writes)."""

    def __init__(self, path):
        self.path = Path(path)
        manifest = self.path / "run.json"
        if not manifest.is_file():
            raise FileNotFoundError(f"{self.path}: no run.json (not the output directory of a sadr run)")
        with open(manifest, encoding="utf-8") as f:
            self.manifest = json.load(f)
        if self.manifest.get("format") != "sadr-run":
            raise ValueError(f"{manifest}: format '{self.manifest.get('format')}', expected 'sadr-run'")

    def __repr__(self):
        return f"sadr.Run('{self.path}', {len(self)} frames, status {self.status})"

    @property
    def status(self) -> str:
        return self.manifest.get("status", "")

    @property
    def timings(self) -> dict:
        """Wall seconds per stage from run.json (``timings_s``)."""
        return dict(self.manifest.get("timings_s", {}))

    def body_forces(self, body: str | None = None) -> pd.DataFrame:
        """The force and torque the fluid exerts on each body (``body_forces.csv``, written
        when the scene lists ``fluid.body_forces``): columns t, dt, body, Fx, Fy, Fz, Tx, Ty,
        Tz, one row per fluid stage and body, in file order; ``body`` keeps one body's rows."""
        import pandas as pd

        path = self.path / "body_forces.csv"
        if not path.is_file():
            raise FileNotFoundError(f"{path}: no such file (the scene lists no fluid.body_forces)")
        table = pd.read_csv(path, dtype={"body": str}, float_precision="round_trip")
        expected = ["t", "dt", "body", "Fx", "Fy", "Fz", "Tx", "Ty", "Tz"]
        if list(table.columns) != expected:
            raise ValueError(f"{path}: columns {list(table.columns)}, expected {expected}")
        if body is None:
            return table
        names = list(dict.fromkeys(table["body"]))
        if body not in names:
            raise KeyError(f"{path}: no body '{body}' (bodies: {', '.join(names)})")
        return table[table["body"] == body].reset_index(drop=True)

    @cached_property
    def files(self) -> list:
        """Per output index, a dict {'csv'|'vtu'|'vtp': Path}, in index order."""
        names = self.manifest.get("frames")
        if names is None:  # older manifests: the folder itself
            names = [f"frames/{p.name}" for p in (self.path / "frames").glob("frame_*")]
        by_index = {}
        for name in names:
            m = _FRAME_NAME.search(name)
            if m:
                by_index.setdefault(int(m.group(1)), {})[m.group(2)] = self.path / name
        return [by_index[k] for k in sorted(by_index)]

    @cached_property
    def indices(self) -> list:
        """The output indices NNNNNN of the frames, in order."""
        return [int(_FRAME_NAME.search(next(iter(f.values())).name).group(1)) for f in self.files]

    @cached_property
    def times(self) -> np.ndarray:
        """Frame times, exact (from the .pvd collection, else the CSV frames)."""
        pvds = sorted(self.path.glob("*.pvd"))
        if pvds:
            t = {p.name: time for time, p in read_pvd(pvds[0])}
            if all(any(f.name in t for f in files.values()) for files in self.files):
                return np.array([next(t[f.name] for f in files.values() if f.name in t)
                                 for files in self.files])
        return np.array([self.frame(k).time for k in range(len(self))])

    def __len__(self):
        return len(self.files)

    def frame(self, k: int, format: str | None = None) -> Frame:
        """Frame number k (0-based, negative from the end) as a sadr.Frame,
        from ``format`` ('csv', 'vtu', 'vtp'; default: csv if written, else VTK)."""
        files = self.files[k]
        if format is None:
            format = next(f for f in ("csv", "vtu", "vtp") if f in files)
        if format not in files:
            raise KeyError(f"{self.path}: frame {k} has no .{format} file (written: {', '.join(files)})")
        frame = read_frame(files[format])
        frame.box_extent = self.box_extent
        return frame

    @cached_property
    def box_extent(self) -> float | None:
        """The largest box length of the run's scene (run.json's scene_path,
        with its overrides), which sets the boundary tolerance of regions
        (sadr.regions); None when the scene file is not found."""
        from .paths import PathError, get_path, load_yaml, set_path

        name = self.manifest.get("scene_path")
        if not name:
            return None
        candidates = [Path(name)] if Path(name).is_absolute() else [Path(name), self.path.parent / name]
        for path in candidates:
            if not path.is_file():
                continue
            try:
                with open(path, encoding="utf-8") as f:
                    data = load_yaml(f)
                for text in self.manifest.get("overrides", []):
                    key, _, value = text.partition("=")
                    if key.startswith("box"):
                        set_path(data, key, load_yaml(value))
                lower, upper = get_path(data, "box.lower"), get_path(data, "box.upper")
                return max(float(u) - float(lo) for lo, u in zip(lower, upper))
            except (OSError, ValueError, TypeError, PathError, yaml.YAMLError):
                return None
        return None

    def frames(self, format: str | None = None) -> Iterator[Frame]:
        """All frames, in order (a generator)."""
        for k in range(len(self)):
            yield self.frame(k, format)

    @cached_property
    def species(self) -> list:
        return list(self.frame(0).species) if len(self) else []

    def series(self, species: str | list[str] | None = None, region=None,
               stat: str = "total") -> pd.DataFrame:
        """pandas DataFrame indexed by time, one column per species (default:
        all): the frame's ``stat`` ('total', 'mean', 'concentration') over
        ``region`` (a sadr.Box/Disk/Kinds, a kind name, or None for all)."""
        import pandas as pd

        names = self._names(species)
        rows = [[observe(f, s, region, stat) for s in names] for f in self.frames()]
        return pd.DataFrame(rows, columns=names, index=pd.Index(self.times, name="time"))

    def _names(self, species):
        if species is None:
            return self.species
        return [species] if isinstance(species, str) else list(species)


class Ensemble:
    """`sadr run SCENE -r R -o DIR` (or `--realization i` tasks + `sadr ensemble DIR`)."""

    def __init__(self, path):
        self.path = Path(path)
        dirs = sorted(p for p in self.path.glob("realization_*") if p.is_dir())
        if not dirs:
            raise FileNotFoundError(f"{self.path}: no realization_NNNN/ folders (not an ensemble)")
        self.runs = [Run(p) for p in dirs]
        self.realizations = [int(p.name.split("_")[1]) for p in dirs]

    def __repr__(self):
        return f"sadr.Ensemble('{self.path}', {len(self.runs)} realizations, {len(self.times)} frames)"

    def __len__(self):
        return len(self.runs)

    def __getitem__(self, i) -> Run:
        return self.runs[i]

    @cached_property
    def times(self) -> np.ndarray:
        """Frame times, common to all realizations (checked)."""
        t = self.runs[0].times
        for r in self.runs[1:]:
            if not np.array_equal(r.times, t):
                raise ValueError(f"{r.path}: frame times differ from {self.runs[0].path} "
                                 f"({len(r.times)} vs {len(t)} frames; an unfinished realization?)")
        return t

    @property
    def species(self) -> list:
        return self.runs[0].species

    def values(self, species: str, region=None, stat: str = "total") -> np.ndarray:
        """(realizations x frames) array of ``stat`` of ``species`` over ``region``."""
        self.times  # noqa: B018 - checks that the realizations agree
        return np.array([[observe(f, species, region, stat) for f in r.frames()] for r in self.runs])

    def series(self, species: str, region=None, stat: str = "total") -> pd.DataFrame:
        """pandas DataFrame indexed by time, one column per realization."""
        import pandas as pd

        return pd.DataFrame(self.values(species, region, stat).T, columns=self.realizations,
                            index=pd.Index(self.times, name="time"))

    def band(self, species: str, region=None, stat: str = "total",
             confidence: float = 0.95) -> pd.DataFrame:
        """Ensemble mean of the observable with its ``confidence`` band (Student t
        over the realizations): DataFrame indexed by time, columns n, mean, std,
        sem, lower, upper."""
        return band(self.values(species, region, stat), self.times, confidence)

    def mean_frame(self, k: int) -> dict:
        """The per-particle ensemble statistics sadr wrote for frame k
        (``ensemble/frame_NNNNNN.csv``), as a dict of numpy arrays over its N
        particles (in the file's order, by id):

        * ``'time'``: the frame time (a float);
        * ``'ids'``: (N,) uint64 particle ids;
        * ``'realizations'``: (N,) how many realizations each row combines;
        * ``'positions'``: (N, 3) float64, realization 0's positions at that
          frame (particles that move differ between realizations; these are
          where to draw the statistics, as the sweep aggregates do);
        * ``'kinds'``: (N,) uint8, realization 0's kinds;
        * one entry per species: a tuple (mean, variance) of (N,) arrays
          (unbiased variance over the realizations)."""
        index = self.runs[0].indices[k]
        path = self.path / "ensemble" / f"frame_{index:06d}.csv"
        if not path.is_file():
            raise FileNotFoundError(f"{path}: missing (run `sadr ensemble {self.path}` to combine)")
        time, ids, count, stats = read_ensemble_frame(path)
        first = self.runs[0].frame(k)
        order = np.argsort(first.ids, kind="stable")
        at = order[np.clip(np.searchsorted(first.ids, ids, sorter=order), 0, max(len(order) - 1, 0))]
        if not np.array_equal(first.ids[at], ids):
            raise ValueError(f"{path}: particle ids differ from {first.path}")
        return {"time": time, "ids": ids, "realizations": count, "positions": first.positions[at],
                "kinds": first.kinds[at], **stats}


def open_output(path: str | os.PathLike) -> Run | Ensemble | Sweep:
    """A sadr.Run, sadr.Ensemble or sadr.Sweep for an output directory, by its layout."""
    path = Path(path)
    from .sweeps import Sweep, is_sweep

    if is_sweep(path):
        return Sweep(path)
    if (path / "run.json").is_file():
        return Run(path)
    if any(path.glob("realization_*")):
        return Ensemble(path)
    raise FileNotFoundError(f"{path}: neither a run (run.json), an ensemble (realization_NNNN/) "
                            "nor a sweep (sweep.json)")
