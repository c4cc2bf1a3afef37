"""The command line: ``fretting run | validate | info | plot | stress | examples`` (also ``python -m fretting``).

Exit codes: 0 success, 2 bad input (files, keys, values, arguments), 3 gross slip, 1 a solver
failure, 130 interrupted. Errors are one line on stderr; ``--debug`` shows the traceback.
"""

import argparse
import json
import signal
import sys
import threading
from pathlib import Path

import numpy as np
import xarray as xr
from tqdm import tqdm

from fretting import __version__
from fretting._validate import positive
from fretting.analysis import nucleation
from fretting.analysis.fatigue import (
    CRITERIA,
    Material,
    MaterialFileError,
    apply,
    hot_spot,
    line_method,
    point_method,
)
from fretting.analysis.stress import BULK_STATES, COMPONENTS, field
from fretting.engine.recorder import (
    CYCLE_FIELDS_EXPECTED,
    CYCLE_FIELDS_STORED,
    RECORD_ALL_STEPS,
    RECORDED_ENDS,
    CycleFields,
)
from fretting.engine.runner import CHECKPOINT_SECONDS, run_file
from fretting.errors import FrettingError, GrossSlipError, HistoryError, MissingDependencyError
from fretting.loading.examples import examples, resolve_history
from fretting.loading.history_file import read_history_source
from fretting.models import Grid, Mesh
from fretting.models.collocation import DEFAULT_NODES
from fretting.models.galerkin import DEFAULT_RTOL, MAX_DEFAULT_MESH, MAX_DEFAULT_WORK
from fretting.results.io import ResultError, load, save
from fretting.studies.sweeps import add_arguments as add_sweep_arguments
from fretting.studies.sweeps import run as run_sweep

__all__ = ["main"]

EXIT_FAILURE, EXIT_INPUT, EXIT_GROSS_SLIP, EXIT_INTERRUPTED = 1, 2, 3, 130

#: Default resolution of `fretting plot` and `fretting stress --figure` (raster formats): 6.4 x 4.4
#: inch figures at 100 dpi keep results/ of eight examples near 5 MB (7.9 MB at 150 dpi).
FIGURE_DPI = 100
#: Default size [inch] of those figures, and the formats they can be written in (vector: svg, pdf).
FIGURE_SIZE = (6.4, 4.4)
FIGURE_FORMATS = ("png", "svg", "pdf")

#: Default grid of `fretting stress`: points along x and in depth, the depth and the half-span in
#: half-widths a (two half-widths hold the peak shear under the contact and the edge gradients).
STRESS_NX, STRESS_NZ, STRESS_DEPTH, STRESS_SPAN = 201, 101, 2.0, 2.0

#: Criterion of `fretting stress --material` without --criterion: SWT needs only E and nu.
DEFAULT_CRITERION = "swt"

#: Seconds a run lasts before its progress bar appears: short runs show none.
PROGRESS_DELAY = 2.0


def main(argv=None):
    """Run the command line with the arguments `argv` (``sys.argv[1:]`` when None); return the exit code.

    Ctrl-C is `_Interrupts`': never lost, and said in one line. With `argv` None (the process's own
    command line), an interrupt after the work is done is ignored: it would only kill the exiting
    interpreter, with a traceback or none.
    """
    args = _parser().parse_args(argv)
    with _Interrupts() as interrupts:
        code = _main(args, interrupts)
    if argv is None and threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    return code


class _Interrupts:
    """SIGINT, while the block runs in the main thread: KeyboardInterrupt as Python's own handler raises
    it, and remembered, so that one raised where Python cannot pass it on (a weakref callback or a
    ``__del__``, which it reports as "Exception ignored" and drops: h5py and xarray run both) is
    raised again at the next `check`, not lost, and is not reported there."""

    def __init__(self):
        self.lost = False

    def __enter__(self):
        self._main = threading.current_thread() is threading.main_thread()
        if self._main:
            self._handler = signal.signal(signal.SIGINT, self._interrupted)
            self._hook, sys.unraisablehook = sys.unraisablehook, self._unraisable
        return self

    def __exit__(self, *exception):
        if self._main:
            signal.signal(signal.SIGINT, self._handler)
            sys.unraisablehook = self._hook

    def _interrupted(self, signum, frame):
        self.lost = True  # until it is seen to pass (`passed`)
        raise KeyboardInterrupt

    def _unraisable(self, unraisable):
        if not issubclass(unraisable.exc_type, KeyboardInterrupt):
            self._hook(unraisable)

    def passed(self):
        """The interrupt raised was caught where it is handled: none is lost."""
        self.lost = False

    def check(self):
        """Raise KeyboardInterrupt if an interrupt was dropped since the last `passed`."""
        if self.lost:
            raise KeyboardInterrupt


def _main(args, interrupts):
    """`main` of the parsed arguments `args`."""
    args.interrupts = interrupts
    try:
        args.command(args)
        interrupts.check()
    except KeyboardInterrupt as interrupt:
        interrupts.passed()
        return _fail(args, interrupt, f"interrupted{f': {interrupt}' if interrupt.args else ''}", EXIT_INTERRUPTED)
    except GrossSlipError as error:
        return _fail(args, error, f"{args.file}: {error}", EXIT_GROSS_SLIP)
    except OSError as error:
        return _fail(args, error, f"{error.filename or args.file}: {error.strerror or error}", EXIT_INPUT)
    except (HistoryError, ResultError, MaterialFileError, MissingDependencyError) as error:
        return _fail(args, error, str(error), EXIT_INPUT)
    except FrettingError as error:
        return _fail(args, error, f"{args.file}: {error}", EXIT_FAILURE)
    return 0


def _fail(args, error, message, code):
    if args.debug:
        raise error
    print(f"fretting: error: {message}", file=sys.stderr)
    return code


def _parser():
    parser = argparse.ArgumentParser(
        prog="fretting", description="Partial-slip half-plane contacts under shear and bulk-tension histories."
    )
    parser.add_argument("--version", action="version", version=f"fretting {__version__}")
    commands = parser.add_subparsers(title="commands", required=True, metavar="COMMAND")
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--debug", action="store_true", help="show the traceback of an error")
    figures = argparse.ArgumentParser(add_help=False)
    figures.add_argument(
        "--format", choices=FIGURE_FORMATS, default="png", help="file format of the figures (default: png)"
    )
    figures.add_argument(
        "--dpi", type=_at_least(1, int), default=FIGURE_DPI, help=f"resolution of png figures (default {FIGURE_DPI})"
    )
    figures.add_argument(
        "--size",
        nargs=2,
        type=_at_least(0.5, float),
        default=FIGURE_SIZE,
        metavar=("WIDTH", "HEIGHT"),
        help=f"figure size in inches (default {FIGURE_SIZE[0]:g} {FIGURE_SIZE[1]:g})",
    )

    run = commands.add_parser("run", parents=[common], help="run a history file and write its result")
    run.add_argument("file", metavar="HISTORY", help="history file (TOML), or the name of a shipped example")
    run.add_argument(
        "-o", "--output", metavar="OUT", help="result file (default: <history stem>.h5 in the current folder)"
    )
    run.add_argument("--resume", action="store_true", help="continue an interrupted run from its checkpoint")
    model = run.add_mutually_exclusive_group()
    model.add_argument(
        "--nodes",
        type=_at_least(4, int),
        help=f"solve on a fixed grid of this many Gauss-Chebyshev collocation nodes instead (e.g. {DEFAULT_NODES})",
    )
    model.add_argument(
        "--rtol",
        type=_positive,
        help=f"relative accuracy of the energy asked of the P1 Galerkin model, on a mesh adapted to "
        f"the whole history (default: the exact model where Q alone loads a symmetric profile, else "
        f"{DEFAULT_RTOL:g}; a coarser mesh, said in a note, where that mesh would exceed {MAX_DEFAULT_MESH} "
        f"nodes or its run {MAX_DEFAULT_WORK:.2g} nodes squared times increments)",
    )
    run.add_argument(
        "--record",
        choices=("default", "all"),
        default="default",
        help=f"steps whose fields are stored: default every step of histories up to {RECORD_ALL_STEPS} steps, "
        f"else the first and last {RECORDED_ENDS}; energy and slip range per cycle always cover every cycle",
    )
    run.add_argument(
        "--checkpoint-interval",
        type=_at_least(0, float),
        default=CHECKPOINT_SECONDS,
        metavar="SECONDS",
        help=f"seconds between checkpoints (default {CHECKPOINT_SECONDS:g}; 0: after every chunk of steps)",
    )
    run.add_argument(
        "--every-step",
        action="store_true",
        help="solve every step (default: the steps inside straight stretches that are not recorded are skipped; "
        "the energy, w, slip range and q_peak are the same, the sigma_xx peaks per cycle are then not tallied)",
    )
    run.add_argument(
        "--cycle-fields",
        type=_cycle_fields,
        default="default",
        metavar="POLICY",
        help=f"cycles whose fields (w, slip amplitude, peaks) are stored: default every cycle of histories up to "
        f"{CYCLE_FIELDS_STORED} cycles, else first,last,every=K,maxima with K = cycles / {CYCLE_FIELDS_STORED} "
        f"rounded up; all; or a list of first, last, every=K, maxima. Energy per cycle, w_total and the fields' "
        f"maxima always cover every cycle",
    )
    run.set_defaults(command=_run)

    validate = commands.add_parser("validate", parents=[common], help="check a history file without running it")
    validate.add_argument("file", metavar="HISTORY", help="history file (TOML), or the name of a shipped example")
    validate.set_defaults(command=_validate)

    info = commands.add_parser("info", parents=[common], help="describe a result file")
    info.add_argument("file", metavar="RESULT", help="result file written by `fretting run`")
    info.set_defaults(command=_info)

    plot = commands.add_parser("plot", parents=[common, figures], help="draw a result as figure files")
    plot.add_argument("file", metavar="RESULT", help="result file written by `fretting run`")
    plot.add_argument("-o", "--output", metavar="DIR", help="directory of the figures (default: the result's)")
    plot.add_argument(
        "--body",
        type=int,
        choices=(1, 2),
        help="body of the surface-stress figure: 1 (traction q) or 2 (-q) "
        "(default: the specimen, with its bulk stress)",
    )
    plot.set_defaults(command=_plot)

    _stress_parser(commands, common, figures)

    listing = commands.add_parser("examples", parents=[common], help="list the shipped example histories")
    listing.set_defaults(command=_examples, file="examples")

    sweep = commands.add_parser("sweep", parents=[common], help="run a sweep file on dask.distributed")
    add_sweep_arguments(sweep)
    sweep.set_defaults(command=run_sweep)
    return parser


def _stress_parser(commands, common, figures):
    stress = commands.add_parser(
        "stress", parents=[common, figures], help="write the stress field under the surface of a result (and a figure)"
    )
    stress.add_argument("file", metavar="RESULT", help="result file written by `fretting run`")
    stress.add_argument("-o", "--output", metavar="OUT", help="field file (default: <result stem>_stress.h5 beside it)")
    stress.add_argument("--nx", type=_at_least(2, int), default=STRESS_NX, help=f"points along x (default {STRESS_NX})")
    stress.add_argument("--nz", type=_at_least(2, int), default=STRESS_NZ, help=f"depths (default {STRESS_NZ})")
    stress.add_argument(
        "--depth",
        type=_positive,
        default=STRESS_DEPTH,
        help=f"largest depth, in half-widths a (default {STRESS_DEPTH:g})",
    )
    stress.add_argument(
        "--span",
        type=_positive,
        default=STRESS_SPAN,
        help=f"x from centre - SPAN a to centre + SPAN a (default {STRESS_SPAN:g})",
    )
    stress.add_argument(
        "--step",
        type=_at_least(0, int),
        nargs="+",
        help="recorded steps (default: those of the last load cycle recorded whole, from its starting state, "
        "else the last step)",
    )
    stress.add_argument(
        "--body", choices=("specimen", "pad"), default="specimen", help="body of the field (default: the specimen)"
    )
    stress.add_argument("--nu", type=float, help="Poisson's ratio (default: the nu the result records)")
    stress.add_argument(
        "--bulk-state",
        choices=tuple(state.replace(" ", "-") for state in BULK_STATES),
        default="plane-strain",
        help="state of the specimen's bulk stress: plane-strain (held across its width, the default) or "
        "plane-stress (free across it, as a bar in tension); the contact's field is in plane strain either way",
    )
    stress.add_argument(
        "--material",
        metavar="FILE",
        help="material file (TOML, keys of fretting.analysis.fatigue.Material): map fatigue criteria over the steps, "
        "taken as one cycle, and read them at the critical distance when it gives critical_distance",
    )
    stress.add_argument(
        "--criterion",
        nargs="+",
        choices=tuple(CRITERIA),
        help=f"criteria mapped with --material (default: {DEFAULT_CRITERION})",
    )
    stress.add_argument(
        "--figure",
        choices=(*COMPONENTS, *CRITERIA),
        help="also draw this component at the last step, or this criterion's map (with --material), "
        "as <OUT stem>_<name>.<format>",
    )
    stress.set_defaults(command=_stress, usage_error=stress.error)


def _at_least(minimum, kind):
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


def _positive(text):
    """Argument type: a finite number > 0 (`fretting._validate.positive`)."""
    try:
        return positive("value", float(text))
    except ValueError:
        raise argparse.ArgumentTypeError(f"found {text!r}, expected a number > 0") from None


def _model(args):
    """The model spec the arguments ask for (None: the default)."""
    if args.nodes is not None:
        return Grid(args.nodes)
    return None if args.rtol is None else Mesh(rtol=args.rtol)


def _examples(args):
    for name, description in examples().items():
        print(f"{name:<32} {description}")


def _cycle_fields(text):
    """`text` once `fretting.engine.recorder.CycleFields` reads it as a policy; argparse's error otherwise."""
    try:
        CycleFields.parse(text, 0)
    except ValueError as error:
        raise argparse.ArgumentTypeError(f"expected {CYCLE_FIELDS_EXPECTED}, found {text!r}") from error
    return text


def _run(args):
    history = resolve_history(args.file)
    output = Path(args.output or f"{history.stem}.h5")
    record = None if args.record == "default" else args.record
    with tqdm(unit="step", delay=PROGRESS_DELAY, disable=not sys.stderr.isatty(), file=sys.stderr) as bar:

        def progress(done, total):
            args.interrupts.check()  # after each chunk: an interrupt dropped in it stops the run here
            bar.total, bar.n = total, done
            bar.refresh()

        run = run_file(
            history,
            output,
            _model(args),
            record=record,
            resume=args.resume,
            checkpoint_interval=args.checkpoint_interval,
            progress=progress,
            every_step=args.every_step,
            cycle_fields=args.cycle_fields,
        )
    for note in run.notes:
        print(f"fretting: note: {note}", file=sys.stderr)
    result = run.result
    print(f"{output}: {result.attrs['steps'] - 1} steps, {_cycles(result)} cycles, {_dissipated(result)}")


def _validate(args):
    source = read_history_source(resolve_history(args.file))
    contact, history = source.contact, source.history
    print(f"{source.path}: {contact.profile!r}, a = {contact.a:.4g} m, p0 = {contact.p0:.4g} Pa")
    print(f"  {len(history) - 1} steps, {history.vertex_step.size} vertices, {history.cycle_count} cycles")
    print(f"  {_peaks(*history.largest_loads(), contact.f, contact.P, contact.p0)}")
    fP = contact.f * contact.P
    step = history.first_step(lambda Q, sigma: np.abs(Q) >= fP)
    if step is not None:
        Q, sigma, _, _ = history.at([step])
        raise GrossSlipError(step, float(Q[0]), float(sigma[0]), fP)


def _info(args):
    result = load(args.file)
    attrs = result.attrs
    versions = json.loads(attrs.get("versions", "{}"))
    lines = {
        "history": f"{attrs.get('history_file', '?')} (sha256 {attrs.get('history_sha256', '?')})",
        "contact": f"{attrs['profile']}, E_star = {attrs['E_star']:.4g} Pa, f = {attrs['f']:.4g}, "
        f"P = {attrs['P']:.4g} N/m",
        "solution": f"a = {attrs['a']:.4g} m, centre = {attrs['centre']:.4g} m, p0 = {attrs['p0']:.4g} Pa",
        "model": f"{attrs['model']} ({attrs.get('model_description', '')}), {attrs['nodes']} nodes"
        + (f"; fell back: {attrs['model_fallback']}" if "model_fallback" in attrs else "")
        + (f"; mesh {attrs['model_sample']}" if "model_sample" in attrs else ""),
        "steps": f"{result.attrs['steps'] - 1} steps ({result.sizes['step']} recorded), "
        f"{result.sizes['vertex']} vertices, {_cycles(result)} cycles",
        "loads": _peaks(result.Q.values, result.sigma.values, attrs["f"], attrs["P"], attrs["p0"]),
        "energy": _dissipated(result),
        "created": attrs.get("created", "?"),
        "versions": ", ".join(f"{name} {version}" for name, version in versions.items()),
    }
    print(args.file)
    for name, text in lines.items():
        print(f"  {name:<9} {text}")


def _plot(args):
    import matplotlib  # here, not at the top: the other commands do without its start-up time

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from fretting import plots

    result = load(args.file)
    directory = Path(args.output) if args.output else Path(args.file).parent
    directory.mkdir(parents=True, exist_ok=True)
    for name in plots.figures_for(result):
        figure = Figure(figsize=args.size, layout="constrained")
        options = {"body": args.body} if name == "surface_stress" else {}
        plots.FIGURES[name](result, ax=figure.subplots(), **options)
        _saved(figure, directory / f"{Path(args.file).stem}_{name}", args)


def _saved(figure, stem, args):
    """Write `figure` as ``<stem>.<args.format>`` at ``args.dpi`` and print its path."""
    path = stem.with_name(f"{stem.name}.{args.format}")
    figure.savefig(path, dpi=args.dpi, format=args.format)
    print(path)


def _stress(args):
    criteria = _stress_criteria(args)
    material = Material.from_file(args.material) if criteria else None
    result = load(args.file)
    a, centre = result.attrs["a"], result.attrs["centre"]
    x = centre + a * np.linspace(-args.span, args.span, args.nx)
    z = a * np.linspace(0.0, args.depth, args.nz)
    specimen = nucleation.specimen(result)
    body = specimen if args.body == "specimen" else 3 - specimen
    try:
        stresses = field(
            result,
            x,
            z,
            step=args.step or _last_cycle(result),
            body=body,
            nu=args.nu,
            bulk_state=args.bulk_state.replace("-", " "),
        )
    except ValueError as error:
        raise ResultError(f"{args.file}: {error}") from None
    written = xr.merge([stresses, *(_criterion_map(stresses, name, material, args.material) for name in criteria)])
    output = Path(args.output or Path(args.file).with_name(f"{Path(args.file).stem}_stress.h5"))
    save(written, output)
    print(
        f"{output}: {stresses.sizes['step']} steps, {stresses.sizes['z']} x {stresses.sizes['x']} points, "
        f"body {body} ({args.body}), "
        f"bulk stress in {stresses.attrs['bulk_state']}"
    )
    for name in criteria:
        print(_critical_distances(name, written[name]))
    if args.figure:
        import matplotlib  # as in _plot: only when a figure is asked for

        matplotlib.use("Agg")
        from matplotlib.figure import Figure

        from fretting import plots

        figure = Figure(figsize=args.size, layout="constrained")
        plots.stress_map(written[args.figure], result, step=int(written.step[-1]), ax=figure.subplots())
        _saved(figure, output.with_name(f"{output.stem}_{args.figure}"), args)


def _stress_criteria(args):
    """The criteria `fretting stress` maps: --criterion (default `DEFAULT_CRITERION`) and a --figure of one."""
    if args.material is None:
        if args.criterion or args.figure in CRITERIA:
            option = "--criterion" if args.criterion else f"--figure {args.figure}"
            args.usage_error(f"{option}: a criterion needs --material FILE (the material's constants)")
        return []
    criteria = list(dict.fromkeys(args.criterion or [DEFAULT_CRITERION]))
    return criteria + ([args.figure] if args.figure in CRITERIA and args.figure not in criteria else [])


def _criterion_map(stresses, name, material, path):
    """`fretting.analysis.fatigue.apply` over the field's steps, its variables renamed ``<name>`` (the parameter)
    and ``<name>_<variable>``, the parameter's attributes holding its critical distances."""
    try:
        maps = apply(stresses, name, material)
    except ValueError as error:  # a constant the criterion needs is missing from the file
        raise MaterialFileError(path, None, str(error).removeprefix("material: ")) from None
    maps = maps.rename({variable: name if variable == "parameter" else f"{name}_{variable}" for variable in maps})
    maps[name].attrs.update(_distances(maps[name], material, path))
    return maps


def _distances(parameter, material, path):
    """The surface hot spot, and the point and line methods below it (`fretting.analysis.fatigue`) when the material
    gives ``L``, as attributes [the parameter's units, m]."""
    value, x_hot = hot_spot(parameter)
    attributes = {"hot_spot": value, "x_hot": x_hot}
    L = material.critical_distance
    if L is None:
        return attributes
    try:
        point, line = point_method(parameter, L, x_hot=x_hot), line_method(parameter, L, x_hot=x_hot)
    except ValueError:
        reach = f"expected 2 L = {2 * L:.6g} m within the grid's depth {float(parameter.z[-1]):.6g} m (raise --depth)"
        raise MaterialFileError(path, "critical_distance", f"found {L!r} m, {reach}") from None
    return attributes | {"critical_distance": L, "point_method": point.value, "line_method": line.value}


def _critical_distances(name, parameter):
    """One line: a criterion's hot spot and its values at the critical distance."""
    attrs, units = parameter.attrs, parameter.attrs["units"]
    line = f"{name}: hot spot {attrs['hot_spot']:.6g} {units} at x = {attrs['x_hot']:.6g} m"
    if "critical_distance" not in attrs:
        return f"{line}; no critical distance (the material gives none)"
    return (
        f"{line}; point method (L/2 = {attrs['critical_distance'] / 2:.6g} m below it) "
        f"{attrs['point_method']:.6g} {units}; line method (mean over 2 L) {attrs['line_method']:.6g} {units}"
    )


def _last_cycle(result):
    """Steps of the last load cycle recorded whole, from its starting state; else the last step."""
    if "cycle_number" in result.dims and result.sizes["cycle_number"]:
        rows = nucleation.complete_cycles(result)[-1]
        if rows is not None:
            return result.step.values[rows].tolist()
    return [int(result.step[-1])]


def _peaks(Q, sigma, f, P, p0):
    """The largest loads of a history, relative to those of gross slip."""
    psi, tau = np.abs(Q).max() / (f * P), np.abs(sigma).max() / (f * p0)
    return f"max |Q| / (f P) = {psi:.3g}, max |sigma| / (f p0) = {tau:.3g}"


def _cycles(result):
    return result.cycle_dissipation.size if "cycle_dissipation" in result else 0


def _dissipated(result):
    total = f"dissipated {float(result.total_dissipation):.4g} J/m"
    if _cycles(result):
        return f"{total}, {float(result.cycle_dissipation[-1]):.4g} J/m in the last cycle"
    return total
