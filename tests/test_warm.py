"""Warming the cache: every shipped kernel flavour is listed, built from a scene of its
kind, announced with its own measured estimate, and compiled by ``shroudnet cache --warm``."""

import re

import pytest

from shroudnet.engine import compiled, generate
from shroudnet.front import warm
from shroudnet.front.cli import main


def test_every_flavour_has_its_measured_estimate_and_every_estimate_a_flavour():
    keys = {(f.method, f.structures, f.sliders, f.tangent) for f in warm.FLAVOURS}
    assert keys == set(compiled.COMPILE_SECONDS)
    assert len(keys) == len(warm.FLAVOURS) == 10
    assert len({f.name for f in warm.FLAVOURS}) == len(warm.FLAVOURS)


@pytest.mark.parametrize("flavour", warm.FLAVOURS, ids=lambda f: f.name)
def test_each_flavours_scene_loads_the_kernel_of_that_flavour(flavour):
    """The kernel a flavour's scene loads (built, not compiled: numba compiles on first
    call) is that flavour's, and the notice quotes that flavour's estimate."""
    scene = warm._scene(flavour)
    kernel = generate.load_kernel(scene, tangent=flavour.tangent, method=flavour.method)
    assert (kernel.METHOD, kernel.HAS_STRUCTURES, kernel.HAS_SLIDERS, kernel.TANGENT) == (
        flavour.method, flavour.structures, flavour.sliders, flavour.tangent)
    assert kernel.SHARED
    assert compiled.compile_seconds(kernel) == compiled.COMPILE_SECONDS[
        (flavour.method, flavour.structures, flavour.sliders, flavour.tangent)]


def test_the_warm_up_compiles_on_processes_of_its_own_and_says_what_it_took(
        monkeypatch, capsys):
    """On the one flavour the suite compiles anyway (the paper's group, adaptive): each
    flavour a line with its seconds, then the whole."""
    blades = warm.Flavour("adaptive")
    monkeypatch.setattr(warm, "FLAVOURS", (blades,))
    assert main(["cache", "--warm", "--workers", "2"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("warming  1 integrators in ") and out[0].endswith(", 1 at once")
    assert re.fullmatch(r"  adaptive, blades +\d+\.\d s", out[1])
    assert re.fullmatch(r"warmed   1 integrators in \d+ s \(their compiles: \d+ s of "
                        r"processor time\)", out[2])


def test_warm_and_clear_are_one_or_the_other(capsys):
    with pytest.raises(SystemExit):
        main(["cache", "--warm", "--clear"])
    assert "not allowed with argument" in capsys.readouterr().err
