"""Files: scene files (TOML, ``scenefile``) and result files (``results``: simulations,
sweep stores, branches), each checked field by field as it is read. Files import the
computational layers whose records they hold, never the front; the package's
``shroudnet.scenefile`` and ``shroudnet.results`` are their public faces.
"""
