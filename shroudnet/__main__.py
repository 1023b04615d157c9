"""``python -m shroudnet``: the same as the ``shroudnet`` command."""

from .cli import main

raise SystemExit(main())
