"""Bad input is refused before any work, with a message that names the argument (or the
file) and what is allowed: the cases that once let an internal exception out, passed
silently or hung, grouped by the door they come through."""

from __future__ import annotations

import functools

import pytest

from shroudnet import Exponential, FixedStep, results, scenefile, simulate
from shroudnet.methods import MOST_STEPS_PER_PERIOD
from shroudnet.scenes import three_blade_paper


@functools.cache
def paper_run():
    """Two periods of the paper's group (its kernel is the one most tests compile)."""
    return simulate(three_blade_paper(), 2, samples_per_period=10)


# ---- the writers of files ------------------------------------------------------------------

WRITERS = {
    "document of a string": (lambda path: scenefile.document("scene"), TypeError,
                             r"scenefile\.document\.scene must be a shroudnet\.Scene, got "
                             r"str 'scene'"),
    "scene file with run settings of a string": (
        lambda path: scenefile.save(path, three_blade_paper(), run="fast"), TypeError,
        r"scenefile\.save\.run must be scenefile\.RunSettings\(\.\.\.\) or None, got str "
        r"'fast'"),
    "simulation of a string": (
        lambda path: results.save_simulation(path, "not a sim"), TypeError,
        r"results\.save_simulation\.sim must be a shroudnet\.Simulation \(what simulate "
        r"returns\), got str 'not a sim'"),
    "simulation with run settings of a string": (
        lambda path: results.save_simulation(path, paper_run(), run="fast"), TypeError,
        r"results\.save_simulation\.run must be scenefile\.RunSettings\(\.\.\.\) or None"),
    "branch of a string": (
        lambda path: results.save_branch(path, "x"), TypeError,
        r"results\.save_branch\.branch must be a shroudnet\.Branch \(what continuation "
        r"returns\), got str 'x'"),
}


@pytest.mark.parametrize("case", WRITERS)
def test_a_writer_refuses_what_is_not_its_own_by_name_and_writes_nothing(tmp_path, case):
    write, error, message = WRITERS[case]
    with pytest.raises(error, match=message):
        write(tmp_path / "file")
    assert list(tmp_path.iterdir()) == []


def test_a_scene_file_saves_what_loading_it_returned(tmp_path):
    """``save(path, load(file))`` writes the same scene, and the [run] table where the file
    had one."""
    with_run = scenefile.save(tmp_path / "with_run.toml", three_blade_paper(),
                              scenefile.RunSettings(periods=12, transient=4))
    without = scenefile.save(tmp_path / "without.toml", three_blade_paper(speed_rpm=5000.0))
    for path in (with_run, without):
        loaded = scenefile.load(path)
        again = scenefile.load(scenefile.save(tmp_path / f"again_{path.name}", loaded))
        assert again.document == loaded.document and again.run == loaded.run
        assert scenefile.save(loaded, tmp_path / "swapped.toml").read_text() \
            == (tmp_path / f"again_{path.name}").read_text()
    assert "[run]" in (tmp_path / "again_with_run.toml").read_text()
    assert "[run]" not in (tmp_path / "again_without.toml").read_text()


# ---- the methods ---------------------------------------------------------------------------

@pytest.mark.parametrize("method", [FixedStep, Exponential])
def test_a_method_on_a_grid_takes_at_most_a_million_steps_a_period(method):
    """10¹² steps a period would take some 220 days for one: refused as the method is
    made, before any run, and so is a scene file's [run] asking for them."""
    assert method(steps_per_period=MOST_STEPS_PER_PERIOD).steps_per_period == 10**6
    for steps in (MOST_STEPS_PER_PERIOD + 1, 10**12):
        with pytest.raises(ValueError, match=rf"^{method.__name__}\.steps_per_period must be "
                                             rf"an int >= 8 and <= 1000000, got {steps}$"):
            method(steps_per_period=steps)
    document = scenefile.document(three_blade_paper())
    document["run"] = {"method": {FixedStep: "fixed", Exponential: "exponential"}[method],
                       "steps_per_period": 10**12}
    with pytest.raises(scenefile.SceneFileError, match=r"run: .*steps_per_period must be an "
                                                       r"int >= 8 and <= 1000000"):
        scenefile.read(document)
