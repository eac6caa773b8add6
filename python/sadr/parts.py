# SPDX-License-Identifier: MIT
"""The building blocks of sadr.Model and sadr.geometry: a piece of a scene
is a dataclass whose fields are the scene's keys, in the scene format's
order, so a key is named once, in one field (the tests compare the fields
with the scene loader's key lists). ``None`` is a key that is not written
(the product's default applies); ``extra`` holds keys this package does not
know, passed on so that the CLI names them."""
from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any, ClassVar


class Written:
    """Anything that writes itself as a piece of a scene (``to_dict``)."""

    def to_dict(self) -> dict:  # pragma: no cover - every subclass defines it
        raise NotImplementedError


class Part(Written):
    """A dataclass piece of a scene: fields in the scene's key order, ``None``
    for a key that is not written, ``extra`` for keys this package does not
    know; ``_nested`` maps a key to the class of its value ([cls]: a list)."""

    _nested: ClassVar[dict[str, Any]] = {}

    def to_dict(self) -> dict:
        out: dict = {}
        for f in dataclasses.fields(self):
            if f.name == "extra":
                continue
            value = getattr(self, f.name)
            if value is None:
                continue
            out[f.name] = plain(value)
        out.update(plain(getattr(self, "extra", {}) or {}))
        return out

    @classmethod
    def keys(cls) -> list[str]:
        """The scene keys this part takes (its fields but ``extra``)."""
        return [f.name for f in dataclasses.fields(cls) if f.name != "extra"]

    @classmethod
    def from_dict(cls, data: dict):
        if not isinstance(data, dict):
            raise TypeError(f"{cls.__name__}: expected a mapping, got {data!r}")
        names = set(cls.keys())
        kwargs: dict = {}
        extra: dict = {}
        for key, value in data.items():
            if key in names:
                kind = cls._nested.get(key)
                kwargs[key] = build(kind, value) if kind is not None and value is not None else value
            else:
                extra[key] = value
        obj = cls(**kwargs)
        obj.extra = extra
        return obj


def plain(value: Any) -> Any:
    """``value`` as plain dicts, lists and numbers, as YAML writes them."""
    if isinstance(value, Written):
        return value.to_dict()
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, Path):
        return str(value)
    if hasattr(value, "tolist"):  # numpy scalars and arrays
        return value.tolist()
    return value


def build(kind: Any, value: Any) -> Any:
    """``value`` read into ``kind``: a class with ``from_dict``, or [class] for
    a list of them; what is not a mapping is kept as written (the CLI says
    what is wrong with it)."""
    if isinstance(kind, list):
        if not isinstance(value, list):
            return value
        return [build(kind[0], v) for v in value]
    return kind.from_dict(value) if isinstance(value, dict) else value
