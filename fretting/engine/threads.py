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
def _blas():
    """The controllers of the BLAS libraries loaded (found once: a limit through them is cheap)."""
    return tuple(ThreadpoolController().select(user_api="blas").lib_controllers)


class one_blas_thread:  # noqa: N801 - a context used as a function, as threadpoolctl's limits are
    """Context in which the BLAS libraries loaded run `BLAS_THREADS` threads (the caller's count after).

    Each library is asked for its count and set only where it differs, so that entering costs two
    calls into each library rather than threadpoolctl's inventory of all of them: `Stepper.step`
    enters it at every increment.
    """

    __slots__ = ("_changed",)

    def __enter__(self):
        self._changed = []
        for library in _blas():
            threads = library.get_num_threads()
            if threads != BLAS_THREADS:
                library.set_num_threads(BLAS_THREADS)
                self._changed.append((library, threads))
        return self

    def __exit__(self, *exc):
        for library, threads in self._changed:
            if threads is not None:
                library.set_num_threads(threads)
        return False
