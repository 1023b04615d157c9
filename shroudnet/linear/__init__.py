"""The linear limits of a scene: its modes with every contact open, stuck or closed, their
nodal diameters and Campbell diagram, and the frequency response of the linearised
structure. Linear algebra on the model (and the engine's stick clusters), without
integration: it imports the model and the engine, nothing above.
"""
