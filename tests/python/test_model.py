# SPDX-License-Identifier: MIT
"""sadr.Model: scenes built in Python equal their YAML, load -> save keeps
every example's meaning (same data, same `sadr validate` output), every
refusal is the CLI's message, and runs return the result objects."""
import re
import shutil
import subprocess
from pathlib import Path

import pytest

import sadr
from conftest import EXAMPLES, REPO
from sadr.model import Boundary, BoundaryFlux, Fluid, Initial, Observable, Reaction, Region, Species
from sadr.paths import PathError, load_yaml


def static_model(end=2.0):
    """examples/static_reaction_diffusion.yaml, written in Python."""
    m = sadr.Model("static_reaction_diffusion", dimension=2, seed=7,
                   description="production in a disk, decay everywhere; stochastic A vs deterministic B")
    m.set_box([0.0, 0.0], [1.0, 1.0], periodic=[True, True])
    m.add_region("source", "disk", center=[0.5, 0.5], radius=0.15)
    m.set_lattice(spacing=0.05, density=1.0)
    m.set_fluid("static", h_over_dx=2.0)
    m.add_species("A", stochastic=True, diffusivity=0.01)
    m.add_species("B", stochastic=False, diffusivity=0.01)
    for s in ("A", "B"):
        m.add_reaction(f"0 -> {s}", name=f"make_{s}", rate=4000, regions=["source"])
        m.add_reaction(f"{s} -> 0", name=f"decay_{s}", rate=1.0)
    m.set_time(coupling_step=0.05, end=end)
    m.set_output(every=0.25, formats=["vtu", "csv"])
    return m


def meaning_hash(validate_output):
    """The "scene meaning" hash `sadr validate` prints: the scene's meaning, not its bytes."""
    found = re.search(r"^sadr: scene meaning (fnv1a64:[0-9a-f]{16})$", validate_output, re.M)
    return found.group(1) if found else None


def plan(text, *paths):
    """`sadr validate` output with the scene's path, the log lines' clock and the warnings'
    line:column (a saved file lays its keys out anew) taken out."""
    for p in paths:
        text = text.replace(str(p), "SCENE")
    text = re.sub(r"^\[\d\d:\d\d:\d\d\.\d+\] ", "", text, flags=re.M)
    return re.sub(r"SCENE:\d+:\d+: ", "SCENE: ", text)


def test_built_in_python_equals_the_example(tmp_path):
    m = static_model()
    example = load_yaml((EXAMPLES / "static_reaction_diffusion.yaml").read_text())
    assert m.to_dict() == example
    assert list(m.to_dict()) == list(example)  # the scene format's key order
    path = m.save(tmp_path / "static_reaction_diffusion.yaml")
    mine = sadr.run_cli(["validate", path]).stderr
    theirs = sadr.run_cli(["validate", EXAMPLES / "static_reaction_diffusion.yaml"]).stderr
    assert plan(mine, path) == plan(theirs, EXAMPLES / "static_reaction_diffusion.yaml")
    assert meaning_hash(mine) is not None and meaning_hash(mine) == meaning_hash(theirs)
    assert "sadr: scene 'static_reaction_diffusion' (400 particles, 2 species, 4 reactions)" in mine


EXAMPLE_FILES = sorted(p.name for p in EXAMPLES.glob("*.yaml"))


@pytest.mark.parametrize("name", EXAMPLE_FILES)
def test_load_save_keeps_the_meaning(tmp_path, name):
    """Every example: load, save elsewhere (a particle file's path rewritten),
    the same data with paths resolved, and the same `sadr validate` output."""
    source = EXAMPLES / name
    m = sadr.Model.load(source)
    assert m.to_dict() == load_yaml(source.read_text())  # nothing lost or added on reading
    saved = m.save(tmp_path / "elsewhere" / name)
    back = sadr.Model.load(saved)
    assert back.resolved() == sadr.Model.load(source).resolved()
    # both validations at once (the largest examples take seconds each)
    procs = [subprocess.Popen([str(sadr.find_sadr()), "validate", str(p)], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True) for p in (saved, source)]
    (out_saved, err_saved), (out_source, err_source) = [p.communicate() for p in procs]
    assert [p.returncode for p in procs] == [0, 0], err_saved + err_source
    assert plan(err_saved + out_saved, saved) == plan(err_source + out_source, source)


def test_edit_and_save(tmp_path):
    m = sadr.Model.load(EXAMPLES / "yeast_cell_channel.yaml")
    original = m.copy()
    assert original == m
    m.get_reaction("binding").rate = 8e-7
    assert original != m and original.get_reaction("binding").rate == 4e-7
    m.set("time.end", 0.5).set("species[R].diffusivity", 0.001)
    assert m["reactions[binding].rate"] == 8e-7 and m.get_species("R").diffusivity == 0.001
    assert m.time.end == 0.5
    with pytest.raises(PathError, match="no item named 'X'.*L, R, RL"):
        m.set("species[X].diffusivity", 1.0)
    path = m.save(tmp_path / "yeast.yaml")
    assert (path.parent / m.particles.file).resolve() == (EXAMPLES / "data" / "yeast_cell_particles.csv").resolve()
    back = load_yaml(path.read_text())
    assert back["reactions"][0]["rate"] == 8e-7 and back["species"][1]["diffusivity"] == 0.001
    assert "t_end = 0.5" in sadr.run_cli(["validate", path]).stderr


def every_law_model():
    """Mass action (each order, reversible), Michaelis-Menten, Hill, expression,
    assigned species, parameters by name, hybrid laws, boundary fluxes,
    boundary conditions, observables."""
    m = sadr.Model("laws", dimension=2, seed=3)
    m.set_box([0, 0], [1, 1], periodic=[True, False])
    m.add_region("top", "box", lower=[0, 0.9], upper=[1, 1])
    m.add_region("patch", "box", lower=[0.2, 0], upper=[0.6, 0])
    m.add_region("cell", "annulus", center=[0.5, 0.5], inner_radius=0.05, outer_radius=0.2)
    m.add_region("slab", "channel", axis="x", lower=0.0, upper=0.3)
    m.add_region("three", "ids", ids=[0, 1, 2])
    m.set_lattice(spacing=0.1)
    m.add_fill("top", "wall")
    m.add_fill(kind="fluid")
    m.set_fluid("static", smoothing_length=0.25, kernel="wendland_c2", parameters={"diffusion_eps": 0.02})
    m.parameters.update(kcat=2.5, Km=0.1, q=0.3)
    m.add_species("S", 0.01).add_initial(count=5).add_initial("slab", count=8)
    m.add_species("E", 0.0).add_initial("cell", count=3)
    m.add_species("P", 0.01).add_boundary("top", "dirichlet", value=0.0)
    m.add_species("R", 0.0)
    m.add_species("B", 0.01, stochastic=False).add_initial(concentration=1.0)
    m.add_assigned_species("SP", "S*P/2")
    m.add_reaction("S + E <-> P", name="bind", rate=1e-3, reverse_rate=0.5)
    m.add_reaction("2 S -> P", name="dimer", rate=1e-4, regions=["slab"])
    m.add_reaction(name="make_R", reactants={}, products={"R": 1}, rate=10.0)
    m.add_reaction("S -> P", name="cleave", law=sadr.MichaelisMenten(kcat="kcat", Km="Km", catalyst="E"))
    m.add_reaction("0 -> R", name="switch", law=sadr.Hill(Vmax=4, K=0.5, n=2, of="S"))
    m.add_reaction("R -> 0", name="custom", law=sadr.Expression("kcat*R/(Km+R) + 0*t"))
    m.add_reaction("0 -> B", name="b_from_s", law=sadr.Expression("0.1*S"))  # hybrid: the fluid reads S
    m.add_boundary_flux("y-", sadr.Expression("q"), species="S", name="supply")
    m.add_boundary_flux("y-", sadr.Expression("0.8*P/(0.5+P)"), equation="P -> 0", region="patch")
    m.set_time(0.01, 0.05, splitting="strang")
    m.set_output(times=[0.0, 0.05], formats=["csv"], species=["S", "P", "B", "SP"])
    m.add_observable("total_P", "P")
    m.add_observable("mean_S", "S", region="slab", stat="mean")
    m.set_ssa(convention="symmetric", regularization=0.02)
    return m


def test_every_rate_law_validates():
    m = every_law_model()
    text = m.validate()
    # 7 SSA reactions (bind has a reverse) and 2 fluxes; one fluid reaction reading S
    assert "ssa_service: launched; species on the wire: S, E, P, R; reactions: 9" in text
    assert "fluid_service (static): launched, advanced every coupling step; species on the wire: B, S; " \
        "reactions: 1" in text
    assert "back-transfer ssa -> fluid: S" in text and "ssa laws of t" in text
    assert "splitting: strang" in text and text.rstrip().endswith("laws.yaml: valid")
    d = m.to_dict()
    assert d["reactions"][3]["law"] == {"type": "michaelis_menten", "kcat": "kcat", "Km": "Km",
                                        "catalyst": "E"}
    assert d["boundary_fluxes"][1] == {"equation": "P -> 0", "face": "y-", "region": "patch",
                                       "law": {"type": "expression", "expression": "0.8*P/(0.5+P)"}}
    on_cell = sadr.Model().add_boundary_flux(None, sadr.Expression("q"), species="S", surface="cell")
    assert on_cell.to_dict() == {"species": "S", "surface": "cell",
                                 "law": {"type": "expression", "expression": "q"}}
    again = sadr.Model.from_dict(d)
    assert again.to_dict() == d and again.reactions[4].law == sadr.Hill(4, 0.5, 2, of="S")
    assert isinstance(again.reactions[0], Reaction) and isinstance(again.species[0], Species)
    assert isinstance(again.species[0].initial[0], Initial)
    assert isinstance(again.species[2].boundaries[0], Boundary)
    assert isinstance(again.boundary_fluxes[0], BoundaryFlux) and isinstance(again.regions[0], Region)
    assert isinstance(again.output.observables[1], Observable) and isinstance(again.fluid, Fluid)


def cli_message(data, tmp_path, name):
    path = tmp_path / name / "laws.yaml"
    sadr.Scene(data).write(path)
    proc = sadr.run_cli(["validate", path], check=False)
    assert proc.returncode == 1
    return proc.stderr.replace(str(path), "SCENE")


@pytest.mark.parametrize("edit", ["negative_end", "unknown_key", "bad_law", "unknown_backend_parameter",
                                  "unknown_species"])
def test_refusals_are_the_clis_message(tmp_path, edit):
    m = every_law_model()
    if edit == "negative_end":
        m.time.end = -1.0
    elif edit == "unknown_key":
        m.get_species("S").extra["diffusivty"] = 0.1
    elif edit == "bad_law":
        m.get_reaction("cleave").law = sadr.MichaelisMenten(kcat=1, Km=-1, catalyst="E")
    elif edit == "unknown_backend_parameter":
        m.fluid.parameters["density_diffusion"] = 0.1
    else:
        m.add_reaction("X -> 0", rate=1.0)
    with pytest.raises(sadr.InvalidInput) as e:
        m.validate()
    assert e.value.code == 1
    stem = re.search(r"sadr-model-\w+/laws\.yaml", e.value.stderr).group(0)
    path = re.search(r"'([^']*" + re.escape(stem) + ")'", e.value.stderr).group(1)
    assert e.value.stderr.replace(path, "SCENE") == cli_message(m.to_dict(), tmp_path, edit)
    assert e.value.scene_yaml == m.to_yaml(path)
    assert e.value.message.startswith("sadr exited with 1: ")


def test_run_locally(tmp_path):
    m = static_model(end=0.2)
    m.set_output(every=0.1, formats=["csv"])
    run = m.run(tmp_path / "one")
    assert isinstance(run, sadr.Run) and run.times.tolist() == [0.0, 0.1, 0.2]
    assert (tmp_path / "one.yaml").is_file() and run.manifest["scene_path"].endswith("one.yaml")
    assert run.series("B").iloc[-1, 0] > 0
    ens = m.run(tmp_path / "ens", realizations=2, jobs=2, overrides={"reactions[make_A].rate": 8000})
    assert isinstance(ens, sadr.Ensemble) and len(ens) == 2
    assert ens[0].manifest["overrides"] == ["reactions[make_A].rate=8000"]


def test_run_on_dask(tmp_path):
    distributed = pytest.importorskip("distributed", reason="python3-distributed is not installed")
    m = static_model(end=0.1)
    m.set_output(every=0.1, formats=["csv"])
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        ens = m.run(tmp_path / "dask", realizations=2, client=client)
    assert isinstance(ens, sadr.Ensemble) and len(ens) == 2
    assert ens.mean_frame(-1)["realizations"].min() == 2


def test_a_particle_file_built_in_python(tmp_path, monkeypatch):
    """A relative particle file is taken from the working directory and written
    relative to the scene file, wherever that is."""
    data = tmp_path / "data"
    data.mkdir()
    shutil.copy(EXAMPLES / "data" / "yeast_cell_particles.csv", data / "p.csv")
    monkeypatch.chdir(tmp_path)
    m = sadr.Model.load(EXAMPLES / "yeast_cell_channel.yaml")
    m.set_particle_file("data/p.csv")
    path = m.save(tmp_path / "deep" / "er" / "yeast.yaml")
    assert load_yaml(path.read_text())["particles"]["file"] == "../../data/p.csv"
    sadr.run_cli(["validate", path])
    # a backend's file parameter (prescribed's field_file) is re-anchored the same way
    flow = sadr.Model.from_dict({"fluid": {"backend": "prescribed", "parameters": {"field_file": "f.csv"}}},
                                base_dir=data)
    out = flow.save(tmp_path / "x" / "flow.yaml")
    assert load_yaml(out.read_text())["fluid"]["parameters"]["field_file"] == "../data/f.csv"
    assert flow.resolved()["fluid"]["parameters"]["field_file"] == str(data / "f.csv")


def test_model_knows_every_key_of_the_loader():
    """The builder's fields are the scene loader's keys (orchestrator/scene/src),
    so nothing the format takes needs ``extra``."""
    src = "\n".join(p.read_text() for p in (REPO / "orchestrator" / "scene" / "src").glob("scene*.cpp"))
    arrays = {m[0]: re.findall(r'"([^"]+)"', m[1])
              for m in re.findall(r"k(\w*Keys)\{([^}]*)\}", src)}
    import dataclasses

    from sadr import model

    def fields(cls):
        return {f.name for f in dataclasses.fields(cls)} - {"extra"}
    expect = {"SpeciesKeys": fields(model.Species) - {"assigned"}, "InitialKeys": fields(model.Initial),
              "BoundaryKeys": fields(model.Boundary), "ReactionKeys": fields(model.Reaction),
              "FluidKeys": fields(model.Fluid), "PlaneKeys": fields(model.WallPlane),
              "OpenKeys": fields(model.OpenBoundary), "BoussinesqKeys": fields(model.Boussinesq),
              "FluxKeys": fields(model.BoundaryFlux), "ParticleKeys": fields(model.Particles),
              "FillKeys": fields(model.Fill), "RegionKeys": fields(model.Region),
              "TimeKeys": fields(model.Time), "OutputKeys": fields(model.Output),
              "ObservableKeys": fields(model.Observable), "TopKeys": set(model._TOP)}
    for name, keys in expect.items():
        assert set(arrays[name]) == keys, name
    laws = {"MichaelisKeys": sadr.MichaelisMenten(1, 1, "E", "S"), "HillKeys": sadr.Hill(1, 1, 1, "A"),
            "ExpressionKeys": sadr.Expression("1")}
    for name, law in laws.items():
        assert set(arrays[name]) == set(law.to_dict()), name


def test_docs_example_runs(tmp_path, monkeypatch):
    """The sadr.Model example of docs/python.md, as written there."""
    text = (REPO / "docs" / "python.md").read_text()
    section = text[text.index("## Building a scene in Python"):]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    env: dict = {}
    exec(compile(code, "docs/python.md", "exec"), env)  # noqa: S102 - the documented example
    assert isinstance(env["run"], sadr.Run) and len(env["run"]) >= 2
    assert Path("runs/decay.yaml").is_file()


def tutorial_scenes():
    """The YAML blocks of docs/tutorials/*.md that are whole scenes."""
    out = []
    for page in sorted((REPO / "docs" / "tutorials").glob("*.md")):
        for k, block in enumerate(re.findall(r"```yaml\n(.*?)```", page.read_text(), re.S)):
            data = load_yaml(block)
            if isinstance(data, dict) and "dimension" in data:
                out.append(pytest.param(block, id=f"{page.stem}-{k}"))
    return out


@pytest.mark.parametrize("block", tutorial_scenes() or [pytest.param(None, marks=pytest.mark.skip(
    reason="docs/tutorials has no scene"))])
def test_tutorial_scenes_round_trip(tmp_path, block):
    """Each scene of the tutorials, read into a Model and written back: the
    same data, and `sadr validate` says the same of both files."""
    data = load_yaml(block)
    m = sadr.Model.from_dict(data, tmp_path)
    assert m.to_dict() == data
    (tmp_path / "a.yaml").write_text(block)
    m.save(tmp_path / "b.yaml")
    said = []
    for name in ("a.yaml", "b.yaml"):
        proc = sadr.run_cli(["validate", name], check=False, cwd=tmp_path)
        said.append((proc.returncode, proc.stdout.replace(name, "S"), proc.stderr.replace(name, "S")))
    assert said[0][0] == 0, said[0][2]
    assert said[0] == said[1]


def first_scene():
    """Tutorial 1's scene, written in Python."""
    m = sadr.Model("first", dimension=2, seed=7, description="molecules made in a disk, diffusing and decaying")
    m.set_box([0.0, 0.0], [1.0, 1.0], periodic=[True, True])
    m.add_region("source", "disk", center=[0.5, 0.5], radius=0.15)
    m.set_lattice(spacing=0.05, density=1.0)
    m.set_fluid("static", h_over_dx=2.0)
    m.add_species("A", stochastic=True, diffusivity=0.01)
    m.add_reaction("0 -> A", name="make", rate=4000, regions=["source"])
    m.add_reaction("A -> 0", name="decay", rate=1.0)
    m.set_time(coupling_step=0.05, end=2.0)
    m.set_output(every=0.5, formats=["vtu", "csv"])
    return m


def reaction_network():
    """Tutorial 2's scene (rate laws, mixed species), written in Python."""
    m = sadr.Model("network", dimension=2, seed=11)
    m.set_box([0.0, 0.0], [10.0, 10.0], periodic=[True, True])
    m.add_region("source", "disk", center=[5.0, 5.0], radius=2.0)
    m.set_lattice(spacing=1.0, density=1.0)
    m.set_fluid("static", h_over_dx=2.0)
    m.parameters.update(q=50, Vmax=20, K=10, kcat=0.5, Km=20)
    m.add_species("L", stochastic=False, diffusivity=1.0)
    m.add_species("R", stochastic=True, diffusivity=0.0)
    m.add_species("S", stochastic=True, diffusivity=0.5).add_initial(count=50)
    m.add_species("P", stochastic=True, diffusivity=0.5)
    m.add_reaction("0 -> L", name="release", regions=["source"], law=sadr.Expression("t < 1 ? q : 0"))
    m.add_reaction("L -> 0", name="clear", rate=1.0)
    m.add_reaction("0 -> R", name="activate", law=sadr.Hill(Vmax="Vmax", K="K", n=2, of="L"))
    m.add_reaction("R -> 0", name="deactivate", rate=0.5)
    m.add_reaction("S -> P", name="convert", law=sadr.MichaelisMenten(kcat="kcat", Km="Km", catalyst="R"))
    m.set_time(coupling_step=0.05, end=4.0)
    m.set_output(every=1.0, formats=["csv"])
    return m


def cell_in_channel():
    """Tutorial 3's scene: the channel and the cell from the geometry section (sadr.geometry)."""
    from sadr.geometry import Box, Disk

    m = sadr.Model("cell", dimension=2, seed=5, description="a cell with surface receptors in a 2D channel flow")
    m.set_box([0.0, -0.15], [2.0, 1.15], periodic=[True, False])
    m.add_region("inlet", "box", lower=[0.0, 0.05], upper=[0.2, 0.95])
    geo = m.set_geometry(spacing=0.05)
    geo.add_fluid("channel", Box([-1.0, 0.0], [3.0, 1.0]))
    geo.add_solid("cell", Disk([0.6, 0.5], 0.12), wall_layer="membrane")
    m.set_fluid("sdpd", h_over_dx=3.0, shear_viscosity=0.1, temperature=0.0, gravity=[0.4, 0.0])
    m.add_species("L", diffusivity=0.002).add_boundary("inlet", "inflow", count=20).add_boundary("membrane", "free")
    m.add_species("R", diffusivity=0.0).add_initial("membrane", count=50).add_boundary("membrane", "free")
    m.add_species("RL", diffusivity=0.0).add_boundary("membrane", "free")
    m.add_reaction("R + L <-> RL", name="binding", rate=0.01, reverse_rate=0.1, kinds=["wall"],
                   regions=["membrane"])
    m.set_time(coupling_step=0.02, end=6.0)
    m.set_output(every=1.0, formats=["vtu", "csv"])
    return m


def disk_scene(name="disk", end=1.0, every=0.5, formats=("csv",), observable=True):
    """Tutorials 4, 5 and 6: tutorial 1's scene, shorter (4: with an observable)."""
    m = sadr.Model(name, dimension=2, seed=7)
    m.set_box([0.0, 0.0], [1.0, 1.0], periodic=[True, True])
    m.add_region("source", "disk", center=[0.5, 0.5], radius=0.15)
    m.set_lattice(spacing=0.05, density=1.0)
    m.set_fluid("static", h_over_dx=2.0)
    m.add_species("A", stochastic=True, diffusivity=0.01)
    m.add_reaction("0 -> A", name="make", rate=4000, regions=["source"])
    m.add_reaction("A -> 0", name="decay", rate=1.0)
    m.set_time(coupling_step=0.05, end=end)
    m.set_output(every=every, formats=list(formats))
    if observable:
        m.add_observable("A_disk", "A", region="source")
    return m


def decay_sweep():
    """Tutorial 4's sweep file: three decay rates x 8 realizations of its scene."""
    sw = sadr.SweepFile(disk_scene(), realizations=8, seed=2024, output="sweeps/decay")
    sw.add_grid("reactions[decay].rate", [0.5, 1.0, 2.0])
    sw.executor = sadr.sweep_file.Executor("local", workers=2)
    return sw


TUTORIAL_SCENES = [
    ("01-first-scene", first_scene), ("02-reaction-network", reaction_network),
    ("03-cell-in-channel", cell_in_channel), ("04-parameter-sweep", disk_scene),
    ("05-python-paraview", lambda: disk_scene("first", 2.0, 0.25, ("vtu", "csv"), False)),
    ("06-cluster", lambda: disk_scene("first", 1.0, 0.5, ("vtu", "csv"), False))]


def test_every_tutorial_with_a_scene_is_built_in_python():
    pages = {p.stem for p in (REPO / "docs" / "tutorials").glob("0*.md")
             if re.search(r"```yaml\n(?:.*\n)*?dimension:", p.read_text())}
    assert pages == {page for page, _ in TUTORIAL_SCENES}


@pytest.mark.parametrize("page,build", TUTORIAL_SCENES)
def test_tutorial_scene_built_in_python_equals_its_yaml(tmp_path, page, build):
    text = (REPO / "docs" / "tutorials" / f"{page}.md").read_text()
    block = re.search(r"```yaml\n(.*?)```", text, re.S).group(1)
    m = build()
    assert m.to_dict() == load_yaml(block)
    (tmp_path / "yaml.yaml").write_text(block)
    m.save(tmp_path / "python.yaml")
    said = [sadr.run_cli(["validate", n], cwd=tmp_path).stderr.replace(n, "S") for n in ("yaml.yaml", "python.yaml")]
    assert said[0] == said[1]
    hashes = [meaning_hash(text) for text in said]
    assert hashes[0] is not None and hashes[0] == hashes[1]


def test_tutorial_sweep_built_in_python_equals_its_yaml(tmp_path):
    """Tutorial 4's sweep file and its scene built in Python: the same file, and
    `sadr sweep --dry-run` lists the same points, overrides, seeds and runs."""
    text = (REPO / "docs" / "tutorials" / "04-parameter-sweep.md").read_text()
    scene, sweep = re.findall(r"```yaml\n(.*?)```", text, re.S)[:2]
    (tmp_path / "yaml").mkdir()
    (tmp_path / "yaml" / "disk.yaml").write_text(scene)
    (tmp_path / "yaml" / "decay.yaml").write_text(sweep)
    sw = decay_sweep()
    path = sw.save(tmp_path / "python" / "decay.yaml", scene_file="disk.yaml")
    assert load_yaml(path.read_text()) == load_yaml(sweep)
    assert load_yaml((tmp_path / "python" / "disk.yaml").read_text()) == load_yaml(scene)
    said = [sadr.SweepFile.load(tmp_path / d / "decay.yaml").dry_run().replace(str(tmp_path / d), "D")
            for d in ("yaml", "python")]
    assert said[0] == said[1]
    assert said[0].count("reactions[decay].rate=") >= 3
    back = sadr.SweepFile.load(path)
    assert back.to_dict() == load_yaml(sweep) and back.parameters.grid == {"reactions[decay].rate": [0.5, 1.0, 2.0]}


def test_sweep_file_has_the_loaders_keys():
    src = (REPO / "orchestrator" / "scene" / "src" / "sweep_spec.cpp").read_text()
    arrays = [re.findall(r'"([^"]+)"', m) for m in re.findall(r"kKeys\{([^}]*)\}", src)]
    from sadr import sweep_file

    expect = [sweep_file.Parameters.keys(), sweep_file.Executor.keys(), sweep_file.SweepFile.keys()]
    assert sorted(map(sorted, arrays)) == sorted(map(sorted, expect))


def test_a_bad_sweep_is_refused_with_the_clis_message(tmp_path):
    sw = decay_sweep()
    sw.add_grid("reactions[decay].rat", [1.0])
    sw.save(tmp_path / "decay.yaml", scene_file="disk.yaml")
    with pytest.raises(sadr.InvalidInput) as e:
        sw.dry_run()
    direct = sadr.run_cli(["sweep", tmp_path / "decay.yaml", "--dry-run"], check=False)
    assert direct.returncode == 1 and e.value.stderr == direct.stderr
    assert "rat" in e.value.message
