# SPDX-License-Identifier: MIT
"""Build a scene in Python: ``sadr.Model``.

A Model holds every part of a scene file (docs/scene-format.md) as Python
objects: the box, regions, particles (a lattice with fill rules, a
particle file, or the ``geometry`` section: sadr.geometry), the fluid backend and its settings, species with initial
values and boundary conditions, parameters, reactions with their rate laws,
boundary fluxes, time, output, SSA options and the seed. It writes the YAML
that `sadr` reads, and validates and runs it through the `sadr` CLI::

    import sadr
    m = sadr.Model("decay", dimension=2)
    m.set_box([0, 0], [1, 1], periodic=[True, True])
    m.set_lattice(spacing=0.05)
    m.set_fluid("static", h_over_dx=2.0)
    m.add_region("source", "disk", center=[0.5, 0.5], radius=0.15)
    m.add_species("A", diffusivity=0.01)
    m.add_reaction("0 -> A", name="make_A", rate=4000, regions=["source"])
    m.add_reaction("A -> 0", name="decay_A", rate=1.0)
    m.set_time(coupling_step=0.05, end=1.0)
    m.set_output(every=0.25)
    m.validate()                     # `sadr validate`; InvalidInput with its message
    run = m.run("runs/decay")        # a sadr.Run

Nothing here checks a value: a part left unset (None) is left out of the
file, so the product's default applies, and every check is the CLI's (a
refusal raises sadr.InvalidInput carrying `sadr validate`'s message). Keys
this module does not know are kept (``extra``) and passed on, so the CLI
names them too. ``Model.load(path)`` reads any scene file; ``save(path)``
writes it back with the same meaning (paths of particle and field files are
rewritten relative to the new file).
"""
from __future__ import annotations

import copy
import dataclasses
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar, Union

from .cli import InvalidInput, run_cli
from .geometry import Geometry, GeometryBuild, read_particles
from .parts import Part as _Part
from .parts import Written, build as _build, plain as _plain
from .paths import dump_yaml, get_path, load_yaml, set_path
from .runs import Ensemble, Run

Number = Union[int, float]
Value = Union[int, float, str]
"""A number, or the name of a top-level parameter (in rate laws)."""
Vector = list


# --- rate laws ----------------------------------------------------------------

class Law(Written):
    """A rate law other than mass action (``law:`` of a reaction or a boundary
    flux). Use MichaelisMenten, Hill or Expression; ``Law(type, **keys)`` writes
    any other ``type`` as given."""

    type: str = ""

    def __init__(self, type: str, **keys: Any):  # noqa: A002 - the scene's key
        self.type = type
        self.keys = dict(keys)

    def to_dict(self) -> dict:
        head = {"type": self.type} if self.type is not None else {}  # no type: the CLI says so
        return {**head, **{k: _plain(v) for k, v in self.keys.items() if v is not None}}

    @staticmethod
    def from_dict(data: dict) -> Law:
        data = dict(data)
        kind = data.pop("type", None)
        cls = _LAWS.get(kind)
        if cls is None:
            return Law(kind, **data)
        try:
            return cls(**data)
        except TypeError:  # a key missing: written as it was, and the CLI says which
            law = Law(kind, **data)
            law.__class__ = cls
            return law

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Law) and self.to_dict() == other.to_dict()

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.to_dict().items() if k != "type")
        return f"{type(self).__name__}({args})" if type(self) is not Law else f"Law({self.type!r}, {args})"


class MichaelisMenten(Law):
    """v = kcat [catalyst] [substrate] / (Km + [substrate]); ``substrate``
    defaults to the reaction's single reactant."""

    def __init__(self, kcat: Value, Km: Value, catalyst: str, substrate: str | None = None,
                 **extra: Any):
        super().__init__("michaelis_menten", kcat=kcat, Km=Km, catalyst=catalyst, substrate=substrate,
                         **extra)


class Hill(Law):
    """v = Vmax [of]^n / (K^n + [of]^n); ``of`` defaults to the single reactant."""

    def __init__(self, Vmax: Value, K: Value, n: Value, of: str | None = None, **extra: Any):
        super().__init__("hill", Vmax=Vmax, K=K, n=n, of=of, **extra)


class Expression(Law):
    """v as a muparser expression of species (concentrations), parameters and ``t``."""

    def __init__(self, expression: str, **extra: Any):
        super().__init__("expression", expression=expression, **extra)


_LAWS: dict[str | None, Any] = {"michaelis_menten": MichaelisMenten, "hill": Hill,
                                "expression": Expression}


# --- the parts of a scene -------------------------------------------------------

@dataclass
class Domain(_Part):
    """``box``: the domain, ``dimension`` numbers each."""

    lower: Vector | None = None
    upper: Vector | None = None
    periodic: list[bool] | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class Region(_Part):
    """A named region (``regions``): shape ``box``, ``sphere``, ``disk``,
    ``annulus``, ``channel`` or ``ids`` with that shape's keys; ``kinds``
    restricts it to particle kinds."""

    name: str | None = None
    shape: str | None = None
    lower: Any = None
    upper: Any = None
    center: Vector | None = None
    radius: Number | None = None
    inner_radius: Number | None = None
    outer_radius: Number | None = None
    axis: str | None = None
    ids: list[int] | None = None
    kinds: list[str] | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class Fill(_Part):
    """A lattice fill rule: lattice points in ``region`` become particles of ``kind``."""

    region: str | None = None
    kind: str | None = None
    density: Number | None = None
    mass_factor: Number | None = None
    velocity: Vector | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class Particles(_Part):
    """``particles``: a lattice (``spacing``, ``density``, ``fill``) or a CSV
    particle ``file`` (relative to the scene file, or absolute)."""

    spacing: Number | None = None
    density: Number | None = None
    fill: list[Fill] | None = None
    file: str | None = None
    extra: dict = field(default_factory=dict)
    _nested: ClassVar[dict[str, Any]] = {"fill": [Fill]}

    def add_fill(self, region: str | None = None, kind: str | None = None, *,
                 density: Number | None = None, mass_factor: Number | None = None,
                 velocity: Vector | None = None) -> Fill:
        """Appends a fill rule (the first rule whose region holds a point decides it)."""
        rule = Fill(region, kind, density, mass_factor, velocity)
        self.fill = (self.fill or []) + [rule]
        return rule


@dataclass
class Boussinesq(_Part):
    """``fluid.boussinesq``: body force g beta (C - reference) along ``direction``."""

    species: str | None = None
    coefficient: Number | None = None
    reference: Number | None = None
    direction: Vector | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class OpenBoundary(_Part):
    """``fluid.open_boundary``: inflow and outflow buffers along one axis."""

    axis: str | None = None
    inlet: Vector | None = None
    outlet: Vector | None = None
    profile: str | None = None
    mean_velocity: Number | None = None
    max_velocity: Number | None = None
    walls: Vector | None = None
    cross_axis: str | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class WallPlane(_Part):
    """A ``fluid.wall_planes`` entry: a plane (``point``, ``normal``) or a
    circle/sphere (``center``, ``radius``) for the wall particles of ``region``."""

    region: str | None = None
    point: Vector | None = None
    normal: Vector | None = None
    center: Vector | None = None
    radius: Number | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class Fluid(_Part):
    """``fluid``: the backend, its common settings, and ``parameters`` (the
    backend's own, by name: `sadr backends` lists them)."""

    backend: str | None = None
    smoothing_length: Number | None = None
    h_over_dx: Number | None = None
    kernel: str | None = None
    reference_density: Number | None = None
    sound_speed: Number | None = None
    shear_viscosity: Number | None = None
    temperature: Number | None = None
    gravity: Vector | None = None
    density_mode: str | None = None
    boussinesq: Boussinesq | None = None
    max_time_step: Number | None = None
    force_time_step: bool | None = None
    parameters: dict | None = None
    open_boundary: OpenBoundary | None = None
    wall_model: str | None = None
    wall_planes: list[WallPlane] | None = None
    body_forces: list[str] | None = None
    extra: dict = field(default_factory=dict)
    _nested: ClassVar[dict[str, Any]] = {"boussinesq": Boussinesq, "open_boundary": OpenBoundary,
                                         "wall_planes": [WallPlane]}


@dataclass
class Initial(_Part):
    """A species' initial value over a region: exactly one of ``count``,
    ``concentration``, ``count_column``, ``concentration_column``."""

    region: str | None = None
    count: Number | None = None
    concentration: Number | None = None
    count_column: str | None = None
    concentration_column: str | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class Boundary(_Part):
    """A species' condition on a region's non-fluid particles: ``dirichlet``,
    ``neumann``, ``none``, ``free`` or ``inflow``, with ``value`` or ``count``.
    Instead of ``region``: ``surface``, the wall particles behind a fluid or solid body's
    surface, and with ``group`` only those behind one physical group of its mesh file."""

    region: str | None = None
    condition: str | None = None
    value: Number | None = None
    count: Number | None = None
    surface: str | None = None
    group: str | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class Species(_Part):
    """A species: stochastic (copy numbers, the default) or deterministic, or
    ``assigned`` (an expression evaluated where frames are written)."""

    name: str | None = None
    stochastic: bool | None = None
    diffusivity: Number | None = None
    initial: list[Initial] | None = None
    boundaries: list[Boundary] | None = None
    assigned: str | None = None
    extra: dict = field(default_factory=dict)
    _nested: ClassVar[dict[str, Any]] = {"initial": [Initial], "boundaries": [Boundary]}

    def add_initial(self, region: str | None = None, *, count: Number | None = None,
                    concentration: Number | None = None, count_column: str | None = None,
                    concentration_column: str | None = None) -> Species:
        """Appends an initial value (later entries overwrite earlier ones); returns the species."""
        self.initial = (self.initial or []) + [
            Initial(region, count, concentration, count_column, concentration_column)]
        return self

    def add_boundary(self, region: str, condition: str, *, value: Number | None = None,
                     count: Number | None = None) -> Species:
        """Appends a boundary condition; returns the species."""
        self.boundaries = (self.boundaries or []) + [Boundary(region, condition, value, count)]
        return self


@dataclass
class Reaction(_Part):
    """A reaction: ``equation`` (or ``reactants``/``products`` maps) with a
    mass-action ``rate`` (and ``reverse_rate`` for ``<->``) or a ``law``."""

    name: str | None = None
    equation: str | None = None
    reactants: dict | None = None
    products: dict | None = None
    rate: Value | None = None
    reverse_rate: Value | None = None
    law: Law | None = None
    kinds: list[str] | None = None
    regions: list[str] | None = None
    extra: dict = field(default_factory=dict)
    _nested: ClassVar[dict[str, Any]] = {"law": Law}


@dataclass
class BoundaryFlux(_Part):
    """A flux through a box face or the ``surface`` of a fluid or solid body of the geometry
    (``boundary_fluxes``) whose density is ``law``: an influx of ``species``, or ``equation``
    (reactants leave, products enter). ``group`` (with ``surface``): one physical group of the
    body's mesh file, the part of its surface that takes the flux."""

    name: str | None = None
    species: str | None = None
    equation: str | None = None
    face: str | None = None
    surface: str | None = None
    region: str | None = None
    law: Law | None = None
    group: str | None = None
    extra: dict = field(default_factory=dict)
    _nested: ClassVar[dict[str, Any]] = {"law": Law}


@dataclass
class Time(_Part):
    """``time``: the coupling step, the end time, the splitting (lie, strang) and the
    tolerance of the error-controlled step (a number, or a map of relative, absolute and
    max_step)."""

    coupling_step: Number | None = None
    end: Number | None = None
    splitting: str | None = None
    tolerance: Number | dict | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class Observable(_Part):
    """A named scalar of ``output.observables`` (a sweep's observables.csv)."""

    name: str | None = None
    species: str | None = None
    region: str | None = None
    stat: str | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class Output(_Part):
    """``output``: frame times (``every`` or ``times``), formats, species, checkpoints."""

    directory: str | None = None
    every: Number | None = None
    times: list[Number] | None = None
    include_initial: bool | None = None
    formats: list[str] | None = None
    species: list[str] | None = None
    checkpoint_every: Number | None = None
    vtk_encoding: str | None = None
    observables: list[Observable] | None = None
    extra: dict = field(default_factory=dict)
    _nested: ClassVar[dict[str, Any]] = {"observables": [Observable]}


@dataclass
class Ssa(_Part):
    """``ssa``: the diffusion convention (volume, symmetric), regularization, and the
    method (exact, adaptive) with its tolerance (adaptive only)."""

    convention: str | None = None
    regularization: Number | None = None
    method: str | None = None
    tolerance: Number | None = None
    extra: dict = field(default_factory=dict)


_TOP = ("name", "description", "dimension", "box", "regions", "particles", "geometry", "fluid",
        "species", "parameters", "reactions", "boundary_fluxes", "time", "output", "ssa", "seed")
_TOP_PARTS: dict[str, Any] = {"box": Domain, "regions": [Region], "particles": Particles,
                              "geometry": Geometry, "fluid": Fluid, "species": [Species], "reactions": [Reaction],
                              "boundary_fluxes": [BoundaryFlux], "time": Time, "output": Output,
                              "ssa": Ssa}


class Model:
    """A scene built in Python (see the module doc). Attributes hold the parts
    (None: not written, the product's default): ``name``, ``description``,
    ``dimension``, ``box`` (Domain), ``regions``, ``particles``, ``geometry``
    (a sadr.geometry.Geometry: particles from shapes, instead of ``particles``), ``fluid``,
    ``species``, ``parameters`` (dict), ``reactions``, ``boundary_fluxes``,
    ``time``, ``output``, ``ssa``, ``seed``, and ``extra`` (unknown top-level
    keys, passed on to the CLI)."""

    def __init__(self, name: str | None = None, dimension: int | None = None, *,
                 description: str | None = None, seed: int | None = None):
        self.name = name
        self.description = description
        self.dimension = dimension
        self.box: Domain | None = None
        self.regions: list[Region] = []
        self.particles: Particles | None = None
        self.geometry: Geometry | None = None
        self.fluid: Fluid | None = None
        self.species: list[Species] = []
        self.parameters: dict[str, Number] = {}
        self.reactions: list[Reaction] = []
        self.boundary_fluxes: list[BoundaryFlux] = []
        self.time: Time | None = None
        self.output: Output | None = None
        self.ssa: Ssa | None = None
        self.seed = seed
        self.extra: dict = {}
        self.base_dir: Path | None = None
        """Where relative file paths (particles.file, fluid.parameters.field_file,
        the files of geometry meshes) point from: the loaded file's folder; None: the working directory."""

    def __repr__(self) -> str:
        return (f"sadr.Model({self.name!r}, dimension={self.dimension}, {len(self.species)} species, "
                f"{len(self.reactions)} reactions)")

    def copy(self) -> Model:
        """An independent deep copy (same base_dir)."""
        return copy.deepcopy(self)

    def __eq__(self, other: object) -> bool:
        """Equal when they write the same scene (file paths resolved)."""
        return isinstance(other, Model) and self.resolved() == other.resolved()

    __hash__ = None  # mutable

    # --- building ---------------------------------------------------------------

    def set_box(self, lower: Vector, upper: Vector, periodic: list[bool] | None = None) -> Domain:
        """The domain: ``lower``/``upper`` corners, ``periodic`` per axis (default: all walled)."""
        self.box = Domain(list(lower), list(upper), None if periodic is None else list(periodic))
        return self.box

    def add_region(self, name: str, shape: str, *, kinds: list[str] | None = None,
                   **geometry: Any) -> Region:
        """A named region: ``add_region("cell", "disk", center=[0.5, 0.5], radius=0.1)``;
        geometry keys: lower, upper, center, radius, inner_radius, outer_radius, axis, ids."""
        known = {f.name for f in dataclasses.fields(Region)} - {"name", "shape", "kinds", "extra"}
        extra = {k: geometry.pop(k) for k in list(geometry) if k not in known}
        region = Region(name=name, shape=shape, kinds=kinds, **geometry)
        region.extra = extra
        self.regions.append(region)
        return region

    def set_lattice(self, spacing: Number, *, density: Number | None = None,
                    fill: list[Fill] | None = None) -> Particles:
        """Particles on a lattice of ``spacing``; add fill rules with ``add_fill``."""
        self.particles = Particles(spacing=spacing, density=density, fill=fill)
        return self.particles

    def add_fill(self, region: str | None = None, kind: str | None = None, **keys: Any) -> Fill:
        """A lattice fill rule (density, mass_factor, velocity as keywords)."""
        if self.particles is None:
            raise ValueError("add_fill: set_lattice() first")
        return self.particles.add_fill(region, kind, **keys)

    def set_particle_file(self, path: str | os.PathLike) -> Particles:
        """Particles from a CSV file (a relative path is taken from the working
        directory and written relative to the scene file)."""
        self.particles = Particles(file=str(Path(path).resolve()))
        return self.particles

    def set_geometry(self, spacing: Number | Geometry, *, lattice: str | None = None,
                     density: Number | None = None, wall_depth: Number | None = None,
                     offset: Vector | None = None, relax: Any = None) -> Geometry:
        """Particles from shapes (the ``geometry`` section, sadr.geometry) instead
        of ``particles``: a Geometry, or its settings (add bodies to the result:
        ``add_fluid``, ``add_solid``, ``add_region``). ``relax``: a
        sadr.geometry.Relax, or a mapping of its keys."""
        if isinstance(spacing, Geometry):
            self.geometry = spacing
        else:
            from .geometry import Relax

            if isinstance(relax, dict):
                relax = Relax.from_dict(relax)
            self.geometry = Geometry(spacing=spacing, lattice=lattice, density=density,
                                     wall_depth=wall_depth, offset=offset, relax=relax)
        return self.geometry

    def set_fluid(self, backend: str, *, parameters: dict | None = None, **settings: Any) -> Fluid:
        """The fluid backend (``static``, ``sdpd``, ``tdpd``, ``prescribed``; `sadr
        backends`), its common settings as keywords (smoothing_length, h_over_dx,
        sound_speed, ...) and its own ``parameters``."""
        nested = {"boussinesq": Boussinesq, "open_boundary": OpenBoundary}
        for key, cls in nested.items():
            if isinstance(settings.get(key), dict):
                settings[key] = cls.from_dict(settings[key])
        if settings.get("wall_planes") is not None:
            settings["wall_planes"] = [WallPlane.from_dict(p) if isinstance(p, dict) else p
                                       for p in settings["wall_planes"]]
        self.fluid = Fluid(backend=backend, parameters=parameters, **settings)
        return self.fluid

    def add_species(self, name: str, diffusivity: Number | None = None, *,
                    stochastic: bool | None = None, initial: list[Initial] | None = None,
                    boundaries: list[Boundary] | None = None) -> Species:
        """A species (stochastic unless ``stochastic=False``); chain
        ``.add_initial(...)`` and ``.add_boundary(...)`` on the result."""
        s = Species(name=name, stochastic=stochastic, diffusivity=diffusivity, initial=initial,
                    boundaries=boundaries)
        self.species.append(s)
        return s

    def add_assigned_species(self, name: str, expression: str) -> Species:
        """An assigned species: ``expression`` of other species and parameters."""
        s = Species(name=name, assigned=expression)
        self.species.append(s)
        return s

    def set_parameter(self, name: str, value: Number) -> None:
        """A named constant that rate laws may use."""
        self.parameters[name] = value

    def add_reaction(self, equation: str | None = None, *, name: str | None = None,
                     rate: Value | None = None, reverse_rate: Value | None = None,
                     law: Law | None = None, kinds: list[str] | None = None,
                     regions: list[str] | None = None, reactants: dict | None = None,
                     products: dict | None = None) -> Reaction:
        """A reaction: mass action (``rate``, ``reverse_rate`` with ``<->``) or a
        ``law`` (MichaelisMenten, Hill, Expression)."""
        r = Reaction(name=name, equation=equation, reactants=reactants, products=products, rate=rate,
                     reverse_rate=reverse_rate, law=law, kinds=kinds, regions=regions)
        self.reactions.append(r)
        return r

    def add_boundary_flux(self, face: str | None, law: Law, *, species: str | None = None,
                          equation: str | None = None, region: str | None = None,
                          name: str | None = None, surface: str | None = None,
                          group: str | None = None) -> BoundaryFlux:
        """A flux through box face ``face`` (``x-`` ... ``z+``) with density ``law``; or, with
        ``face=None`` and ``surface``, through the surface of that fluid or solid body (only its
        physical group ``group`` of a mesh file, and only its part in ``region``, when given)."""
        f = BoundaryFlux(name=name, species=species, equation=equation, face=face,
                         surface=surface, region=region, law=law, group=group)
        self.boundary_fluxes.append(f)
        return f

    def set_time(self, coupling_step: Number, end: Number, splitting: str | None = None,
                 tolerance: Number | dict | None = None) -> Time:
        """The coupling step tau, the end time, the splitting (``lie``, ``strang``), and the
        tolerance that makes tau the first step of an error-controlled one (a number: relative;
        or ``{"relative": .., "absolute": .., "max_step": ..}``)."""
        self.time = Time(coupling_step, end, splitting, tolerance)
        return self.time

    def set_output(self, *, every: Number | None = None, times: list[Number] | None = None,
                   **keys: Any) -> Output:
        """Frame times (``every`` or ``times``) and the other ``output`` keys
        (formats, species, include_initial, checkpoint_every, vtk_encoding, directory)."""
        observables = keys.pop("observables", None)
        self.output = Output(every=every, times=times, **keys)
        for o in observables or []:
            self.output.observables = (self.output.observables or []) + [
                Observable.from_dict(o) if isinstance(o, dict) else o]
        return self.output

    def add_observable(self, name: str, species: str, region: str | None = None,
                       stat: str | None = None) -> Observable:
        """A named observable of the output (total or mean of a species over a region)."""
        if self.output is None:
            self.output = Output()
        o = Observable(name, species, region, stat)
        self.output.observables = (self.output.observables or []) + [o]
        return o

    def set_ssa(self, convention: str | None = None, regularization: Number | None = None,
                method: str | None = None, tolerance: Number | None = None) -> Ssa:
        """Options of the spatial SSA."""
        self.ssa = Ssa(convention, regularization, method, tolerance)
        return self.ssa

    # --- finding parts ----------------------------------------------------------

    def get_species(self, name: str) -> Species:
        return _named(self.species, name, "species")

    def get_reaction(self, name: str) -> Reaction:
        return _named(self.reactions, name, "reaction")

    def get_region(self, name: str) -> Region:
        return _named(self.regions, name, "region")

    def __getitem__(self, path: str) -> Any:
        """The value at a path of the scene (the syntax of ``sadr run --set``)."""
        return get_path(self.to_dict(), path)

    def set(self, path: str, value: Any) -> Model:
        """Sets the value at ``path`` (``reactions[decay].rate``, ``species[0].diffusivity``,
        ``fluid.sound_speed``: the syntax of ``sadr run --set``); returns the model.
        The parts are rebuilt: objects taken from the model before refer to the old ones."""
        data = self.to_dict()
        set_path(data, path, value)
        new = Model.from_dict(data, self.base_dir)
        self.__dict__.update(new.__dict__)
        return self

    __setitem__ = set

    # --- to and from a scene ------------------------------------------------------

    def to_dict(self) -> dict:
        """The scene as nested dicts and lists, in the scene format's key order."""
        out: dict = {}
        for key in _TOP:
            value = getattr(self, key)
            if value is None or (isinstance(value, (list, dict)) and not value):
                continue
            out[key] = _plain(value)
        out.update(_plain(self.extra))
        return out

    @classmethod
    def from_dict(cls, data: dict, base_dir: str | os.PathLike | None = None) -> Model:
        """A Model of a scene's data (``base_dir``: where its relative paths point from)."""
        if not isinstance(data, dict):
            raise TypeError(f"a scene is a mapping at the top level, not {type(data).__name__}")
        m = cls()
        for key, value in data.items():
            if key not in _TOP:
                m.extra[key] = value
                continue
            kind = _TOP_PARTS.get(key)
            if kind is not None and value is not None:
                value = _build(kind, value)
            if key in ("regions", "species", "reactions", "boundary_fluxes", "parameters") and value is None:
                continue
            setattr(m, key, value)
        m.base_dir = Path(base_dir).resolve() if base_dir is not None else None
        return m

    @classmethod
    def load(cls, path: str | os.PathLike) -> Model:
        """Reads a scene file (YAML numbers as the CLI reads them)."""
        path = Path(path)
        with open(path, encoding="utf-8") as f:
            data = load_yaml(f)
        return cls.from_dict(data if data is not None else {}, path.parent)

    def to_yaml(self, path: str | os.PathLike | None = None) -> str:
        """The scene as YAML text; relative file paths are written relative to
        ``path``'s folder (default: absolute)."""
        return dump_yaml(self._data_for(Path(path) if path is not None else None))

    def save(self, path: str | os.PathLike) -> Path:
        """Writes the scene file (creating its folder); returns the path. Later
        relative paths of the model point from its folder."""
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        data = self._data_for(path)
        path.write_text(dump_yaml(data), encoding="utf-8")
        for key, value, put in self._files():  # the model's relative paths now point from path's folder
            put(get_path(data, key))
        self.base_dir = path.parent.resolve()
        return path

    def _absolute(self, file: str | os.PathLike) -> Path:
        p = Path(file)
        if p.is_absolute():
            return p
        return ((self.base_dir or Path.cwd()) / p).resolve()

    def _files(self) -> list[tuple[str, Any, Any]]:
        """(path, value, setter) of the scene's file-valued keys: the setter puts a
        new value into the model's part."""
        data = self.to_dict()
        out = []
        setters = {"particles.file": lambda v: setattr(self.particles, "file", v),
                   "fluid.parameters.field_file": lambda v: self.fluid.parameters.__setitem__("field_file", v)}
        for path, put in setters.items():
            try:
                value = get_path(data, path)
            except KeyError:
                continue
            if isinstance(value, str):
                out.append((path, value, put))
        if isinstance(self.geometry, Geometry):
            for path, mesh in self.geometry.meshes():
                out.append((path, mesh.file, lambda v, mesh=mesh: setattr(mesh, "file", v)))
        return out

    def _data_for(self, target: Path | None) -> dict:
        data = self.to_dict()
        for path, value, _ in self._files():
            absolute = self._absolute(value)
            if target is None:
                set_path(data, path, str(absolute))
            else:
                set_path(data, path, os.path.relpath(absolute, target.parent.resolve()))
        return data

    def resolved(self) -> dict:
        """to_dict() with file paths absolute: what the scene means wherever it is written."""
        return self._data_for(None)

    # --- through the CLI ----------------------------------------------------------

    def validate(self, *, overrides: dict | None = None) -> str:
        """`sadr validate` on the scene written to a temporary file; returns its
        output (the plan). An invalid scene raises sadr.InvalidInput carrying
        the CLI's message verbatim (``message``, ``stderr``), and the YAML it
        read as ``scene_yaml`` (the message's line numbers are its lines)."""
        from .scene import set_options

        with tempfile.TemporaryDirectory(prefix="sadr-model-") as tmp:
            path = Path(tmp) / f"{_file_stem(self.name)}.yaml"
            text = self.to_yaml(path)
            path.write_text(text, encoding="utf-8")
            try:
                proc = run_cli(["validate", path] + set_options(overrides))
            except InvalidInput as e:
                e.scene_yaml = text
                raise
        return proc.stderr + proc.stdout

    def build_geometry(self, output: str | os.PathLike, *,
                       overrides: dict | None = None) -> GeometryBuild:
        """`sadr geometry` on the scene: writes it to ``OUTPUT/<name>.yaml`` (the
        model is not changed), the particles its ``geometry`` section makes to
        ``OUTPUT/particles.csv`` and ``particles.vtu``, and returns a
        sadr.geometry.GeometryBuild (the particles as a pandas DataFrame, the
        printed summary). A refusal raises sadr.InvalidInput carrying the CLI's
        message, with the YAML it read as ``scene_yaml``."""
        from .scene import set_options

        output = Path(output)
        output.mkdir(parents=True, exist_ok=True)
        path = output / f"{_file_stem(self.name)}.yaml"
        text = self.to_yaml(path)
        path.write_text(text, encoding="utf-8")
        try:
            proc = run_cli(["geometry", path, "--output", output] + set_options(overrides))
        except InvalidInput as e:
            e.scene_yaml = text
            raise
        return GeometryBuild(output, path, read_particles(output), proc.stdout, proc.stderr)

    def run(self, output: str | os.PathLike, *, realizations: int | None = None,
            realization: int | None = None, jobs: int | None = None,
            overrides: dict | None = None, client: Any = None, force: bool = True,
            quiet: bool = True, args: tuple = ()) -> Run | Ensemble:
        """Writes the scene to ``<output>.yaml`` and runs it: locally with `sadr
        run` (sadr.Scene.run: a sadr.Run, or a sadr.Ensemble for ``realizations``
        > 1), or, with a Dask ``client``, one task per realization
        (sadr.dask_runner.run_ensemble: a sadr.Ensemble). Failures raise the
        sadr.SadrError of the CLI's exit code with its message."""
        from .scene import Scene

        output = Path(output)
        scene_file = self.save(Path(str(output).rstrip("/") + ".yaml"))
        if client is not None:
            from . import dask_runner

            if overrides or realization is not None or jobs is not None or args:
                raise ValueError("run(client=...): overrides, realization, jobs and args are for "
                                 "local runs; edit the model instead")
            return dask_runner.run_ensemble(scene_file, output, realizations or 1, client)
        return Scene.load(scene_file).run(output, realizations=realizations, realization=realization,
                                          jobs=jobs, overrides=overrides, force=force, quiet=quiet,
                                          args=args)


def _named(items: list, name: str, what: str):
    for item in items:
        if item.name == name:
            return item
    names = ", ".join(str(i.name) for i in items if i.name is not None) or "none"
    raise KeyError(f"no {what} named '{name}' (names: {names})")


def _file_stem(name: str | None) -> str:
    keep = "".join(c if c.isalnum() or c in "_.-" else "_" for c in (name or "scene"))
    return keep.lstrip(".-") or "scene"
