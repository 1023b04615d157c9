"""Running a scene: ``simulate``, the ``Simulation`` record with its event log and energy
ledger, the integration methods, the checks of scale and memory made before any work, and
the records a run or a sweep point returns (``classification``, the ``reporting`` protocol a
long computation reports to). The run layer imports the engine and the model, nothing above:
a run record is read, saved and loaded without any study.
"""
