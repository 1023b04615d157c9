"""Independent reference implementations: event-driven ``scipy.integrate.solve_ivp``
solutions of one-mass blade groups, Jenkins elements and small structures, written from the
equations alone. They share no code with the engine (they import at most the model and the
engine's enums) and no product code imports them: they are for the tests and the benchmark.
"""
