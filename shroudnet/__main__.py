"""``python -m shroudnet``: the same as the ``shroudnet`` command."""

from .front.cli import main

raise SystemExit(main())
