# SPDX-License-Identifier: MIT
"""The ``geometry`` section of a scene in Python: particles made from bodies,
each a shape with a role (docs/scene-format.md, "geometry"; docs/geometry.md)::

    from sadr.geometry import Box, Disk, Geometry

    geo = Geometry(spacing=0.05)
    geo.add_fluid("channel", Box([-1.0, 0.0], [3.0, 1.0]))
    geo.add_solid("cell", Disk([0.6, 0.5], 0.12), wall_layer="membrane")
    model.geometry = geo                        # a sadr.Model (or model.set_geometry(...))
    built = model.build_geometry("geo")         # `sadr geometry`: particles and summary
    built.particles                             # pandas DataFrame of DIR/particles.csv
    print(built.summary)

Shapes: Box, Disk/Sphere, Ellipse/Ellipsoid, Capsule, Cylinder, Torus,
Polygon, Extrusion, Mesh (a ``.stl``/``.msh`` file, optionally a physical
group), and the CSG shapes Union, Intersection and Difference (also ``a | b``,
``a & b``, ``a - b``). Transforms chain: ``Sphere([0, 0, 0], 1).scale(2)
.rotate(30, axis=[0, 0, 1]).translate([1, 0, 0])``. The scene applies a
shape's ``scale``, ``rotate`` and ``translate`` once each, in that order; a
transform that would come after one already set (``.translate(a).scale(2)``)
wraps the shape in a one-shape union, so the result is the order written.

Every class's fields are the scene's keys (sadr.parts): the keys are named
once, and ``python_model`` compares them with the scene loader's lists.
Nothing here checks a value: a key left ``None`` is not written (the
product's default applies), unknown keys are kept in ``extra`` and every
refusal is the CLI's (sadr.InvalidInput with `sadr validate`'s or `sadr
geometry`'s file:line message).
"""
from __future__ import annotations

import copy
import dataclasses
import os
from dataclasses import dataclass, field
from pathlib import Path
import typing
from typing import TYPE_CHECKING, Any, ClassVar, Iterator

from .parts import Part, Written, build, plain

if TYPE_CHECKING:
    import pandas as pd

    from .model import Model

Number = typing.Union[int, float]
Vector = list

TRANSFORMS = ("scale", "rotate", "translate")
"""A shape's transform keys, in the order the scene applies them."""


class Shape(Written):
    """A shape: ``type`` and that type's keys (the dataclass fields of its
    class), its transforms (``transforms``: scale, rotate, translate) and keys
    this package does not know (``extra``). ``Shape.from_dict`` reads any."""

    type: ClassVar[str] = ""

    def _setup(self) -> None:
        if not hasattr(self, "transforms"):
            self.transforms: dict = {}
        if not hasattr(self, "extra"):
            self.extra: dict = {}

    def __post_init__(self) -> None:
        self._setup()

    @classmethod
    def keys(cls) -> list[str]:
        """The type's own keys (besides ``type`` and the transforms)."""
        return [f.name for f in dataclasses.fields(cls)] if dataclasses.is_dataclass(cls) else []

    def _type(self) -> str | None:
        return self.type

    def to_dict(self) -> dict:
        self._setup()
        out: dict = {} if self._type() is None else {"type": self._type()}
        for name in self.keys():
            value = getattr(self, name)
            if value is not None:
                out[name] = plain(value)
        for name in TRANSFORMS:
            if name in self.transforms:
                out[name] = plain(self.transforms[name])
        out.update(plain(self.extra))
        return out

    @staticmethod
    def from_dict(data: dict) -> Shape:
        """The shape a scene's mapping describes (an unknown ``type`` as AnyShape)."""
        data = dict(data)
        kind = data.pop("type", None)
        cls = SHAPES.get(kind) if isinstance(kind, str) else None
        transforms = {k: data.pop(k) for k in TRANSFORMS if k in data}
        if cls is None:
            shape: Shape = AnyShape(kind, **data)
        else:
            names = set(cls.keys())
            kwargs = {k: data.pop(k) for k in list(data) if k in names}
            if "shapes" in kwargs:
                kwargs["shapes"] = build([Shape], kwargs["shapes"])
            shape = cls(**kwargs)
            shape.extra = data
        shape.transforms = transforms
        return shape

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Shape) and self.to_dict() == other.to_dict()

    __hash__ = None  # mutable

    def __repr__(self) -> str:
        self._setup()
        keys = {k: getattr(self, k) for k in self.keys() if getattr(self, k) is not None}
        args = ", ".join(f"{k}={v!r}" for k, v in {**keys, **self.extra}.items())
        text = f"{type(self).__name__}({args})"
        for k in TRANSFORMS:
            if k in self.transforms:
                text += f".{k}({self.transforms[k]!r})"
        return text

    # --- transforms ---------------------------------------------------------------

    def _with(self, key: str, value: Any) -> Shape:
        self._setup()
        later = TRANSFORMS[TRANSFORMS.index(key):]
        if any(k in self.transforms for k in later):
            out: Shape = Union([copy.deepcopy(self)])  # the scene's order is fixed: keep the one written
        else:
            out = copy.deepcopy(self)
        out._setup()
        out.transforms[key] = value
        return out

    def scale(self, factor: Number | Vector) -> Shape:
        """A copy scaled about the origin: one factor, or one per axis."""
        return self._with("scale", list(factor) if isinstance(factor, (list, tuple)) else factor)

    def rotate(self, angle: Number, axis: Vector | None = None) -> Shape:
        """A copy rotated about the origin by ``angle`` degrees: counter-clockwise
        in 2D (no ``axis``), about ``axis`` by the right-hand rule in 3D."""
        return self._with("rotate", angle if axis is None else {"axis": list(axis), "angle": angle})

    def translate(self, offset: Vector) -> Shape:
        """A copy moved by ``offset`` (``dimension`` numbers)."""
        return self._with("translate", list(offset))

    # --- CSG ----------------------------------------------------------------------

    def _plain_csg(self, cls: type) -> bool:
        self._setup()
        return type(self) is cls and not self.transforms and not self.extra

    def __or__(self, other: Shape) -> Union:
        if not isinstance(other, Shape):
            return NotImplemented
        return Union((self.shapes if self._plain_csg(Union) else [self]) + [other])

    def __and__(self, other: Shape) -> Intersection:
        if not isinstance(other, Shape):
            return NotImplemented
        return Intersection((self.shapes if self._plain_csg(Intersection) else [self]) + [other])

    def __sub__(self, other: Shape) -> Difference:
        if not isinstance(other, Shape):
            return NotImplemented
        return Difference((self.shapes if self._plain_csg(Difference) else [self]) + [other])


class AnyShape(Shape):
    """A shape of a ``type`` this package has no class for, written as given
    (the CLI names the allowed types)."""

    def __init__(self, type: str | None, **keys: Any):  # noqa: A002 - the scene's key
        self.shape_type = type
        self.extra = dict(keys)
        self.transforms = {}

    def _type(self) -> str | None:
        return self.shape_type


@dataclass(eq=False, repr=False)
class Box(Shape):
    """An axis-aligned box (2D, 3D): ``lower`` and ``upper`` corners."""

    type: ClassVar[str] = "box"
    lower: Vector | None = None
    upper: Vector | None = None


@dataclass(eq=False, repr=False)
class Disk(Shape):
    """A disk (2D): ``center`` and ``radius``."""

    type: ClassVar[str] = "disk"
    center: Vector | None = None
    radius: Number | None = None


@dataclass(eq=False, repr=False)
class Sphere(Disk):
    """A sphere (3D): ``center`` and ``radius``."""

    type: ClassVar[str] = "sphere"


@dataclass(eq=False, repr=False)
class Ellipse(Shape):
    """An axis-aligned ellipse (2D): ``center`` and ``radii`` (semi-axes along x, y)."""

    type: ClassVar[str] = "ellipse"
    center: Vector | None = None
    radii: Vector | None = None


@dataclass(eq=False, repr=False)
class Ellipsoid(Ellipse):
    """An axis-aligned ellipsoid (3D): ``center`` and ``radii`` along x, y, z."""

    type: ClassVar[str] = "ellipsoid"


@dataclass(eq=False, repr=False)
class Capsule(Shape):
    """The points within ``radius`` of the segment ``start``-``end`` (2D: a stadium; 3D)."""

    type: ClassVar[str] = "capsule"
    start: Vector | None = None
    end: Vector | None = None
    radius: Number | None = None


@dataclass(eq=False, repr=False)
class Cylinder(Capsule):
    """A cylinder (3D) between the centres ``start`` and ``end`` of its end caps."""

    type: ClassVar[str] = "cylinder"


@dataclass(eq=False, repr=False)
class Torus(Shape):
    """A torus (3D) around the z axis through ``center``."""

    type: ClassVar[str] = "torus"
    center: Vector | None = None
    major_radius: Number | None = None
    minor_radius: Number | None = None


@dataclass(eq=False, repr=False)
class Polygon(Shape):
    """A polygon (2D): at least 3 ``vertices`` [x, y], inside by the even-odd rule."""

    type: ClassVar[str] = "polygon"
    vertices: list | None = None


@dataclass(eq=False, repr=False)
class Extrusion(Shape):
    """A polygon in the xy plane (``vertices``) extruded over ``z`` = [z0, z1] (3D)."""

    type: ClassVar[str] = "extrusion"
    vertices: list | None = None
    z: Vector | None = None


@dataclass(eq=False, repr=False)
class Mesh(Shape):
    """A closed mesh from ``file`` (``.stl``, or gmsh ``.msh`` with an optional
    physical ``group``). A relative path points from the scene file when it is
    read by `sadr`; sadr.Model takes it from its ``base_dir`` (the loaded
    file's folder, else the working directory) and re-writes it relative to
    wherever the scene is saved."""

    type: ClassVar[str] = "mesh"
    file: str | None = None
    group: str | None = None


@dataclass(eq=False, repr=False)
class Union(Shape):
    """The union of ``shapes`` (also ``a | b``)."""

    type: ClassVar[str] = "union"
    shapes: list[Shape] | None = None

    def __post_init__(self) -> None:
        self.shapes = list(self.shapes) if isinstance(self.shapes, (list, tuple)) else self.shapes
        self._setup()


@dataclass(eq=False, repr=False)
class Intersection(Union):
    """The intersection of ``shapes`` (also ``a & b``)."""

    type: ClassVar[str] = "intersection"


@dataclass(eq=False, repr=False)
class Difference(Union):
    """The first of ``shapes`` minus all the others (also ``a - b``)."""

    type: ClassVar[str] = "difference"


SHAPES: dict[str, type] = {cls.type: cls for cls in (
    Box, Disk, Sphere, Ellipse, Ellipsoid, Capsule, Cylinder, Torus, Polygon, Extrusion, Mesh,
    Union, Intersection, Difference)}
"""The shape class of each ``type``."""


def union(*shapes: Shape) -> Union:
    """The union of ``shapes``."""
    return Union(list(shapes))


def intersection(*shapes: Shape) -> Intersection:
    """The intersection of ``shapes``."""
    return Intersection(list(shapes))


def difference(first: Shape, *others: Shape) -> Difference:
    """``first`` minus every one of ``others``."""
    return Difference([first, *others])


# --- bodies and the section ----------------------------------------------------------

ROLES = ("fluid", "solid", "region")
"""A body's roles (docs/scene-format.md, "geometry")."""


@dataclass
class Body(Part):
    """A body: ``name`` (a region of the scene), ``role`` (fluid, solid,
    region), ``shape``; fluid and solid bodies may name their ``wall_layer``
    and ``fluid_layer`` regions (``layer_thickness`` deep), region bodies
    may restrict their members to ``kinds``; a solid body's ``motion`` is its
    walls' prescribed motion, a map ``{velocity: [..]}`` and/or
    ``{angular_velocity: w, center: [..], axis: [..]}``, with ``moves: True``
    a body that translates and turns (docs/scene-format.md "Moving walls",
    "Moving bodies")."""

    name: str | None = None
    role: str | None = None
    shape: Shape | None = None
    wall_layer: str | None = None
    fluid_layer: str | None = None
    layer_thickness: Number | None = None
    kinds: list[str] | None = None
    motion: dict | None = None
    extra: dict = field(default_factory=dict)
    _nested: ClassVar[dict[str, Any]] = {"shape": Shape}


@dataclass
class Relax(Part):
    """``relax``: move the fluid particles until max |n_i / n_ref - 1| is below
    ``tolerance`` or after ``max_iterations``; ``Relax()`` takes the defaults."""

    tolerance: Number | None = None
    max_iterations: int | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class Geometry(Part):
    """The ``geometry`` section: lattice ``spacing`` (required), ``lattice``
    (cubic, hexagonal), particle ``density``, ``wall_depth``, lattice
    ``offset`` (in spacings), ``relax`` (a Relax), and the ``bodies``."""

    spacing: Number | None = None
    lattice: str | None = None
    density: Number | None = None
    wall_depth: Number | None = None
    offset: Vector | None = None
    relax: Relax | None = None
    bodies: list[Body] | None = None
    extra: dict = field(default_factory=dict)
    _nested: ClassVar[dict[str, Any]] = {"relax": Relax, "bodies": [Body]}

    def add_body(self, name: str, role: str, shape: Shape, **keys: Any) -> Body:
        """Appends a body; ``keys``: wall_layer, fluid_layer, layer_thickness, kinds, motion."""
        body = Body.from_dict({"name": name, "role": role, "shape": None, **keys})
        body.shape = shape
        self.bodies = (self.bodies or []) + [body]
        return body

    def add_fluid(self, name: str, shape: Shape, *, wall_layer: str | None = None,
                  fluid_layer: str | None = None, layer_thickness: Number | None = None) -> Body:
        """The fluid body (at most one; none: the whole box is the fluid)."""
        return self.add_body(name, "fluid", shape, wall_layer=wall_layer, fluid_layer=fluid_layer,
                             layer_thickness=layer_thickness)

    def add_solid(self, name: str, shape: Shape, *, wall_layer: str | None = None,
                  fluid_layer: str | None = None, layer_thickness: Number | None = None) -> Body:
        """A solid the fluid flows around: wall particles behind its surface."""
        return self.add_body(name, "solid", shape, wall_layer=wall_layer, fluid_layer=fluid_layer,
                             layer_thickness=layer_thickness)

    def add_region(self, name: str, shape: Shape, *, kinds: list[str] | None = None) -> Body:
        """A named region only (every particle inside ``shape``, of ``kinds`` if given)."""
        return self.add_body(name, "region", shape, kinds=kinds)

    def set_relax(self, tolerance: Number | None = None, max_iterations: int | None = None) -> Relax:
        """Relaxation of the fluid particles (no arguments: the defaults)."""
        self.relax = Relax(tolerance, max_iterations)
        return self.relax

    def get_body(self, name: str) -> Body:
        for b in self.bodies or []:
            if isinstance(b, Body) and b.name == name:
                return b
        names = ", ".join(str(b.name) for b in self.bodies or [] if isinstance(b, Body)) or "none"
        raise KeyError(f"no body named '{name}' (names: {names})")

    def meshes(self) -> Iterator[tuple[str, Mesh]]:
        """(path in the scene, as for ``--set``, Mesh) of every mesh shape, nested ones too."""
        def walk(shape: Any, where: str) -> Iterator[tuple[str, Mesh]]:
            if isinstance(shape, Mesh) and isinstance(shape.file, (str, os.PathLike)):
                yield f"{where}.file", shape
            if isinstance(shape, Union) and isinstance(shape.shapes, list):
                for k, child in enumerate(shape.shapes):
                    yield from walk(child, f"{where}.shapes[{k}]")

        for k, body in enumerate(self.bodies or []):
            if isinstance(body, Body):
                yield from walk(body.shape, f"geometry.bodies[{k}].shape")

    def build(self, output: str | os.PathLike, model: Model, *,
              overrides: dict | None = None) -> GeometryBuild:
        """`sadr geometry` on ``model`` with this section (its box, dimension and
        fluid give the lattice's box and the kernel support): writes the scene
        to ``OUTPUT/<name>.yaml``, the particles to ``OUTPUT/particles.csv`` and
        ``.vtu``; returns a GeometryBuild. Refusals raise sadr.InvalidInput with
        the CLI's message (and the scene it read as ``scene_yaml``)."""
        m = model.copy()
        m.geometry = self
        m.particles = None
        return m.build_geometry(output, overrides=overrides)


# --- what `sadr geometry` made -------------------------------------------------------

@dataclass
class GeometryBuild:
    """The particles `sadr geometry` made: ``particles`` (DIR/particles.csv as
    a pandas DataFrame, exact: kind, positions, surface_id, surface_distance,
    volume, density_error and one 0/1 ``region_<name>`` column per region),
    ``summary`` (what it printed: counts, bodies, volumes, density error,
    smallest feature, regions, warnings count), ``log`` (its stderr:
    warnings), the ``directory`` and the ``scene_file`` it read."""

    directory: Path
    scene_file: Path
    particles: pd.DataFrame
    summary: str
    log: str = ""

    @property
    def regions(self) -> list[str]:
        """The regions' names, in the CSV's column order."""
        return [c[len("region_"):] for c in self.particles.columns if c.startswith("region_")]

    def region(self, name: str) -> pd.DataFrame:
        """The rows of the particles in region ``name``."""
        column = f"region_{name}"
        if column not in self.particles.columns:
            raise KeyError(f"no region '{name}' (regions: {', '.join(self.regions)})")
        return self.particles[self.particles[column] == 1]

    def counts(self) -> dict[str, int]:
        """Particles per kind name (fluid, wall, ...), kinds that occur only."""
        from .frames import KIND_NAMES

        values = self.particles["kind"].value_counts().sort_index()
        return {KIND_NAMES[int(k)] if int(k) < len(KIND_NAMES) else str(k): int(n)
                for k, n in values.items()}


def read_particles(path: str | os.PathLike) -> pd.DataFrame:
    """``particles.csv`` of `sadr geometry` (a file, or its folder) as a pandas
    DataFrame, every number exact (numpy's parser; id and kind as integers)."""
    import pandas as pd

    from .frames import read_columns

    path = Path(path)
    if path.is_dir():
        path = path / "particles.csv"
    header, columns = read_columns(path, integer_columns=("id", "kind"))
    return pd.DataFrame({name: columns[name] for name in header})
