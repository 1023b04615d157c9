"""Harmonic balance with alternating frequency–time contact forces, condensed onto the
contacts (DESIGN §8): a module per job —

- ``fourier``: the truncated series and the time samples they are read at;
- ``model``: what harmonic balance needs of a scene, the contacts in coordinates of
  their own;
- ``condensation``: the structure's dynamic compliance at the contacts, per harmonic;
- ``hysteresis``: elastic contacts' sliders marched over a period;
- ``aft``: the contacts' forces in time and their exact Jacobian;
- ``newton``: Newton's method with a line search;
- ``balance``: ``harmonic_balance``, a scene's orbit as a ``HarmonicOrbit`` (``orbit``);
- ``hill``: stability by Hill's method;
- ``continuation``: ``harmonic_continuation``, branches in a parameter with their folds;
- ``certificate``: ``certify``, the exact orbit by shooting from a series, and its error;
- ``sectors``: a tuned ring forced in engine order on one sector, its neighbours'
  harmonics lagging by 2πkl/N.

Continuation in the excitation frequency at a fixed speed needs nothing of its own: a
scene forced at a frequency of its own (``Excitation(frequency=f)``) gives
``model.harmonic_model`` its fundamental. Importing this package imports nothing:
``shroudnet`` exports its public names.
"""
