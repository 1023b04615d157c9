"""Defaults that several entry points share are defined once, as named constants, and every
signature, record, scene file and command line takes them from there."""

import ast
import dataclasses
import importlib
import inspect
from pathlib import Path

import pytest

from shroudnet import (
    classify,
    classify_section,
    continuation,
    lyapunov,
    mistuning_study,
    monodromy,
    periodic_orbit,
    simulate,
    sweep,
)
from shroudnet.analysis import stability
from shroudnet.front import cli
from shroudnet.io import scenefile
from shroudnet.run.classification import REPEAT_TOLERANCE
from shroudnet.run.methods import EVENT_TOLERANCE, TRANSIENT
from shroudnet.run.simulate import integrate
from shroudnet.studies import precision

PACKAGE = Path(__file__).resolve().parents[1] / "shroudnet"
sweeps = importlib.import_module("shroudnet.studies.sweep")  # shroudnet.sweep names the function

#: Each shared default: the parameter names that take it, and the constant.
SHARED = {"event_tolerance": EVENT_TOLERANCE, "transient": TRANSIENT,
          "tolerance": REPEAT_TOLERANCE}


def test_the_shared_defaults_keep_their_values():
    assert (EVENT_TOLERANCE, TRANSIENT, REPEAT_TOLERANCE) == (1e-10, 300, 1e-5)


@pytest.mark.parametrize("function, parameter", [
    (simulate, "event_tolerance"), (integrate, "event_tolerance"),
    (monodromy, "event_tolerance"), (stability.stroboscopic_step, "event_tolerance"),
    (lyapunov, "event_tolerance"), (lyapunov, "transient"),
    (periodic_orbit, "event_tolerance"), (continuation, "event_tolerance"),
    (sweep, "transient"), (sweep, "tolerance"), (sweeps.steady_point, "tolerance"),
    (mistuning_study, "transient"), (precision.paper_regimes, "transient"),
    (classify, "tolerance"), (classify_section, "tolerance"),
])
def test_each_signature_takes_the_shared_default_itself(function, parameter):
    """The very object, not an equal literal written again."""
    assert inspect.signature(function).parameters[parameter].default is SHARED[parameter]


@pytest.mark.parametrize("record, field", [
    (scenefile.RunSettings, "event_tolerance"), (scenefile.RunSettings, "transient"),
    (precision.Setting, "event_tolerance"),
])
def test_each_record_takes_the_shared_default_itself(record, field):
    default, = (f.default for f in dataclasses.fields(record) if f.name == field)
    assert default is SHARED[field]


def test_the_command_line_takes_the_shared_transient():
    args = cli._parser().parse_args(["mistuning", "scene.toml", "--spread", "0.01",
                                     "--samples", "2", "--speeds", "3000"])
    assert args.transient is TRANSIENT


def test_no_signature_or_record_writes_a_shared_default_as_a_number():
    """A number written as the default of ``event_tolerance``, ``transient`` or
    ``tolerance`` anywhere outside the engine: the constant is what it must name (another
    constant, such as orbits' ``ORBIT_TOLERANCE``, is a default of its own)."""
    written = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if "engine" in path.relative_to(PACKAGE).parts:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            pairs = []
            if isinstance(node, ast.arguments):
                positional = node.posonlyargs + node.args
                pairs += zip(positional[len(positional) - len(node.defaults):], node.defaults)
                pairs += [(a, d) for a, d in zip(node.kwonlyargs, node.kw_defaults) if d]
                pairs = [(arg.arg, default) for arg, default in pairs]
            elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name) \
                    and node.value is not None:
                pairs = [(node.target.id, node.value)]
            written += [f"{path.name}:{default.lineno} {name}" for name, default in pairs
                        if name in SHARED and isinstance(default, ast.Constant)
                        and default.value == SHARED[name]]
    assert written == []
