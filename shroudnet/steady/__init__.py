"""Steady states: periodic orbits by shooting with their Floquet stability, continuation
along a parameter with its folds and bifurcations, the cyclic-symmetry reduction of tuned
rings, a cycle's extremes and per-cycle outputs (energy, damping, harmonics), and
harmonic balance (``harmonic``: series condensed onto the contacts, their continuation,
Hill's stability, and their certificate by exact shooting). It imports
``analysis``, ``linear``, the run layer, the engine and the model, never studies, files or
the front.
"""
