# SPDX-License-Identifier: MIT
"""sadr.geometry: the geometry section built in Python has the scene
loader's keys, writes what the examples write (same scene meaning), chains
transforms and CSG as written, builds particles through `sadr geometry`,
re-bases mesh files, carries the CLI's refusals, and plot-geometry draws
every particle it made."""
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import sadr
from conftest import EXAMPLES, REPO
from sadr import geometry as g
from sadr.paths import load_yaml


def cpp_arrays(text):
    """name -> the strings of every `kName{...}` array of a C++ source."""
    return {m[0]: re.findall(r'"([^"]+)"', m[1]) for m in re.findall(r"k(\w+)\{([^}]*)\}", text)}


def test_the_classes_have_the_loaders_keys():
    """Every key of the geometry section is a field of one class, as the scene
    loader (orchestrator/scene/src/scene_geometry*.cpp) lists them."""
    src = "\n".join(p.read_text() for p in
                    sorted((REPO / "orchestrator" / "scene" / "src").glob("scene_geometry*.cpp")))
    arrays = cpp_arrays(src)
    assert set(arrays["GeometryKeys"]) == set(g.Geometry.keys())
    assert set(arrays["BodyKeys"]) == set(g.Body.keys())
    assert set(arrays["RelaxKeys"]) == set(g.Relax.keys())
    assert set(arrays["Roles"]) == set(g.ROLES)
    assert set(arrays["ShapeTypes"]) == set(g.SHAPES)
    assert arrays["RotateKeys"] == list(g.Sphere([0, 0, 0], 1).rotate(10, axis=[0, 0, 1]).to_dict()["rotate"])
    # each type's own keys: the loader's type_keys()
    body = src[src.index("std::vector<std::string_view> type_keys"):]
    body = body[:body.index("\n}\n")]
    per_type = {}
    for types, keys in re.findall(r"if \(([^)]*)\) return \{([^}]*)\};", body):
        for t in re.findall(r'type == "(\w+)"', types):
            per_type[t] = re.findall(r'"(\w+)"', keys)
    for t in ("union", "intersection", "difference"):
        per_type[t] = re.findall(r'"(\w+)"', re.search(r"\n  return \{([^}]*)\};", body).group(1))
    assert set(per_type) == set(g.SHAPES)
    for t, cls in g.SHAPES.items():
        assert cls.keys() == per_type[t], t
    # and together with type and the transforms, the shape keys (in the loader's order)
    assert arrays["ShapeKeys"][-3:] == ["translate", "rotate", "scale"]
    assert set(arrays["ShapeKeys"]) == {"type", *g.TRANSFORMS} | {k for c in g.SHAPES.values() for k in c.keys()}
    assert list(g.TRANSFORMS) == ["scale", "rotate", "translate"]  # the order docs/scene-format.md gives


def test_transforms_chain_in_the_order_written():
    s = g.Sphere([0, 0, 0], 1).scale(2).rotate(30, axis=[0, 0, 1]).translate([1, 0, 0])
    assert s.to_dict() == {"type": "sphere", "center": [0, 0, 0], "radius": 1, "scale": 2,
                           "rotate": {"axis": [0, 0, 1], "angle": 30}, "translate": [1, 0, 0]}
    d = g.Disk([0, 0], 1)
    moved = d.translate([1, 1])
    assert d.to_dict() == {"type": "disk", "center": [0, 0], "radius": 1}  # a copy: d unchanged
    # scaling after translating: the scene would scale first, so the shape is wrapped
    assert moved.scale(2).to_dict() == {"type": "union", "shapes": [moved.to_dict()], "scale": 2}
    assert moved.translate([0, 1]).to_dict() == {"type": "union", "shapes": [moved.to_dict()],
                                                 "translate": [0, 1]}
    assert d.rotate(45).to_dict()["rotate"] == 45  # 2D: an angle


def test_csg_operators():
    a, b, c = g.Box([0, 0], [1, 1]), g.Disk([0, 0], 1), g.Ellipse([0, 0], [1, 2])
    u = a | b | c
    assert isinstance(u, g.Union) and u.to_dict() == g.union(a, b, c).to_dict()
    assert len(u.shapes) == 3
    assert (a & b).to_dict() == {"type": "intersection", "shapes": [a.to_dict(), b.to_dict()]}
    diff = a - b - c
    assert diff.to_dict() == {"type": "difference", "shapes": [a.to_dict(), b.to_dict(), c.to_dict()]}
    assert (a - (b | c)).to_dict()["shapes"][1]["type"] == "union"  # a - (b | c) is not a - b | c
    nested = (a | b).translate([1, 0]) | c  # a transformed union is not flattened
    assert nested.to_dict()["shapes"][0]["translate"] == [1, 0]
    assert g.Shape.from_dict(diff.to_dict()) == diff and isinstance(g.Shape.from_dict(diff.to_dict()), g.Difference)


def cell_geometry_2d():
    """examples/cell_in_channel_geometry_2d.yaml's geometry section, written in Python."""
    geo = g.Geometry(spacing=0.05, lattice="cubic")
    geo.add_fluid("channel", g.Box([-1.0, 0.0], [3.0, 1.0]))
    geo.add_solid("cell", g.Ellipse([0.7, 0.5], [0.2, 0.15]), wall_layer="membrane", fluid_layer="near_cell")
    return geo


def yeast_geometry_3d():
    geo = g.Geometry(spacing=0.1, lattice="cubic")
    geo.add_fluid("duct", g.Box([-1.0, 0.0, 0.0], [3.0, 1.2, 1.2]))
    geo.add_solid("yeast", g.Ellipsoid([0.7, 0.6, 0.6], [0.3, 0.25, 0.25]) | g.Sphere([1.08, 0.6, 0.6], 0.18),
                  wall_layer="membrane", fluid_layer="near_yeast")
    return geo


@pytest.mark.parametrize("name,build", [("cell_in_channel_geometry_2d.yaml", cell_geometry_2d),
                                        ("yeast_cell_channel_geometry_3d.yaml", yeast_geometry_3d)])
def test_examples_built_in_python(tmp_path, name, build):
    """The examples' geometry built in Python: the same section, and the same
    scene meaning hash from `sadr validate`; loading keeps it as objects."""
    example = load_yaml((EXAMPLES / name).read_text())
    loaded = sadr.Model.load(EXAMPLES / name)
    assert isinstance(loaded.geometry, g.Geometry) and isinstance(loaded.geometry.bodies[1].shape, g.Shape)
    m = loaded.copy()
    m.geometry = build()
    assert m.to_dict()["geometry"] == example["geometry"]
    assert m.to_dict() == example
    path = m.save(tmp_path / name)
    hashes = [re.search(r"scene meaning (fnv1a64:\w+)", sadr.run_cli(["validate", p]).stderr).group(1)
              for p in (path, EXAMPLES / name)]
    assert hashes[0] == hashes[1]


def test_build_returns_the_particles_and_the_summary(tmp_path):
    m = sadr.Model.load(EXAMPLES / "cell_in_channel_geometry_2d.yaml")
    built = m.build_geometry(tmp_path / "geo")
    assert (tmp_path / "geo" / "particles.vtu").is_file() and built.scene_file.is_file()
    p = built.particles
    counts = built.counts()
    assert counts == {"fluid": 764, "wall": 276}  # the example's header
    total = re.search(r"particles: (\d+) \(fluid (\d+), wall (\d+)\)", built.summary).groups()
    assert [int(x) for x in total] == [len(p), counts["fluid"], counts["wall"]]
    assert {"channel", "cell", "membrane", "near_cell", "inlet"} <= set(built.regions)
    said = dict(re.findall(r" (\w+) (\d+)", built.summary.split("regions:")[1].splitlines()[0]))
    for name in built.regions:
        assert int(said[name]) == len(built.region(name)), name
    membrane = built.region("membrane")
    assert len(membrane) > 0 and (membrane["kind"] == 1).all()
    centre = np.hypot((membrane["x"] - 0.7) / 0.2, (membrane["y"] - 0.5) / 0.15)
    assert centre.max() < 1.0  # inside the ellipse: wall particles behind its outline
    assert p["id"].dtype == np.uint64 and np.isclose(p.loc[p["kind"] == 0, "mass"].sum(), 2 - np.pi * 0.2 * 0.15)
    # Geometry.build: the section on another scene's box and fluid, the model unchanged
    geo = cell_geometry_2d()
    geo.bodies[1].shape = g.Disk([0.7, 0.5], 0.2)
    again = geo.build(tmp_path / "disk", m)
    assert m.geometry.bodies[1].shape == g.Ellipse([0.7, 0.5], [0.2, 0.15])
    assert again.counts()["fluid"] < counts["fluid"]  # a larger solid, fewer fluid particles
    with pytest.raises(KeyError, match="no region 'nucleus'.*membrane"):
        built.region("nucleus")


def cube_stl(path, lo, hi):
    """An ASCII STL of an axis-aligned cube (12 triangles, outward normals)."""
    corners = [[(lo, hi)[(k >> a) & 1] for a in range(3)] for k in range(8)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    lines = ["solid cube"]
    for q in quads:
        for tri in ((q[0], q[1], q[2]), (q[0], q[2], q[3])):
            lines += ["facet normal 0 0 0", "outer loop"]
            lines += [f"vertex {corners[v][0]} {corners[v][1]} {corners[v][2]}" for v in tri]
            lines += ["endloop", "endfacet"]
    path.write_text("\n".join(lines + ["endsolid cube"]) + "\n")


def test_a_mesh_file_is_rebased_and_read(tmp_path, monkeypatch):
    """A relative mesh path is taken from the working directory (or the loaded
    file's folder) and written relative to wherever the scene is saved."""
    (tmp_path / "meshes").mkdir()
    cube_stl(tmp_path / "meshes" / "cube.stl", 0.35, 0.65)
    monkeypatch.chdir(tmp_path)
    m = sadr.Model("cube", dimension=3, seed=1)
    m.set_box([0, 0, 0], [1, 1, 1])
    geo = m.set_geometry(0.1)
    geo.add_solid("cube", g.Mesh("meshes/cube.stl"), wall_layer="skin")
    geo.add_region("middle", g.Box([0.2, 0.2, 0.2], [0.8, 0.8, 0.8]) - g.Mesh("meshes/cube.stl"), kinds=["fluid"])
    m.set_fluid("static", h_over_dx=2.0)
    m.add_species("A", diffusivity=0.0)
    m.set_time(0.1, 0.1)
    path = m.save(tmp_path / "deep" / "scene.yaml")
    data = load_yaml(path.read_text())
    assert data["geometry"]["bodies"][0]["shape"]["file"] == "../meshes/cube.stl"
    assert data["geometry"]["bodies"][1]["shape"]["shapes"][1]["file"] == "../meshes/cube.stl"
    assert m.geometry.bodies[0].shape.file == "../meshes/cube.stl"  # now from the scene's folder
    back = sadr.Model.load(path)
    assert back.resolved()["geometry"]["bodies"][0]["shape"]["file"] == str(tmp_path / "meshes" / "cube.stl")
    built = back.build_geometry(tmp_path / "out")
    assert built.counts()["wall"] > 0 and len(built.region("skin")) > 0
    inside = built.particles[["x", "y", "z"]].to_numpy()
    fluid = built.particles["kind"].to_numpy() == 0
    assert not np.any(fluid & np.all((inside > 0.35) & (inside < 0.65), axis=1))  # no fluid in the cube


def test_a_refusal_is_the_clis_message(tmp_path):
    """A bad key: `sadr geometry` (build_geometry) and `sadr validate`
    (validate) refuse with the file:line message the CLI gives that file."""
    m = sadr.Model.load(EXAMPLES / "cell_in_channel_geometry_2d.yaml")
    m.geometry.bodies[1].shape.extra["radius"] = 0.1  # not a key of an ellipse
    with pytest.raises(sadr.InvalidInput) as e:
        m.build_geometry(tmp_path / "geo")
    path = tmp_path / "geo" / "cell_in_channel_geometry_2d.yaml"
    expected = sadr.run_cli(["validate", path], check=False).stderr
    line = next(ln for ln in expected.splitlines() if "does not apply" in ln)
    assert re.match(rf"\s*{re.escape(str(path))}:\d+:\d+: geometry\.bodies\[1\]\.shape\.radius: key 'radius' "
                    r"does not apply to shape type 'ellipse' \(its keys: center, radii, translate, rotate, scale\)",
                    line), line
    assert line in e.value.message and e.value.code == 1
    assert e.value.scene_yaml == path.read_text()
    with pytest.raises(sadr.InvalidInput) as v:
        m.validate()
    assert "key 'radius' does not apply to shape type 'ellipse'" in v.value.message
    # an unknown shape type survives reading and is named by the CLI
    m.geometry.bodies[1].shape = g.Shape.from_dict({"type": "elipse", "center": [0.7, 0.5], "radii": [0.2, 0.1]})
    with pytest.raises(sadr.InvalidInput, match="elipse.*ellipse"):
        m.validate()


def test_plot_geometry_draws_every_particle(tmp_path):
    m = sadr.Model.load(EXAMPLES / "cell_in_channel_geometry_2d.yaml")
    built = m.build_geometry(tmp_path / "geo")
    fig = sadr.plot_geometry(built, "regions")
    drawn = {c.get_label().split(" (")[0]: len(c.get_offsets()) for c in fig.axes[0].collections}
    assert sum(drawn.values()) == len(built.particles)
    assert drawn["membrane"] == len(built.region("membrane"))  # the smallest region wins over 'cell'
    fig = sadr.plot_geometry(tmp_path / "geo", "membrane")
    n = len(built.region("membrane"))
    labels = {c.get_label() for c in fig.axes[0].collections}
    assert labels == {f"membrane ({n})", f"other ({len(built.particles) - n})"}
    with pytest.raises(ValueError, match="allowed: kind, regions, .*membrane"):
        sadr.plot_geometry(built, "nucleus")


def test_plot_geometry_command(tmp_path):
    """`python3 -m sadr plot-geometry`: from a 3D scene (three slices) and from a folder."""
    env_run = [sys.executable, "-m", "sadr", "plot-geometry"]
    env = {**os.environ, "PYTHONPATH": str(REPO / "python")}  # the commands run from other folders
    scene = EXAMPLES / "yeast_cell_channel_geometry_3d.yaml"
    proc = subprocess.run(env_run + [scene, "-o", tmp_path / "yeast.png", "--color", "regions"],
                          capture_output=True, text=True, cwd=tmp_path, env=env)
    assert proc.returncode == 0, proc.stderr
    assert "particles:" in proc.stdout and (tmp_path / "yeast.png").stat().st_size > 10000
    built = sadr.Model.load(scene).build_geometry(tmp_path / "geo3")
    fig = sadr.plot_geometry(built)
    assert [a.get_title().split(" =")[0] for a in fig.axes] == ["slice z", "slice y", "slice x"]
    dx = 0.1
    for ax in fig.axes:
        n = sum(len(c.get_offsets()) for c in ax.collections)
        assert 0 < n < len(built.particles) * 2 * dx  # one lattice plane of a 1.2-wide duct
    proc = subprocess.run(env_run + [tmp_path / "geo3"], capture_output=True, text=True, env=env)
    assert proc.returncode == 0 and (tmp_path / "geo3" / "geometry.png").is_file(), proc.stderr
    bad = subprocess.run(env_run + [EXAMPLES / "static_reaction_diffusion.yaml"], capture_output=True, text=True,
                         cwd=tmp_path, env=env)
    assert bad.returncode == 1 and "has no 'geometry' section" in bad.stderr


@pytest.mark.parametrize("page,heading", [("python.md", "## Geometry"), ("geometry.md", "## From Python")])
def test_docs_examples_run(tmp_path, monkeypatch, page, heading):
    """The geometry examples of docs/python.md and docs/geometry.md, as written there."""
    text = (REPO / "docs" / page).read_text()
    code = re.search(r"```python\n(.*?)```", text[text.index(heading):], re.S).group(1)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "examples").symlink_to(EXAMPLES)
    env: dict = {}
    exec(compile(code, f"docs/{page}", "exec"), env)  # noqa: S102 - the documented example
    built = env["built"]
    assert (tmp_path / "geo" / "particles.csv").is_file() and len(built.region("membrane")) > 0
    assert built.counts()["wall"] > 0 and "warnings:" in built.summary
