"""Option types shared by the command line and the benchmark: each refuses a bad value
while the options are read, before any work."""

import argparse


def whole(low: int):
    """An argparse type: a whole number >= ``low``, so that a bad option stops the benchmark
    before any of its work, not in the middle of it."""
    def number(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be a whole number >= {low}, "
                                             f"got {text!r}") from None
        if value < low:
            raise argparse.ArgumentTypeError(f"must be a whole number >= {low}, got {value}")
        return value
    number.__name__ = f"whole number >= {low}"
    return number
