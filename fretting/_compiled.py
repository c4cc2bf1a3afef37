"""numba's decorators for the package's compiled kernels, with numba's on-disk cache where it can write one.

With ``cache=True`` numba keeps each compiled kernel in a ``__pycache__`` beside the module, or else in
the user's cache folder, and refuses to decorate (a RuntimeError at import) where it can write in
neither: a read-only installation run by a user whose home is read-only too, as in some containers and
clusters. There the kernels are compiled without the cache, once in each process that uses them: the
same machine code and the same numbers, only the time to compile them again.
"""

import numba


def _cached(decorator, function):
    """`decorator` (a numba decorator factory) applied to `function` with numba's cache, or without it
    where numba finds no folder to write it in."""
    try:
        return decorator(cache=True)(function)
    except RuntimeError:  # "cannot cache function ...: no locator available"
        return decorator()(function)


def njit(function):
    """`function` compiled in nopython mode (``numba.njit``), cached where possible."""
    return _cached(numba.njit, function)


def vectorize(function):
    """`function` of scalars as a ufunc compiled at first use for its argument types (``numba.vectorize``),
    cached where possible."""
    return _cached(numba.vectorize, function)
