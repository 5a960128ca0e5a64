"""The command line: `rotbeam simulate`, `sweep`, `critical`, `effects`, `modes`, `bench`,
`damping` and `identify`, one module each; `rotbeam --version`; `python -m rotbeam`."""

from .main import main

__all__ = ["main"]
