# SPDX-License-Identifier: MIT
"""Sweep files (docs/sweeps.md, "The sweep file") built in Python: a base
scene (a file, or a sadr.Model written next to the sweep file), the points
(``grid``, ``zip`` or explicit ``points`` of ``--set`` paths), realizations,
seed, executor, retries, keep and output::

    sw = sadr.SweepFile(model, realizations=8, seed=2024, output="sweeps/decay")
    sw.add_grid("reactions[decay].rate", [0.5, 1.0, 2.0])
    sw.executor = sadr.sweep_file.Executor("local", workers=2)
    sw.save("decay.yaml", scene_file="disk.yaml")   # writes disk.yaml too
    print(sw.dry_run())                              # `sadr sweep --dry-run`: every point checked
    result = sw.run()                                # `sadr sweep`: a sadr.Sweep

As for sadr.Model, the fields are the file's keys (python_model compares them
with the sweep loader's lists) and nothing is checked here: the CLI refuses,
and sadr.InvalidInput carries its message.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Union

from .cli import run_cli
from .parts import Part
from .paths import dump_yaml, load_yaml

if TYPE_CHECKING:
    from .model import Model
    from .sweeps import Sweep


@dataclass
class Executor(Part):
    """``executor``: ``local`` (``workers``) or ``slurm`` (``cpus_per_task``,
    ``partition``, ``sbatch_args``, ``poll_seconds``)."""

    type: str | None = None
    workers: int | None = None
    cpus_per_task: int | None = None
    partition: str | None = None
    sbatch_args: list[str] | None = None
    poll_seconds: float | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class Parameters(Part):
    """``parameters``: ``grid`` (every combination, the last path fastest) and
    ``zip`` (lists taken together), or explicit ``points`` (each a {path: value})."""

    grid: dict | None = None
    zip: dict | None = None
    points: list[dict] | None = None
    extra: dict = field(default_factory=dict)


@dataclass
class SweepFile(Part):
    """A sweep file. ``scene``: the base scene's path (relative: from ``base_dir``,
    the loaded file's folder, else the working directory) or a sadr.Model."""

    scene: Union[str, Model, None] = None
    realizations: int | None = None
    seed: int | None = None
    parameters: Parameters | None = None
    executor: Union[Executor, str, None] = None
    retries: int | None = None
    keep: str | None = None
    output: str | None = None
    extra: dict = field(default_factory=dict)
    _nested: ClassVar[dict[str, Any]] = {"parameters": Parameters, "executor": Executor}

    def __post_init__(self) -> None:
        self.base_dir: Path | None = None
        self.path: Path | None = None

    def _parameters(self) -> Parameters:
        if self.parameters is None:
            self.parameters = Parameters()
        return self.parameters

    def add_grid(self, path: str, values: list) -> SweepFile:
        """A ``grid`` parameter: ``path`` (``--set`` syntax) takes each of ``values``."""
        p = self._parameters()
        p.grid = {**(p.grid or {}), path: list(values)}
        return self

    def add_zip(self, path: str, values: list) -> SweepFile:
        """A ``zip`` parameter (all zip lists have one length and go together)."""
        p = self._parameters()
        p.zip = {**(p.zip or {}), path: list(values)}
        return self

    def add_point(self, values: dict) -> SweepFile:
        """An explicit point: {path: value}."""
        p = self._parameters()
        p.points = (p.points or []) + [dict(values)]
        return self

    def to_dict(self, scene_path: str | None = None) -> dict:
        """The file's mapping; ``scene_path`` stands for a Model scene."""
        out = super().to_dict()
        from .model import Model

        if isinstance(self.scene, Model):
            out["scene"] = scene_path if scene_path is not None else "(a sadr.Model: save() writes it)"
        elif isinstance(self.scene, os.PathLike):
            out["scene"] = str(self.scene)
        return out

    @classmethod
    def load(cls, path: str | os.PathLike) -> SweepFile:
        """Reads a sweep file (its ``scene`` stays a path)."""
        path = Path(path)
        with open(path, encoding="utf-8") as f:
            data = load_yaml(f)
        sw = cls.from_dict(data if data is not None else {})
        sw.base_dir, sw.path = path.parent.resolve(), path
        return sw

    def save(self, path: str | os.PathLike, *, scene_file: str | os.PathLike | None = None) -> Path:
        """Writes the sweep file (and, for a Model scene, the scene: to
        ``scene_file``, relative to the sweep file's folder, default
        ``<sweep stem>_scene.yaml``); a scene path is written relative to the
        sweep file. Returns the path."""
        from .model import Model

        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        scene_path = None
        if isinstance(self.scene, Model):
            target = path.parent / (scene_file or f"{path.stem}_scene.yaml")
            self.scene.save(target)
            scene_path = os.path.relpath(target.resolve(), path.parent.resolve())
        elif isinstance(self.scene, (str, os.PathLike)):
            source = Path(self.scene)
            if not source.is_absolute():
                source = (self.base_dir or Path.cwd()) / source
            scene_path = os.path.relpath(source.resolve(), path.parent.resolve())
        path.write_text(dump_yaml(self.to_dict(scene_path)), encoding="utf-8")
        if not isinstance(self.scene, Model) and scene_path is not None:
            self.scene = scene_path
        self.base_dir, self.path = path.parent.resolve(), path
        return path

    def _file(self) -> Path:
        if self.path is None:
            raise ValueError("save() the sweep file first: its scene and output are relative to it")
        return self.path

    def dry_run(self, *, output: str | os.PathLike | None = None) -> str:
        """`sadr sweep FILE --dry-run`: every point's scene loaded and checked,
        the points and runs listed; returns what it printed. A refusal raises
        sadr.InvalidInput with the CLI's message."""
        cmd: list = ["sweep", self._file(), "--dry-run"]
        if output is not None:
            cmd += ["--output", output]
        proc = run_cli(cmd)
        return proc.stderr + proc.stdout

    def run(self, output: str | os.PathLike | None = None, *, workers: int | None = None,
            force: bool = False) -> Sweep:
        """`sadr sweep FILE` (into ``output``, else the file's ``output``);
        returns the sadr.Sweep it wrote."""
        from .sweeps import Sweep

        cmd: list = ["sweep", self._file()]
        if output is not None:
            cmd += ["--output", output]
        if workers is not None:
            cmd += ["--workers", workers]
        if force:
            cmd.append("--force")
        run_cli(cmd, cwd=None)
        if output is None:
            output = self.output if self.output is not None else f"sweeps/{self._file().stem}"
        return Sweep(output)
