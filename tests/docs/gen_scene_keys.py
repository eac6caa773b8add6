#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Writes docs/reference/scene-keys.md from the scene loader's key tables, or checks it.

    gen_scene_keys.py [--check]

The scene loader (orchestrator/scene/src/scene*.cpp) refuses every key that is not in
the table of its section (`kSpeciesKeys`, `kFluidKeys`, ...). This page lists those
tables as they are in the code, each with its source line. With --check it fails
when the page differs from what the code gives, or when a key of a table is not
documented in docs/scene-format.md (written there as `key`).
"""
import argparse
import difflib
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "reference" / "scene-keys.md"
# table name -> where the keys go in a scene (the YAML path of the section)
SECTIONS = [
    ("TopKeys", "top level"),
    ("RegionKeys", "regions[]"),
    ("ParticleKeys", "particles"),
    ("FillKeys", "particles.fill[]"),
    ("GeometryKeys", "geometry"),
    ("RelaxKeys", "geometry.relax"),
    ("BodyKeys", "geometry.bodies[]"),
    ("MotionKeys", "geometry.bodies[].motion"),
    ("ShapeKeys", "geometry.bodies[].shape (and every nested shape)"),
    ("RotateKeys", "geometry.bodies[].shape.rotate (3D)"),
    ("FluidKeys", "fluid"),
    ("PlaneKeys", "fluid.wall_planes[]"),
    ("OpenKeys", "fluid.open_boundary"),
    ("BoussinesqKeys", "fluid.boussinesq"),
    ("SpeciesKeys", "species[]"),
    ("InitialKeys", "species[].initial[]"),
    ("BoundaryKeys", "species[].boundaries[]"),
    ("ReactionKeys", "reactions[]"),
    ("MichaelisKeys", "reactions[].law (type: michaelis_menten)"),
    ("HillKeys", "reactions[].law (type: hill)"),
    ("ExpressionKeys", "reactions[].law (type: expression)"),
    ("FluxKeys", "boundary_fluxes[]"),
    ("TimeKeys", "time"),
    ("ToleranceKeys", "time.tolerance (the map form)"),
    ("OutputKeys", "output"),
    ("ObservableKeys", "output.observables[]"),
]


def tables():
    """{name: (keys, "file:line")} of every `kNameKeys{...}` in the loader's sources."""
    out = {}
    for path in sorted((ROOT / "orchestrator" / "scene" / "src").glob("scene*.cpp")):
        text = path.read_text()
        for m in re.finditer(r"k(\w+Keys)\{([^}]*)\}", text):
            line = text.count("\n", 0, m.start()) + 1
            out[m.group(1)] = (re.findall(r'"([^"]+)"', m.group(2)),
                               f"{path.relative_to(ROOT)}:{line}")
    return out


def page():
    t = tables()
    lines = ["# Scene keys (generated)", "",
             "Every key the scene loader accepts, section by section, as the code lists it",
             "(`tests/docs/gen_scene_keys.py` writes this page from the loader's key tables; a",
             "test fails when it drifts). Any other key is refused with the nearest allowed",
             "one. What each key means, its unit, default and range:",
             "[the scene format](../scene-format.md). A backend's own `fluid.parameters` are",
             "listed by `sadr backends` and in the scene format's backend tables.", "",
             "| section | keys | defined in |", "|---|---|---|"]
    for name, where in SECTIONS:
        keys, src = t[name]
        lines.append(f"| `{where}` | " + ", ".join(f"`{k}`" for k in keys) + f" | `{src.split(':')[0]}` |")
    return "\n".join(lines) + "\n"


def undocumented():
    doc = (ROOT / "docs" / "scene-format.md").read_text()
    missing = []
    for name, where in SECTIONS:
        for k in tables()[name][0]:
            if f"`{k}`" not in doc:
                missing.append(f"{where}: {k}")
    return missing


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    text = page()
    if not a.check:
        PAGE.write_text(text)
        print(f"wrote {PAGE}")
        return 0
    ok = True
    if PAGE.read_text() != text:
        ok = False
        sys.stdout.writelines(difflib.unified_diff(PAGE.read_text().splitlines(True),
                                                   text.splitlines(True), str(PAGE), "from the code"))
        print(f"{PAGE}: differs from the loader's key tables; run tests/docs/gen_scene_keys.py")
    missing = undocumented()
    if missing:
        ok = False
        print("keys the loader accepts that docs/scene-format.md does not name:")
        for m in missing:
            print("  " + m)
    if ok:
        print(f"{PAGE}: up to date; every key is documented in docs/scene-format.md")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
