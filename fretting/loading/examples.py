"""The example history files shipped with the package, found by name.

Each example is a history file in ``fretting/examples/`` (with the CSV tables it names); its name
is the file's stem, e.g. ``hertz_shear_cycling``, and its description the first line of its
leading comment. Sweep files are in ``fretting/examples/sweeps/``.
"""

import errno
import os
from pathlib import Path

__all__ = ["EXAMPLES", "example_path", "examples", "resolve_history"]

#: The directory of the shipped examples.
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def examples():
    """The shipped example histories.

    Returns
    -------
    dict of str to str
        Name (the file's stem) to a one-line description (its first comment line), sorted by name.

    Examples
    --------
    >>> "hertz_shear_cycling" in examples()
    True
    """
    return {path.stem: _description(path) for path in sorted(EXAMPLES.glob("*.toml"))}


def example_path(name):
    """The history file of the shipped example `name`.

    Parameters
    ----------
    name : str
        An example's name as listed by `examples`, with or without its ``.toml`` suffix.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    FileNotFoundError
        When no example has that name; its message lists the names.

    Examples
    --------
    >>> example_path("hertz_shear_cycling").name
    'hertz_shear_cycling.toml'
    """
    path = EXAMPLES / f"{name.removesuffix('.toml')}.toml"
    if "/" in name or "\\" in name or not path.is_file():
        names = ", ".join(examples())
        problem = f"{os.strerror(errno.ENOENT)}, nor a shipped example: expected a history file or one of: {names}"
        raise FileNotFoundError(errno.ENOENT, problem, name)
    return path


def resolve_history(file):
    """The history file that `file` (a path, or an example's name) names, as a `pathlib.Path`.

    A file that exists wins over an example of the same name; neither raises
    `FileNotFoundError` as `example_path` does.
    """
    path = Path(file)
    return path if path.exists() else example_path(str(file))


def _description(path):
    """The first line of the comment that opens the file `path`, without its ``#``."""
    with path.open(encoding="utf-8") as lines:
        first = lines.readline()
    return first.removeprefix("#").strip()
