"""Plant known bugs one at a time and report which ones the tests miss.

Each mutation edits one line of a copy of the source tree, runs the tests meant to catch
that kind of bug against the copy, and counts as *killed* when a test fails, *hung* when
the tests run past the time limit, and *survived* when they all pass. A surviving
mutation is a bug the test suite cannot see::

    python tests/mutations.py                 # every mutation
    python tests/mutations.py stick-limit     # those whose name contains a word
    python tests/mutations.py --list
    python tests/mutations.py --source DIR    # plant into another checkout's tree

Each run first runs the tests on an unchanged copy (skip it with ``--no-control``): a
test that fails there would kill every mutation and prove nothing.

The copies keep their compiled kernels in one cache folder of their own
(``$SHROUDNET_MUTATION_CACHE``, else ``~/.cache/shroudnet-mutations``), so a second run
compiles only what changed. A mutation of the compiled loop compiles its kernels anew:
count on one to three minutes for each.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: Tests that check the physics, run against every mutation unless it names its own.
PHYSICS_TESTS = (
    "tests/test_contact_laws.py",
    "tests/test_paper_equations.py",
    "tests/test_dynamics_properties.py",
    "tests/test_physics_references.py",
    "tests/test_simulation_errors.py",
    "tests/test_hard_cases.py",
    "tests/test_simulate.py",
    "tests/test_baseline_and_bench.py",
)


@dataclass(frozen=True)
class Mutation:
    """Replace ``old`` by ``new`` (each must occur exactly once) in ``path``."""

    name: str
    path: str
    old: str
    new: str
    why: str


MUTATIONS = (
    Mutation("stick-limit-1.2", "shroudnet/scene.py",
             "f.static_coefficient for f in frictions",
             "1.2 * f.static_coefficient for f in frictions",
             "stuck interfaces hold 20 % more than μ_s N"),
    Mutation("contact-strain-energy-doubled", "shroudnet/simulate.py",
             "return 0.5 * penetration * sum(", "return penetration * sum(",
             "the ledger books twice the contact strain energy"),
    Mutation("stick-rule-slack-0.05", "shroudnet/engine/template.py",
             "if candidates[e] else limit):", "if candidates[e] else 1.05 * limit):",
             "the mode rule keeps a stick the breakaway guard has released"),
    Mutation("friction-slack-0.05", "shroudnet/engine/template.py",
             "FRICTION_SLACK = 1e-9", "FRICTION_SLACK = 0.05",
             "a slip that reaches zero sticks while it needs up to 1.05 μ_s N"),
    Mutation("friction-sign-negative-slip", "shroudnet/engine/template.py",
             "            w.friction[e] = -sliding", "            w.friction[e] = sliding",
             "friction pushes along a negative slip instead of against it"),
    Mutation("projection-loss-dropped", "shroudnet/engine/template.py",
             "    state.energy[PROJECTION] += lost\n    last = log_switches",
             "    last = log_switches",
             "the kinetic energy lost as blades lock together is not booked (expected to "
             "survive: at stick onset it is about m (a τ)², some 1e-20 J)"),
    Mutation("breakaway-logged-as-reversal", "shroudnet/engine/resolve.py",
             "    if before == STICK:\n        return BREAKAWAY",
             "    if before == STICK:\n        return REVERSAL",
             "a breakaway is logged as a slip reversal"),
    Mutation("static-friction-normal-push-sign", "shroudnet/engine/dynamics.py",
             "            imbalance[left[e]] -= push", "            imbalance[left[e]] += push",
             "the normal force's push is added, not taken, in the stuck equilibrium"),
    Mutation("hertz-exponent", "contact_laws/normal.py",
             "    stiffness: float\n    exponent: float = 1.5\n\n    def __post_init__(self):\n"
             "        check_real(\"Hertz\"",
             "    stiffness: float\n    exponent: float = 1.4\n\n    def __post_init__(self):\n"
             "        check_real(\"Hertz\"",
             "Hertz contact with the wrong default exponent"),
    Mutation("exponential-friction-decay", "contact_laws/friction.py",
             "math.exp(-beta * slip_speed)", "math.exp(-beta * slip_speed * 0.5)",
             "the paper's eq. (4) decays at half the rate"),
    Mutation("kelvin-voigt-damping-sign", "contact_laws/normal.py",
             "stiffness * penetration + damping * rate",
             "stiffness * penetration - damping * rate",
             "the contact damper pushes with the closing rate's opposite sign"),
    Mutation("hunt-crossley-damping-dropped", "contact_laws/normal.py",
             "** exponent * (1.0 + damping * rate)", "** exponent * (1.0 + 0.0 * rate)",
             "Hunt–Crossley contact without its damping"),
    Mutation("damping-power-halved", "shroudnet/engine/template.py",
             "damping += s.damping[i] * v[i] * v[i]",
             "damping += 0.5 * s.damping[i] * v[i] * v[i]",
             "the ledger books half the viscous loss"),
)


def _copy_tree(source: Path, target: Path) -> None:
    """The files git tracks, plus untracked ones it does not ignore, as they are now."""
    listed = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"],
                            cwd=source, check=True, capture_output=True).stdout
    for name in filter(None, listed.decode().split("\0")):
        origin = source / name
        if origin.is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(origin, target / name)


#: No change at all: the tests must pass on the copy, or no verdict below means anything.
CONTROL = Mutation("control", "", "", "", "the unchanged source")


def plant(mutation: Mutation, tree: Path) -> bool:
    """Apply ``mutation`` to ``tree``; False when its line is not there (the code moved)."""
    if mutation is CONTROL:
        return True
    path = tree / mutation.path
    text = path.read_text() if path.exists() else ""
    if text.count(mutation.old) != 1:
        return False
    path.write_text(text.replace(mutation.old, mutation.new))
    return True


def run(mutation: Mutation, source: Path, tests, limit: float, cache: Path) -> tuple[str, str]:
    """(verdict, the first failing test or a note) for one mutation."""
    with tempfile.TemporaryDirectory(prefix="shroudnet-mutant-") as folder:
        tree = Path(folder)
        _copy_tree(source, tree)
        if not plant(mutation, tree):
            return "not planted", f"{mutation.old!r} is not once in {mutation.path}"
        present = [t for t in tests if (tree / t).exists()]
        environment = {**os.environ, "PYTHONPATH": str(tree), "SHROUDNET_CACHE": str(cache),
                       "PYTHONDONTWRITEBYTECODE": "1"}
        command = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider",
                   "-o", "addopts=", "-o", f"timeout={int(limit)}", *present]
        try:
            done = subprocess.run(command, cwd=tree, env=environment, capture_output=True,
                                  text=True, timeout=limit)
        except subprocess.TimeoutExpired:
            return "hung", f"tests still running after {limit:.0f} s"
    if done.returncode == 0:
        return "survived", ""
    failed = [line for line in done.stdout.splitlines() if line.startswith("FAILED")]
    return "killed", failed[0].removeprefix("FAILED ") if failed else done.stdout[-300:]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("words", nargs="*", help="run the mutations whose name holds a word")
    parser.add_argument("--list", action="store_true", help="list the mutations and stop")
    parser.add_argument("--source", type=Path, default=ROOT,
                        help="the tree to plant into (default: this checkout)")
    parser.add_argument("--limit", type=float, default=900.0,
                        help="seconds the tests of one mutation may take (default 900)")
    parser.add_argument("--no-control", action="store_true",
                        help="skip the first run on the unchanged source")
    args = parser.parse_args(argv)
    chosen = [m for m in MUTATIONS if not args.words or any(w in m.name for w in args.words)]
    if args.list:
        for m in chosen:
            print(f"{m.name:34s} {m.path:26s} {m.why}")
        return 0
    cache = Path(os.environ.get("SHROUDNET_MUTATION_CACHE")
                 or Path.home() / ".cache" / "shroudnet-mutations")
    if not args.no_control:
        verdict, note = run(CONTROL, args.source.resolve(), PHYSICS_TESTS, args.limit, cache)
        if verdict != "survived":
            print(f"the tests fail on the unchanged source ({verdict}: {note}); fix that first")
            return 2
        print("control: the unchanged source passes", flush=True)
    survivors = 0
    for m in chosen:
        began = time.perf_counter()
        verdict, note = run(m, args.source.resolve(), PHYSICS_TESTS, args.limit, cache)
        survivors += verdict in ("survived", "hung")
        print(f"{m.name:34s} {verdict:11s} {time.perf_counter() - began:6.0f} s  {note}",
              flush=True)
    print(f"{survivors} of {len(chosen)} mutations survived or hung")
    return 1 if survivors else 0


if __name__ == "__main__":
    sys.exit(main())
