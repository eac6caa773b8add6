# SPDX-License-Identifier: MIT
"""Scene files in Python: load a YAML scene, change keys, write it, and
validate or run it through the `sadr` CLI (docs/scene-format.md has every key).

    scene = sadr.Scene.load("examples/poiseuille_tracer_2d.yaml")
    scene["time.end"] = 1.0                  # paths as for `sadr run --set`
    scene["species[0].diffusivity"] = 2e-3   # list items by index or by name
    scene["reactions[decay_A].rate"] = 2.0
    run = scene.run("runs/short")            # a sadr.Run (or Ensemble with realizations=R)

Comments of the original file are not kept (PyYAML); the values are.
"""
from __future__ import annotations

import copy
import os
import re
import tempfile
import warnings
from pathlib import Path
from typing import Any

from .cli import run_cli
from .paths import PathError, dump_yaml, get_path, load_yaml, override_text, set_path
from .runs import Ensemble, Run


def set_options(overrides: dict | None) -> list[str]:
    """``--set PATH=VALUE`` options for the CLI, each value written as flow YAML
    (paths in the syntax of sadr.paths, checked before the CLI runs)."""
    out: list[str] = []
    for path, value in (overrides or {}).items():
        out += ["--set", override_text(path, value)]
    return out


_LEGACY_INDEX = re.compile(r"\.(\d+)(?=\.|$)")


def _path(key: str) -> str:
    """``key`` in the --set syntax; the older ``species.0.name`` (an index
    as a dotted segment) still works, with a DeprecationWarning."""
    new = _LEGACY_INDEX.sub(r"[\1]", key)
    if new != key:
        warnings.warn(f"scene key '{key}': write '{new}' (the syntax of sadr run --set)",
                      DeprecationWarning, stacklevel=3)
    return new


class Scene:
    """A scene as nested dicts and lists (``.data``) plus where it came from."""

    def __init__(self, data: dict, path: str | os.PathLike | None = None):
        if not isinstance(data, dict):
            raise TypeError(f"a scene is a mapping at the top level, not {type(data).__name__}")
        self.data = data
        self.path = Path(path) if path else None
        self._written = dump_yaml(data) if path else None

    @classmethod
    def load(cls, path: str | os.PathLike) -> Scene:
        path = Path(path)
        with open(path, encoding="utf-8") as f:
            data = load_yaml(f)
        return cls(data, path)

    def __repr__(self):
        return f"sadr.Scene('{self.data.get('name', '')}', path={str(self.path) if self.path else None})"

    def copy(self) -> Scene:
        """A deep copy (same source path: relative paths keep resolving)."""
        s = Scene(copy.deepcopy(self.data))
        s.path, s._written = self.path, None
        return s

    def __getitem__(self, key: str) -> Any:
        try:
            return get_path(self.data, _path(key))
        except PathError as e:
            raise PathError(f"scene has no '{key}': {e}") from None

    def __setitem__(self, key: str, value: Any) -> None:
        try:
            set_path(self.data, _path(key), value)
        except PathError as e:
            raise PathError(f"cannot set '{key}': {e}") from None

    def __contains__(self, key: str) -> bool:
        try:
            get_path(self.data, _path(key))
            return True
        except PathError:
            return False

    def _data_for(self, target: Path) -> dict:
        """The data with a relative particles.file re-anchored for a file at ``target``."""
        data = copy.deepcopy(self.data)
        file = (data.get("particles") or {}).get("file")
        if file and self.path and not Path(file).is_absolute():
            src = (self.path.parent / file).resolve()
            try:
                data["particles"]["file"] = str(src.relative_to(target.parent.resolve()))
            except ValueError:
                data["particles"]["file"] = str(src)
        return data

    def write(self, path: str | os.PathLike) -> Path:
        """Writes the scene as YAML; a relative ``particles.file`` is rewritten
        so that it still names the same file. Returns the path."""
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        data = self._data_for(path)
        with open(path, "w", encoding="utf-8") as f:
            dump_yaml(data, f)
        self.data, self.path, self._written = data, path, dump_yaml(data)
        return path

    def _file(self, output: Path | None = None) -> Path:
        """A file holding the current data: the source if unchanged, else
        ``<output>.yaml`` next to the output folder."""
        if self.path and self._written == dump_yaml(self.data):
            return self.path
        if output is None:
            raise ValueError("the scene changed since it was loaded or written: write() it first")
        return self.write(Path(str(output).rstrip("/") + ".yaml"))

    def validate(self) -> str:
        """`sadr validate`; returns its output (the plan). A scene changed since
        it was loaded or written is validated from a temporary copy. Invalid:
        sadr.InvalidInput with the validator's file:line:column message."""
        if self.path and self._written == dump_yaml(self.data):
            proc = run_cli(["validate", self.path])
            return proc.stderr + proc.stdout
        with tempfile.TemporaryDirectory(prefix="sadr-scene-") as tmp:
            path = Path(tmp) / f"{self.data.get('name', 'scene')}.yaml"
            with open(path, "w", encoding="utf-8") as f:
                dump_yaml(self._data_for(path), f)
            proc = run_cli(["validate", path])
        return proc.stderr + proc.stdout

    def run(self, output: str | os.PathLike, *, realizations: int | None = None, realization: int | None = None,
            jobs: int | None = None, overrides: dict | None = None, force: bool = True,
            quiet: bool = True, args=()) -> Run | Ensemble:
        """`sadr run` into ``output``; returns a sadr.Run (one realization) or
        sadr.Ensemble (``realizations`` R > 1, or ``realization`` i: only
        ``output/realization_iiii``). A changed scene is first written to
        ``<output>.yaml``. ``overrides`` {path: value} become ``--set
        path=value`` (docs/cli.md: ``reactions[decay].rate``, values as YAML;
        run.json records them). Failures raise the sadr.SadrError of the exit code."""
        output = Path(output)
        cmd = ["run", self._file(output), "--output", output] + set_options(overrides)
        if realizations is not None:
            cmd += ["--realizations", realizations]
        if realization is not None:
            cmd += ["--realization", realization]
        if jobs is not None:
            cmd += ["--jobs", jobs]
        if force and realization is None:
            cmd.append("--force")
        if quiet:
            cmd.append("--quiet")
        run_cli(cmd + list(args))
        if realization is not None:
            return Run(output / f"realization_{realization:04d}")
        return Ensemble(output) if realizations and realizations > 1 else Run(output)
