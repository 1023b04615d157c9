"""What one reads off a run: spectra, classification of the motion, hysteresis loops and
the friction loss per cycle (``readings``), and the tangent flow's monodromy and Lyapunov
exponents (``stability``). It imports the run layer, the engine and the model, nothing
above.
"""
