"""The command line: ``fretting run | validate | info | plot | examples`` (also ``python -m fretting``).

Exit codes: 0 success, 2 bad input (files, keys, values, arguments), 3 gross slip, 1 a solver
failure, 130 interrupted. Errors are one line on stderr; ``--debug`` shows the traceback.
"""

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
from tqdm import tqdm

from fretting import __version__
from fretting._validate import positive
from fretting.bench import add_arguments as add_bench_arguments
from fretting.bench import run as run_bench
from fretting.errors import FrettingError, GrossSlipError, HistoryError
from fretting.loading.examples import examples, resolve_history
from fretting.loading.history_file import read_history_source
from fretting.results.io import Joiner, ResultError, load, save, source_attributes
from fretting.models.exact import MODEL as MASING_MODEL
from fretting.engine.simulation import (
    DEFAULT_NODES,
    DEFAULT_RTOL,
    MAX_DEFAULT_MESH,
    RECORD_ALL_STEPS,
    RECORDED_ENDS,
    adapted_mesh,
    default_model,
    final_state,
    recorded_steps,
    simulate,
)
from fretting.studies.sweeps import add_arguments as add_sweep_arguments
from fretting.studies.sweeps import run as run_sweep

__all__ = ["main"]

EXIT_FAILURE, EXIT_INPUT, EXIT_GROSS_SLIP, EXIT_INTERRUPTED = 1, 2, 3, 130

#: Steps of the first chunk run at a time: how often the progress bar moves and a checkpoint
#: can be written. A chunk that takes less than CHUNK_SECONDS doubles the next one's steps, so
#: that runs whose cycles repeat (copied, not solved) are not cut into many short runs, each of
#: which solves its first cycles anew.
CHUNK_STEPS = 200
CHUNK_SECONDS = 1.0
#: Most steps of one chunk: 4096 cycles of 64 steps, whose per-cycle fields (12.6 MB at 384
#: nodes) are held twice while the chunk is joined. Each chunk solves its first cycles anew.
MAX_CHUNK_STEPS = 2**18

#: Seconds between checkpoints by default: at most a minute of work lost in a crash. Each
#: checkpoint rewrites the partial result whole.
CHECKPOINT_SECONDS = 60.0

#: Resolution of `fretting plot`: 6.4 x 4.4 inch figures at 100 dpi keep results/ of eight
#: examples near 5 MB (7.9 MB at 150 dpi).
FIGURE_DPI = 100

#: Seconds a run lasts before its progress bar appears: short runs show none.
PROGRESS_DELAY = 2.0


def main(argv=None):
    """Run the command line with the arguments `argv` (``sys.argv[1:]`` when None); return the exit code."""
    args = _parser().parse_args(argv)
    try:
        args.command(args)
    except KeyboardInterrupt as interrupt:
        return _fail(args, interrupt, f"interrupted{f': {interrupt}' if interrupt.args else ''}", EXIT_INTERRUPTED)
    except GrossSlipError as error:
        return _fail(args, error, f"{args.file}: {error}", EXIT_GROSS_SLIP)
    except OSError as error:
        return _fail(args, error, f"{error.filename or args.file}: {error.strerror or error}", EXIT_INPUT)
    except (HistoryError, ResultError) as error:
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

    run = commands.add_parser("run", parents=[common], help="run a history file and write its result")
    run.add_argument("file", metavar="HISTORY", help="history file (TOML), or the name of a shipped example")
    run.add_argument("-o", "--output", metavar="OUT", help="result file (default: results/<history stem>.h5)")
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
        f"{DEFAULT_RTOL:g}, or --nodes {DEFAULT_NODES} where that mesh would exceed {MAX_DEFAULT_MESH} nodes)",
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
    run.set_defaults(command=_run)

    validate = commands.add_parser("validate", parents=[common], help="check a history file without running it")
    validate.add_argument("file", metavar="HISTORY", help="history file (TOML), or the name of a shipped example")
    validate.set_defaults(command=_validate)

    info = commands.add_parser("info", parents=[common], help="describe a result file")
    info.add_argument("file", metavar="RESULT", help="result file written by `fretting run`")
    info.set_defaults(command=_info)

    plot = commands.add_parser("plot", parents=[common], help="draw a result as PNG files")
    plot.add_argument("file", metavar="RESULT", help="result file written by `fretting run`")
    plot.add_argument("-o", "--output", metavar="DIR", help="directory of the figures (default: the result's)")
    plot.set_defaults(command=_plot)

    listing = commands.add_parser("examples", parents=[common], help="list the shipped example histories")
    listing.set_defaults(command=_examples, file="examples")

    bench = commands.add_parser(
        "bench", parents=[common], help="measure speed against error and write results/speed_vs_error.*"
    )
    add_bench_arguments(bench)
    bench.set_defaults(command=_bench, file="bench")

    sweep = commands.add_parser("sweep", parents=[common], help="run a sweep file on dask.distributed")
    add_sweep_arguments(sweep)
    sweep.set_defaults(command=run_sweep)
    return parser


def _bench(args):
    code = run_bench(args)
    if code:
        raise SystemExit(code)


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


def _settings(args):
    """The model a run asks for: ``{"nodes": N}`` (grid), ``{"rtol": r}`` (adapted mesh) or ``{}`` (the default)."""
    if args.nodes is not None:
        return {"nodes": args.nodes}
    return {} if args.rtol is None else {"rtol": args.rtol}


#: The settings of a run of the exact model of Q alone (`fretting.models.exact`): its dataset's `model`.
EXACT_SETTINGS = {"model": MASING_MODEL}
#: What the default model may be (`fretting.engine.simulation.default_model`).
DEFAULT_SETTINGS = (EXACT_SETTINGS, {"rtol": DEFAULT_RTOL}, {"nodes": DEFAULT_NODES})


def _model(contact, history, asked):
    """The settings a run from the start records, and the keywords of `simulate` for its first chunk.

    An adapted mesh is adapted to the whole history, not to the chunk.
    """
    if "nodes" in asked:
        return asked, asked
    if "rtol" in asked:
        return asked, {"mesh": adapted_mesh(contact, history, asked["rtol"])}
    model = default_model(contact, history)
    if not model:
        return EXACT_SETTINGS, model
    return ({"nodes": DEFAULT_NODES} if "nodes" in model else {"rtol": DEFAULT_RTOL}), model


def _examples(args):
    for name, description in examples().items():
        print(f"{name:<32} {description}")


def _run(args):
    source = read_history_source(resolve_history(args.file))
    output = Path(args.output) if args.output else Path("results") / f"{source.path.stem}.h5"
    checkpoint = output.with_name(f"{output.name}.checkpoint")
    if checkpoint.exists() and not args.resume:
        raise ResultError(
            f"{checkpoint}: found the checkpoint of an interrupted run: continue it with --resume, or delete it"
        )
    history, asked = source.history, _settings(args)
    joiner = Joiner()
    start, state, model = 0, None, None
    if args.resume and checkpoint.exists():
        done = _resumable(checkpoint, source, asked)
        settings = _found(done)
        joiner.add(done)
        start, state = done.attrs["steps"] - 1, final_state(done)
        del done  # the joiner holds its cycles
    else:
        settings, model = _model(source.contact, history, asked)
    attributes = source_attributes(source) | settings  # a run on an adapted mesh is a run of `settings["rtol"]`
    record = recorded_steps(None if args.record == "default" else args.record, len(history))
    written = time.monotonic()
    with tqdm(
        total=len(history) - 1,
        initial=start,
        unit="step",
        delay=PROGRESS_DELAY,
        disable=not sys.stderr.isatty(),
        file=sys.stderr,
    ) as progress:
        try:
            for part in _chunks(source.contact, history, model, record, start, state):
                joiner.add(part)
                progress.update(part.attrs["steps"] - 1)
                if time.monotonic() - written >= args.checkpoint_interval:
                    save(joiner.result().assign_attrs(attributes), checkpoint)
                    written = time.monotonic()
        except KeyboardInterrupt:
            if len(joiner):
                save(joiner.result().assign_attrs(attributes), checkpoint)
                raise KeyboardInterrupt(f"progress kept in {checkpoint}; continue with --resume") from None
            raise
        except GrossSlipError:
            checkpoint.unlink(missing_ok=True)  # resuming would only reach it again
            raise
    del source, history  # the loads of every step (154 MB for 10^5 cycles of 64): the result holds what it records
    result = joiner.result().assign_attrs(attributes)
    save(result, output)
    checkpoint.unlink(missing_ok=True)
    print(f"{output}: {result.attrs['steps'] - 1} steps, {_cycles(result)} cycles, {_dissipated(result)}")


def _chunks(contact, history, model, record, start, state):
    """Results of successive chunks of `history` from step `start` in `state` (None: the contact just formed).

    The first chunk of a run from the start runs with the keywords `model` of `simulate` (see
    `_model`), the others from the state before. Each chunk records the steps of `record`
    (numbers in the whole history) that it reaches. Only the state of the previous chunk is
    kept, not its result.
    """
    steps = CHUNK_STEPS
    while state is None or start < len(history) - 1:
        stop = min(start + steps, len(history) - 1)
        began = time.monotonic()
        first = start + 1 if state is not None else 0  # a later chunk's step 0 is the last one's end
        mine = record[(record >= first) & (record <= stop)] - start
        try:
            chunk = model if state is None else {"state": state}
            part = simulate(contact, history[start : stop + 1], record=mine, **chunk)
        except GrossSlipError as error:
            raise GrossSlipError(start + error.step, error.Q, error.sigma, error.limit) from None
        state = final_state(part)
        yield part
        del part
        start = stop
        fast = time.monotonic() - began < CHUNK_SECONDS
        steps = min(2 * steps, MAX_CHUNK_STEPS) if fast else max(steps // 2, CHUNK_STEPS)


def _described(settings):
    """``name = value`` of the one setting in `settings`."""
    ((name, value),) = settings.items()
    return f"{name} = {value}"


def _found(done):
    """The settings a (partial) result was run with."""
    if done.attrs.get("model") == MASING_MODEL:
        return EXACT_SETTINGS
    return {"rtol": done.attrs.get("rtol")} if "theta" in done else {"nodes": done.attrs.get("nodes")}


def _resumable(checkpoint, source, asked):
    """The partial result in `checkpoint`, checked to belong to this history file and the settings `asked`."""
    done = load(checkpoint)
    if done.attrs.get("history_sha256") != source.sha256:
        raise ResultError(f"{checkpoint}: found a run of another version of {source.path}, expected this one")
    found = _found(done)
    if found not in ([asked] if asked else DEFAULT_SETTINGS):
        expected = _described(asked) if asked else "the default model"
        raise ResultError(f"{checkpoint}: found a run with {_described(found)}, expected {expected}")
    history, steps = source.history, done.step.values
    same = done.attrs["steps"] <= len(history) and all(
        np.array_equal(done[name].values, getattr(history, name)[steps]) for name in ("Q", "sigma")
    )
    if not same:
        raise ResultError(f"{checkpoint}: found loads that {source.path} no longer gives (NumPy's random draws?)")
    return done


def _validate(args):
    source = read_history_source(resolve_history(args.file))
    contact, history = source.contact, source.history
    print(f"{source.path}: {contact.profile!r}, a = {contact.a:.4g} m, p0 = {contact.p0:.4g} Pa")
    print(f"  {len(history) - 1} steps, {history.vertex_step.size} vertices, {history.cycle_count} cycles")
    print(f"  {_peaks(history.Q, history.sigma, contact.f, contact.P, contact.p0)}")
    fP = contact.f * contact.P
    sliding = np.flatnonzero(np.abs(history.Q) >= fP)
    if sliding.size:
        step = int(sliding[0])
        raise GrossSlipError(step, float(history.Q[step]), float(history.sigma[step]), fP)


def _info(args):
    result = load(args.file)
    attrs = result.attrs
    versions = json.loads(attrs.get("versions", "{}"))
    lines = {
        "history": f"{attrs.get('history_file', '?')} (sha256 {attrs.get('history_sha256', '?')})",
        "contact": f"{attrs['profile']}, E_star = {attrs['E_star']:.4g} Pa, f = {attrs['f']:.4g}, "
        f"P = {attrs['P']:.4g} N/m",
        "solution": f"a = {attrs['a']:.4g} m, centre = {attrs['centre']:.4g} m, p0 = {attrs['p0']:.4g} Pa",
        "model": f"{attrs['model']}, {attrs['nodes']} nodes",
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
        figure = Figure(figsize=(6.4, 4.4), layout="constrained")
        plots.FIGURES[name](result, ax=figure.subplots())
        path = directory / f"{Path(args.file).stem}_{name}.png"
        figure.savefig(path, dpi=FIGURE_DPI)
        print(path)


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
