# SPDX-License-Identifier: MIT
"""One output frame of a sadr run as numpy arrays, read from CSV or VTK XML.

Readers for the three frame files `sadr run` writes (docs/scene-format.md,
"Frame files"), without VTK:

* ``frame_NNNNNN.csv``: header ``time,id,kind,x,y,z,vx,vy,vz,density,mass,
  <species...>``, every number the shortest decimal that reads back as the
  same double. ``numpy.loadtxt`` parses it exactly (so does pandas, but only
  with ``float_precision='round_trip'``; its default parser is off by up to
  ~1e-12 relative).
* ``frame_NNNNNN.vtu`` / ``.vtp``: VTK XML, arrays as raw appended binary
  (the default) or ASCII; byte order and header type as declared in the
  file. Other encodings (base64, compressed; not written by sadr) are refused
  with a message.

Every reader returns a :class:`Frame`; values are bit-identical to what the
run held, whichever file they come from (tests/python/test_frames.py).
"""
from __future__ import annotations

import dataclasses
import re
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import pandas as pd

KIND_NAMES = ("fluid", "wall", "inlet", "outlet")
"""Particle kinds by their number in the ``kind`` column / array."""

CSV_FIXED_COLUMNS = ("time", "id", "kind", "x", "y", "z", "vx", "vy", "vz", "density", "mass")


class FrameFormatError(ValueError):
    """A frame file that is not what sadr writes; the message names file and place."""


@dataclasses.dataclass
class Frame:
    """The particles at one output time (N particles)."""

    time: float
    ids: np.ndarray  # (N,) uint64, stable particle ids
    kinds: np.ndarray  # (N,) uint8: 0 fluid, 1 wall, 2 inlet, 3 outlet
    positions: np.ndarray  # (N, 3) float64; unused axes are 0
    velocity: np.ndarray  # (N, 3) float64
    density: np.ndarray  # (N,) float64
    mass: np.ndarray  # (N,) float64
    species: dict  # name -> (N,) float64 (copy numbers or concentrations)
    path: Path | None = None
    box_extent: float | None = None  # largest box length of the run's scene, when known (regions)

    def __len__(self) -> int:
        return len(self.ids)

    @property
    def speed(self) -> np.ndarray:
        """|velocity| per particle."""
        return np.sqrt(np.sum(self.velocity**2, axis=1))

    @property
    def volume(self) -> np.ndarray:
        """Voxel volume V_i = m_i / rho_i of each particle."""
        return self.mass / self.density

    def kind_mask(self, *names: str) -> np.ndarray:
        """Boolean mask of the particles of the given kinds ('fluid', 'wall', ...)."""
        codes = [_kind_code(n) for n in names]
        return np.isin(self.kinds, codes)

    def field(self, name: str) -> np.ndarray:
        """A per-particle array by name: a species, 'speed', 'density', 'mass',
        'volume', 'kind', 'id', 'x'/'y'/'z' or 'vx'/'vy'/'vz'."""
        if name in self.species:
            return self.species[name]
        axes = {"x": 0, "y": 1, "z": 2}
        if name in axes:
            return self.positions[:, axes[name]]
        if len(name) == 2 and name[0] == "v" and name[1] in axes:
            return self.velocity[:, axes[name[1]]]
        simple = {"speed": self.speed, "density": self.density, "mass": self.mass,
                  "volume": self.volume, "kind": self.kinds, "id": self.ids}
        if name in simple:
            return simple[name]
        raise KeyError(f"no field '{name}' in frame (species: {', '.join(self.species) or 'none'}; "
                       "also speed, density, mass, volume, kind, id, x, y, z, vx, vy, vz)")

    def to_pandas(self) -> pd.DataFrame:
        """The frame as a pandas DataFrame with the CSV frame's columns."""
        import pandas as pd

        cols = {"time": np.full(len(self), self.time), "id": self.ids, "kind": self.kinds}
        for a, name in enumerate("xyz"):
            cols[name] = self.positions[:, a]
        for a, name in enumerate(("vx", "vy", "vz")):
            cols[name] = self.velocity[:, a]
        cols["density"] = self.density
        cols["mass"] = self.mass
        cols.update(self.species)
        return pd.DataFrame(cols)


def _kind_code(name) -> int:
    if isinstance(name, (int, np.integer)):
        return int(name)
    try:
        return KIND_NAMES.index(name)
    except ValueError:
        raise ValueError(f"unknown particle kind '{name}' (allowed: {', '.join(KIND_NAMES)})") from None


def read_columns(path, integer_columns=("id", "realizations")) -> tuple:
    """A sadr CSV (frame, ensemble or sweep aggregate) as (header, {column: array}):
    float64 columns parsed exactly by numpy, ``integer_columns`` as integers
    (id uint64, kind uint8, realizations int64; frames pass ("id", "kind"))."""
    path = Path(path)
    with open(path, encoding="ascii") as f:
        header = f.readline().rstrip("\n").split(",")
    types = {"id": np.uint64, "kind": np.uint8, "realizations": np.int64}
    dtype = [(f"c{i}", types[n] if n in integer_columns else np.float64) for i, n in enumerate(header)]
    try:
        rows = np.loadtxt(path, delimiter=",", skiprows=1, dtype=dtype, ndmin=1)
    except ValueError as e:
        raise FrameFormatError(f"{path}: {e}") from None
    return header, {n: rows[f"c{i}"].copy() for i, n in enumerate(header)}


def read_frame(path) -> Frame:
    """Reads a .csv, .vtu or .vtp frame by its extension."""
    path = Path(path)
    if path.suffix == ".csv":
        return read_csv_frame(path)
    if path.suffix in (".vtu", ".vtp"):
        return read_vtk_frame(path)
    raise FrameFormatError(f"{path}: unknown frame extension '{path.suffix}' (.csv, .vtu, .vtp)")


def read_csv_frame(path) -> Frame:
    """Reads a CSV frame exactly (numpy's parser rounds correctly)."""
    path = Path(path)
    with open(path, encoding="ascii") as f:
        header = f.readline().rstrip("\n").split(",")
    if tuple(header[: len(CSV_FIXED_COLUMNS)]) != CSV_FIXED_COLUMNS:
        raise FrameFormatError(f"{path}:1: not a sadr frame CSV (expected the header "
                               f"{','.join(CSV_FIXED_COLUMNS)},<species...>, got {','.join(header)})")
    species = header[len(CSV_FIXED_COLUMNS):]
    _, col = read_columns(path, ("id", "kind"))
    times = col["time"]
    if len(times) and np.any(times != times[0]):
        raise FrameFormatError(f"{path}: the time column is not constant")
    return Frame(
        time=float(times[0]) if len(times) else float("nan"),
        ids=col["id"],
        kinds=col["kind"],
        positions=np.column_stack([col["x"], col["y"], col["z"]]),
        velocity=np.column_stack([col["vx"], col["vy"], col["vz"]]),
        density=col["density"],
        mass=col["mass"],
        species={s: col[s] for s in species},
        path=path,
    )


_VTK_TYPES = {"Float64": "f8", "Float32": "f4", "Int64": "i8", "UInt64": "u8", "Int32": "i4",
              "UInt32": "u4", "Int16": "i2", "UInt16": "u2", "Int8": "i1", "UInt8": "u1"}
_ATTR = re.compile(rb'([A-Za-z_]+)="([^"]*)"')
_TAG = re.compile(rb"<(/?)(DataArray|PointData|Points|FieldData|Cells|Verts|AppendedData|VTKFile)\b([^>]*)>")


def _attrs(raw: bytes) -> dict:
    return {k.decode(): v.decode() for k, v in _ATTR.findall(raw)}


def read_vtk_arrays(path) -> dict:
    """All DataArrays of a VTK XML file (.vtu/.vtp) as {(section, name): array}.

    section is 'PointData', 'Points', 'FieldData', 'Cells' or 'Verts';
    multi-component arrays have shape (n, components)."""
    path = Path(path)
    data = path.read_bytes()
    head = data.find(b"<AppendedData")
    xml = data if head < 0 else data[:head]
    root = _TAG.search(xml)
    if not root or root.group(2) != b"VTKFile":
        raise FrameFormatError(f"{path}: not a VTK XML file (no <VTKFile> element)")
    top = _attrs(root.group(3))
    if "compressor" in top:
        raise FrameFormatError(f"{path}: compressed VTK XML ({top['compressor']}) is not supported; "
                               "sadr writes uncompressed files")
    order = "<" if top.get("byte_order", "LittleEndian") == "LittleEndian" else ">"
    header_type = np.dtype(order + _VTK_TYPES[top.get("header_type", "UInt32")])
    appended = None
    if head >= 0:
        tag_end = data.index(b">", head)
        enc = _attrs(data[head:tag_end]).get("encoding", "raw")
        if enc != "raw":
            raise FrameFormatError(f"{path}: AppendedData encoding '{enc}' is not supported (raw only)")
        appended = data.index(b"_", tag_end) + 1
    arrays, section = {}, None
    for m in _TAG.finditer(xml):
        closing, tag, rest = m.group(1), m.group(2).decode(), m.group(3)
        if tag != "DataArray":
            if tag not in ("VTKFile", "AppendedData"):
                section = None if closing else tag
            continue
        if closing:
            continue
        a = _attrs(rest)
        name = a.get("Name", "")
        where = f"{path}: DataArray '{name}'"
        if a.get("type") not in _VTK_TYPES:
            raise FrameFormatError(f"{where}: unsupported type '{a.get('type')}'")
        dtype = np.dtype(order + _VTK_TYPES[a["type"]])
        fmt = a.get("format", "ascii")
        if fmt == "appended":
            if appended is None:
                raise FrameFormatError(f"{where}: format 'appended' but the file has no <AppendedData>")
            start = appended + int(a["offset"])
            nbytes = int(np.frombuffer(data, header_type, 1, start)[0])
            values = np.frombuffer(data, dtype, nbytes // dtype.itemsize, start + header_type.itemsize)
        elif fmt == "ascii":
            end = xml.index(b"</DataArray>", m.end())
            values = np.array(xml[m.end():end].split(), dtype=dtype)
        else:
            raise FrameFormatError(f"{where}: format '{fmt}' is not supported (sadr writes "
                                   "'appended' raw binary or 'ascii')")
        values = values.astype(dtype.newbyteorder("="))  # native order, a copy
        comps = int(a.get("NumberOfComponents", "1"))
        if comps > 1:
            if values.size % comps:
                raise FrameFormatError(f"{where}: {values.size} values, not a multiple of {comps}")
            values = values.reshape(-1, comps)
        arrays[(section or "", name)] = values
    return arrays


def read_vtk_frame(path) -> Frame:
    """Reads a .vtu or .vtp frame written by sadr (any of its encodings)."""
    path = Path(path)
    arrays = read_vtk_arrays(path)
    point = {name: v for (sec, name), v in arrays.items() if sec == "PointData"}
    missing = [k for k in ("id", "kind", "velocity", "density", "mass") if k not in point]
    if missing or ("Points", "Points") not in arrays:
        raise FrameFormatError(f"{path}: not a sadr frame (missing point arrays: "
                               f"{', '.join(missing + ([] if ('Points', 'Points') in arrays else ['Points']))})")
    time = arrays.get(("FieldData", "TimeValue"))
    fixed = ("id", "kind", "velocity", "density", "mass")
    return Frame(
        time=float(time[0]) if time is not None else float("nan"),
        ids=point["id"].astype(np.uint64),
        kinds=point["kind"].astype(np.uint8),
        positions=arrays[("Points", "Points")].reshape(-1, 3),
        velocity=point["velocity"].reshape(-1, 3),
        density=point["density"],
        mass=point["mass"],
        species={k: v for k, v in point.items() if k not in fixed},
        path=path,
    )


def read_pvd(path) -> list:
    """The (time, file path) entries of a ParaView .pvd collection, in order."""
    path = Path(path)
    out = []
    for m in re.finditer(rb"<DataSet\b([^>]*)>", path.read_bytes()):
        a = _attrs(m.group(1))
        out.append((float(a["timestep"]), path.parent / a["file"]))
    return out


def read_ensemble_frame(path) -> tuple:
    """An ``ensemble/frame_NNNNNN.csv`` of `sadr run -r R` / `sadr ensemble`:
    returns (time, ids, realizations, {species: (mean, variance)})."""
    path = Path(path)
    header, col = read_columns(path)
    if header[:3] != ["time", "id", "realizations"]:
        raise FrameFormatError(f"{path}:1: not a sadr ensemble CSV (expected time,id,realizations,...)")
    stats = {}
    for n in header[3:]:
        if n.endswith("_mean"):
            s = n[: -len("_mean")]
            stats[s] = (col[n], col[s + "_var"])
    return float(col["time"][0]), col["id"], col["realizations"], stats
