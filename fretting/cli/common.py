"""What the commands share: argument types, the options of figures, progress bars, figure files."""

import argparse
import contextlib
import sys

from tqdm import tqdm

from fretting._validate import positive

#: Default resolution of `fretting plot` and `fretting stress --figure` (raster formats): 6.4 x 4.4
#: inch figures at 100 dpi keep results/ of eight examples near 5 MB (7.9 MB at 150 dpi).
FIGURE_DPI = 100
#: Default size [inch] of those figures, and the formats they can be written in (vector: svg, pdf).
FIGURE_SIZE = (6.4, 4.4)
FIGURE_FORMATS = ("png", "svg", "pdf")

#: Seconds a run or a sweep lasts before its progress bar appears: short runs show none.
PROGRESS_DELAY = 2.0


def figure_options():
    """The options of the commands that draw figures: ``--format``, ``--dpi``, ``--size``."""
    figures = argparse.ArgumentParser(add_help=False)
    figures.add_argument(
        "--format", choices=FIGURE_FORMATS, default="png", help="file format of the figures (default: png)"
    )
    figures.add_argument(
        "--dpi", type=at_least(1, int), default=FIGURE_DPI, help=f"resolution of png figures (default {FIGURE_DPI})"
    )
    figures.add_argument(
        "--size",
        nargs=2,
        type=at_least(0.5, float),
        default=FIGURE_SIZE,
        metavar=("WIDTH", "HEIGHT"),
        help=f"figure size in inches (default {FIGURE_SIZE[0]:g} {FIGURE_SIZE[1]:g})",
    )

    return figures


def at_least(minimum, kind):
    """Argument type: a number of `kind` >= `minimum`."""

    def convert(text):
        try:
            value = kind(text)
        except ValueError:
            value = None
        if value is None or not value >= minimum:
            raise argparse.ArgumentTypeError(f"found {text!r}, expected a {kind.__name__} >= {minimum}")
        return value

    return convert


def positive_number(text):
    """Argument type: a finite number > 0 (`fretting._validate.positive`)."""
    try:
        return positive("value", float(text))
    except ValueError:
        raise argparse.ArgumentTypeError(f"found {text!r}, expected a number > 0") from None


@contextlib.contextmanager
def progress_bar(unit, interrupts):
    """``progress(done, total)``, drawing a bar of `unit` on stderr when it is a terminal and the work
    lasts `PROGRESS_DELAY` seconds; each call raises an interrupt dropped since the last one
    (`_Interrupts.check`), so that the work stops there."""
    with tqdm(unit=unit, delay=PROGRESS_DELAY, disable=not sys.stderr.isatty(), file=sys.stderr) as bar:

        def progress(done, total):
            interrupts.check()
            bar.total, bar.n = total, done
            bar.refresh()

        yield progress


def saved(figure, stem, args):
    """Write `figure` as ``<stem>.<args.format>`` at ``args.dpi`` and print its path."""
    path = stem.with_name(f"{stem.name}.{args.format}")
    figure.savefig(path, dpi=args.dpi, format=args.format)
    print(path)


def figure_class():
    """matplotlib's `Figure` on the Agg backend: imported here, when a command draws, not at start-up
    (the other commands do without its start-up time)."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    return Figure
