"""What accuracy costs: error against CPU time for every integrator setting.

Run: python examples/work_precision.py [OUTPUT_FOLDER]
The paper's group in a period-1 (γ1 = 1), a period-3 (γ1 = 3.5) and a chaotic (γ1 = 8.8)
regime, each run with fixed-step RK4 over its steps per period, adaptive Dormand–Prince
over rtol, the adaptive integrator over the event tolerance, regularised friction over
v_ε, and ``Accuracy`` at the targets it promises. Errors are against a reference at
rtol = 1e-13 and an event tolerance of 1e-12. Saves work_precision.png in OUTPUT_FOLDER
(default examples/output/) and prints the cheapest setting of each kind for 1e-2, 1e-4 and
1e-6 (takes about 4 minutes).
"""

import sys
from pathlib import Path

from shroudnet.front.figures import work_precision_diagram
from shroudnet.studies.precision import default_settings, paper_regimes, study, summary

OUTPUT = Path(__file__).resolve().parent / "output"


def compute(transient=300, record=100, chaotic_record=2000, repeats=3, progress=None):
    """Every default setting measured in the paper's three regimes (a ``precision.Study``)."""
    regimes = paper_regimes(transient=transient, record=record, chaotic_record=chaotic_record)
    return study(regimes, default_settings(), repeats=repeats, progress=progress)


def main(transient=300, record=100, chaotic_record=2000, repeats=3, output=OUTPUT):
    """Compute, print the tables and save the diagram in ``output``; returns the study."""
    result = compute(transient, record, chaotic_record, repeats, progress=print)

    print("\nThe cheapest setting of each kind within each relative error (CPU time of one "
          "core):\n")
    print("| regime | error ≤ | setting | ms per period | error |")
    print("|---|---|---|---|---|")
    for regime, target, family, label, milliseconds, error in summary(result):
        setting = f"{family}: {label}" if label else "no setting"
        print(f"| {regime} | {target:g} | {setting} | {milliseconds:.3f} | {error:.1e} |")

    print("\nThe event tolerance alone (adaptive, rtol = 1e-12): relative error")
    for regime in result.floors:
        errors = ", ".join(f"{m.setting.label.split()[-1]}: {m.error:.1e}"
                           for m in result.measurements
                           if m.regime == regime and m.setting.family == "event tolerance")
        print(f"  {regime}: {errors}")
    for regime, floor in result.floors.items():
        if floor > 0.0:
            print(f"\n{regime}: two exact records of {chaotic_record} periods differ by "
                  f"{floor:.1e}; no setting can be judged below that.")

    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    work_precision_diagram(result).savefig(output / "work_precision.png", dpi=110)
    print(f"\nsaved {output / 'work_precision.png'}")
    return result


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
