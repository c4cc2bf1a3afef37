"""BLAS and LAPACK threads while the engine solves."""

import functools

from threadpoolctl import ThreadpoolController

__all__ = ["BLAS_THREADS", "one_blas_thread"]

#: BLAS and LAPACK threads while the engine solves. Its work is many small products and
#: factorisations, one after another, which threads only slow down (benchmarks/blas_threads.py).
#: Limited with threadpoolctl, which reaches the BLAS already loaded (an environment variable
#: acts only before numpy is imported).
BLAS_THREADS = 1


@functools.cache
def _threads():
    """The controller of the BLAS libraries loaded (found once: a limit through it is cheap)."""
    return ThreadpoolController()


def one_blas_thread():
    """Context in which the BLAS libraries loaded run `BLAS_THREADS` threads (the caller's count after)."""
    return _threads().limit(limits=BLAS_THREADS, user_api="blas")
