"""The log of one workflow job: what it read, what it wrote, how long it took, and why it failed.

Every workflow script runs inside ``job_log(snakemake.log[0], snakemake.input, snakemake.output,
snakemake.rule)`` (after PyPSA-Eur's ``configure_logging(snakemake)``).  It takes the plain fields
of the snakemake object, not the object: rotbeam does not import snakemake.  The log goes to the
file the rule declares; Python warnings and the traceback of an exception go there too, so that
a failed job's log says why it failed.
"""

from __future__ import annotations

import logging
import os
import time
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path

FORMAT = "%(asctime)s %(levelname)s %(message)s"


def _describe(path: str) -> str:
    p = Path(path)
    return f"{path} ({p.stat().st_size} bytes)" if p.is_file() else f"{path} (missing)"


@contextmanager
def job_log(
    log_file: str | os.PathLike, inputs: Iterable = (), outputs: Iterable = (), job: str = "job"
) -> Iterator[logging.Logger]:
    """Log the job to ``log_file`` (overwritten) and yield its logger.  On entry: the inputs; on
    exit: each output with its size (or `missing`), wall and CPU time; an exception is logged
    with its traceback and raised again.

    Parameters
    ----------
    log_file : str or PathLike
        The rule's log file; its folder is created if missing.
    inputs : iterable
        The job's input files (``snakemake.input``).
    outputs : iterable
        The job's output files (``snakemake.output``).
    job : str
        The job's name in the log (``snakemake.rule``).

    Yields
    ------
    logging.Logger
        The job's logger, ``rotbeam.job.<job>``.
    """
    inputs, outputs = [str(f) for f in inputs], [str(f) for f in outputs]
    Path(log_file).parent.mkdir(parents=True, exist_ok=True)
    handler = logging.FileHandler(log_file, mode="w", encoding="utf-8")
    handler.setFormatter(logging.Formatter(FORMAT))
    # rotbeam's own messages from INFO, other libraries' (matplotlib's font notes) from WARNING
    root, ours = logging.getLogger(), logging.getLogger("rotbeam")
    old_levels = root.level, ours.level
    root.addHandler(handler)
    root.setLevel(logging.WARNING)
    ours.setLevel(logging.INFO)
    logging.captureWarnings(True)
    log = logging.getLogger(f"rotbeam.job.{job}")
    wall, cpu = time.perf_counter(), time.process_time()
    try:
        log.info("%s: reading %d input(s)", job, len(inputs))
        for f in inputs:
            log.info("  read %s", _describe(f))
        yield log
    except BaseException:
        log.exception("%s failed after %.2f s", job, time.perf_counter() - wall)
        raise
    else:
        log.info("%s: wrote %d output(s)", job, len(outputs))
        for f in outputs:
            log.info("  wrote %s", _describe(f))
        log.info(
            "%s: done in %.2f s (CPU %.2f s)",
            job,
            time.perf_counter() - wall,
            time.process_time() - cpu,
        )
    finally:
        logging.captureWarnings(False)
        root.removeHandler(handler)
        root.setLevel(old_levels[0])
        ours.setLevel(old_levels[1])
        handler.close()
