"""How many threads the linear algebra of rotbeam's work uses: one, whoever calls it.

The matrices are small (n <= 2 N); a second BLAS thread only adds synchronisation, and on a
busy machine it waits for a core (docs/numerics.md, "One BLAS thread").  The command line and
the workflow set the thread variables before numpy loads; `one_blas_thread` does the same for a
caller of the Python API whose numpy is loaded already, around the work only.
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable
from typing import Any, TypeVar

F = TypeVar("F", bound=Callable[..., Any])

#: the BLAS threads inside the work
THREADS = 1

_depth = threading.local()


def one_blas_thread(func: F) -> F:
    """Run `func` with the BLAS and OpenMP pools held to THREADS, the caller's setting restored
    on return (and on an exception).

    The pools are found once a process (numpy's and scipy's BLAS: 5 ms); a limit then costs
    0.04 ms, and nested calls limit once.

    Parameters
    ----------
    func : callable
        A public entry point that does numerical work.

    Returns
    -------
    callable
        `func` with the same signature and docstring.
    """

    @functools.wraps(func)
    def limited(*args: Any, **kwargs: Any) -> Any:
        if getattr(_depth, "n", 0):
            return func(*args, **kwargs)
        _depth.n = 1
        try:
            with _controller().limit(limits=THREADS):
                return func(*args, **kwargs)
        finally:
            _depth.n = 0

    return limited  # type: ignore[return-value]


@functools.lru_cache(maxsize=1)
def _controller() -> Any:
    """The thread pools of the loaded BLAS libraries (numpy's and scipy's), found once."""
    import scipy.linalg  # noqa: F401 - loads scipy's BLAS, so that its pool is found too
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()
