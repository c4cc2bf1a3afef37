"""The example history files shipped with the package, found by name.

Each example is a history file in the ``histories/`` folder of the source tree (with the CSV
tables it names); its name is the file's stem, e.g. ``hertz_shear_cycling``, and its description
the first line of its leading comment. Sweep files of these histories are in ``histories/sweeps/``,
the illustrative material of the fatigue criteria in ``histories/materials/``. The wheel installs
the folder as ``fretting/histories/`` (pyproject.toml maps the one to the other), so examples run
by name from any folder.
"""

import errno
import os
import shutil
from pathlib import Path

from fretting.loading.history_file import read_history_data

__all__ = ["EXAMPLES", "copy_example", "example_path", "examples", "resolve_history"]

_PACKAGE = Path(__file__).resolve().parents[1]

#: The folder of the shipped examples: ``fretting/histories/`` where the package is installed from
#: a wheel, else ``histories/`` beside the package (a source tree, or an editable install of one).
EXAMPLES = _PACKAGE / "histories" if (_PACKAGE / "histories").is_dir() else _PACKAGE.parent / "histories"


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


def copy_example(name, folder="."):
    """Copy the shipped example `name`, with the tables it names, into `folder`: an editable copy.

    Parameters
    ----------
    name : str
        An example's name (`example_path`).
    folder : str or os.PathLike
        Where the copies go; made if missing.

    Returns
    -------
    list of pathlib.Path
        The files written: the history file first, then its tables.

    Raises
    ------
    FileExistsError
        When a file of that name is already in `folder`: nothing is copied then.
    FileNotFoundError
        When no example has that name (`example_path`).
    """
    history, folder, tables = example_path(name), Path(folder), []
    read_history_data(history, history.read_text(encoding="utf-8"), None, tables)  # the tables it reads
    sources = [history, *dict.fromkeys(tables)]
    targets = [folder / source.relative_to(history.parent) for source in sources]
    for target in targets:
        if target.exists():
            raise FileExistsError(errno.EEXIST, f"{os.strerror(errno.EEXIST)}, not overwritten by the example", target)
    for source, target in zip(sources, targets, strict=True):
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(source, target)
    return targets


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
