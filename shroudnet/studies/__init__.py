"""Studies made of many runs: parameter sweeps and bifurcation diagrams (on every core or a
cluster), mistuning statistics and work–precision. A study takes its progress reporter and
its store from its caller and never prints or touches a file itself; it imports
``steady``, ``analysis``, ``linear``, the run layer and the model.
"""
