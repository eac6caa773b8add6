# SPDX-License-Identifier: MIT
"""Paths into a scene, in the one syntax of ``sadr run --set PATH=VALUE``
(docs/cli.md), used everywhere in this package (``Scene[...]``,
``Model.set``, ``overrides=`` of every run function):

    fluid.sound_speed              a key of a map
    reactions[annihilation].rate   a list item by its ``name``
    species[0].diffusivity         a list item by its 0-based index

Segments are separated by '.'; a selector ``[...]`` follows a key. Setting a
path adds missing map keys, as the CLI does; a missing list item is an error.
The rules mirror the CLI's (orchestrator/scene/src/scene_override.cpp): a
selector made of at most 9 digits is an index, anything else a name.

Also the YAML reading and writing of scenes: numbers as YAML 1.2 reads them
(``1e-3`` is a number, as for the CLI's yaml-cpp, not the string PyYAML's
YAML 1.1 rules make of it).
"""
from __future__ import annotations

import re
from typing import Any, NamedTuple

import yaml


class Step(NamedTuple):
    """One segment of a path: a map key, or a list selector (``[name]``/``[index]``)."""

    text: str
    selector: bool


class PathError(KeyError):
    """A path that does not parse, or does not lead anywhere in the data."""

    def __str__(self) -> str:  # KeyError quotes its argument; this is a message
        return str(self.args[0]) if self.args else ""


_HINT = "PATH like fluid.sound_speed, reactions[annihilation].rate or species[0].diffusivity"


def is_index(text: str) -> bool:
    """A selector that is an index: 1 to 9 digits (the CLI's rule)."""
    return 0 < len(text) <= 9 and text.isdigit()


def split_path(path: str) -> list[Step]:
    """The steps of ``path``; raises PathError naming what is wrong."""
    def fail(why: str):
        raise PathError(f"path '{path}': {why} ({_HINT})")

    steps: list[Step] = []
    i, need_key = 0, True
    while i < len(path):
        c = path[i]
        if c == "[":
            close = path.find("]", i)
            if close < 0:
                fail("'[' without ']'")
            if not steps:
                fail("a path starts with a key, not '['")
            sel = path[i + 1:close]
            if not sel:
                fail("empty '[]'")
            steps.append(Step(sel, True))
            i, need_key = close + 1, False
            continue
        if c == ".":
            if need_key:
                fail("empty key")
            i, need_key = i + 1, True
            continue
        if not need_key:
            fail("expected '.' or '[' after ']'")
        m = re.compile(r"[^.\[\]]+").match(path, i)
        if not m:
            fail("unexpected ']'")
        steps.append(Step(m.group(0), False))
        i, need_key = m.end(), False
    if not steps or need_key:
        fail("empty path or trailing '.'")
    return steps


def _select(node: Any, step: Step, where: str, path: str) -> int:
    """The list index a selector step picks in ``node``."""
    if not isinstance(node, list):
        raise PathError(f"path '{path}': {where} is not a list (selector [{step.text}])")
    if is_index(step.text):
        k = int(step.text)
        if k >= len(node):
            raise PathError(f"path '{path}': index {k} is out of range: {where} has {len(node)} items")
        return k
    names = [item.get("name") for item in node if isinstance(item, dict)]
    for k, item in enumerate(node):
        if isinstance(item, dict) and item.get("name") == step.text:
            return k
    listed = ", ".join(str(n) for n in names if n is not None) or "its items have no names"
    raise PathError(f"path '{path}': no item named '{step.text}' in {where} ({listed})")


def get_path(data: Any, path: str) -> Any:
    """The value at ``path`` in nested dicts and lists; PathError if absent."""
    node, where = data, "the scene"
    for step in split_path(path):
        if step.selector:
            node = node[_select(node, step, where, path)]
            where = f"'{where}[{step.text}]'"
        else:
            if not isinstance(node, dict) or step.text not in node:
                raise PathError(f"path '{path}': no key '{step.text}' in {where}")
            node = node[step.text]
            where = f"'{step.text}'"
    return node


def set_path(data: dict, path: str, value: Any) -> None:
    """Sets the value at ``path`` as ``sadr run --set`` does: missing map keys
    are added, list items must exist (by name or index)."""
    steps = split_path(path)
    node, where = data, "the scene"
    for k, step in enumerate(steps):
        last = k + 1 == len(steps)
        if step.selector:
            index = _select(node, step, where, path)
            if last:
                node[index] = value
            else:
                node = node[index]
            where = f"'{step.text}'"
            continue
        if not isinstance(node, dict):
            raise PathError(f"path '{path}': {where} is not a map with key '{step.text}'")
        if last:
            node[step.text] = value
        else:
            if node.get(step.text) is None:
                node[step.text] = {}
            node = node[step.text]
        where = f"'{step.text}'"


def override_text(path: str, value: Any) -> str:
    """``PATH=VALUE`` for ``--set``, the value as one line of flow YAML."""
    split_path(path)  # syntax check before the CLI sees it
    text = yaml.safe_dump(value, default_flow_style=True, width=1 << 30, allow_unicode=True).strip()
    if text.endswith("\n..."):
        text = text[: -len("\n...")]
    return f"{path}={text}"


# --- YAML as the CLI reads it -------------------------------------------------

class SceneLoader(yaml.SafeLoader):
    """PyYAML's safe loader with YAML 1.2 floats: ``1e-3``, ``5E+2`` are numbers."""


SceneLoader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?
                   |[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)
                   |\.[0-9_]+(?:[eE][-+]?[0-9]+)?
                   |[-+]?\.(?:inf|Inf|INF)
                   |\.(?:nan|NaN|NAN))$""", re.X),
    list("-+0123456789."))


def load_yaml(text_or_stream) -> Any:
    """A scene's YAML as nested dicts and lists (numbers as the CLI reads them)."""
    return yaml.load(text_or_stream, Loader=SceneLoader)  # noqa: S506 - a SafeLoader subclass


def dump_yaml(data: Any, stream=None) -> str | None:
    """Block YAML, keys in their order, unicode kept (``∅`` in equations)."""
    return yaml.safe_dump(data, stream, sort_keys=False, allow_unicode=True, width=100)
