# SPDX-License-Identifier: MIT
"""Scenes from Python: edit, write, validate and run through the CLI; its exit
codes as exceptions carrying its message."""
import pytest
import yaml

import sadr
from conftest import EXAMPLES, static_scene


def test_keys_and_round_trip(tmp_path):
    s = sadr.Scene.load(EXAMPLES / "static_reaction_diffusion.yaml")
    assert s["time.end"] == 2.0
    assert s["species[0].name"] == "A" and s["reactions[decay_B].rate"] == 1.0
    s["species[0].diffusivity"] = 0.02
    s["reactions[make_B].regions"] = ["source"]
    s["output.vtk_encoding"] = "ascii"
    assert "output.vtk_encoding" in s and "output.nothing" not in s
    with pytest.raises(KeyError, match=r"scene has no 'species\[5\].name'.*index 5 is out of range"):
        s["species[5].name"]
    path = s.write(tmp_path / "edited.yaml")
    back = yaml.safe_load(path.read_text())
    assert back["species"][0]["diffusivity"] == 0.02
    assert back["output"]["vtk_encoding"] == "ascii"
    assert "valid" in sadr.Scene.load(path).validate()


def test_particle_file_keeps_resolving(tmp_path):
    s = sadr.Scene.load(EXAMPLES / "yeast_cell_channel.yaml")
    path = s.write(tmp_path / "sub" / "yeast.yaml")
    target = (path.parent / s["particles.file"]).resolve()
    assert target == (EXAMPLES / "data" / "yeast_cell_particles.csv").resolve()
    sadr.Scene.load(path).validate()


def test_invalid_scene_raises_with_message(tmp_path):
    s = static_scene()
    s["time.end"] = -1.0
    s.write(tmp_path / "bad.yaml")
    with pytest.raises(sadr.InvalidInput) as e:
        s.validate()
    assert e.value.code == 1
    assert "time.end" in e.value.message and "bad.yaml" in e.value.message
    with pytest.raises(sadr.InvalidInput, match="time.end"):
        s.run(tmp_path / "out")


def test_usage_error_code_2():
    with pytest.raises(sadr.UsageError) as e:
        sadr.run_cli(["validate", EXAMPLES / "static_reaction_diffusion.yaml", "--no-such-option"])
    assert e.value.code == 2 and "no-such-option" in e.value.stderr


def test_changed_scene_is_written_next_to_the_output(tmp_path):
    s = static_scene(end=0.1, every=0.1)
    run = s.run(tmp_path / "short")
    assert (tmp_path / "short.yaml").is_file()
    assert run.manifest["scene_path"].endswith("short.yaml")
    assert run.times.tolist() == [0.0, 0.1]
    one = s.run(tmp_path / "ens", realization=2)
    assert one.path.name == "realization_0002" and one.manifest["realization"] == 2


def test_overrides_become_set_options(tmp_path):
    s = sadr.Scene.load(EXAMPLES / "static_reaction_diffusion.yaml")
    assert sadr.scene.set_options({"time.end": 0.1, "output.times": [0.0, 0.1],
                                   "reactions[decay_A].rate": 2}) == [
        "--set", "time.end=0.1", "--set", "output.times=[0.0, 0.1]",
        "--set", "reactions[decay_A].rate=2"]
    run = s.run(tmp_path / "o", overrides={"time.end": 0.1, "output.every": 0.05})
    assert run.manifest["overrides"] == ["time.end=0.1", "output.every=0.05"]
    assert run.times.tolist() == [0.0, 0.05, 0.1]
    with pytest.raises(sadr.InvalidInput, match="decay_X"):
        s.run(tmp_path / "bad", overrides={"reactions[decay_X].rate": 1})
