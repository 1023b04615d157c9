"""What a scene is: blades and substructures (with their reductions, beams and matrix
files), interfaces, couplings, excitation, prescribed motion, the group graph, the ``Scene``
that bundles them and its lowering to flat arrays. The model imports ``contact_laws`` and
``checked_records``, never the engine or anything above it: a scene is data, checked when it
is built.
"""
