"""The commands of one history and its result: ``run``, ``validate``, ``info``, ``plot``, ``export``, ``examples``."""

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from fretting.cli.common import at_least, figure_class, positive_number, progress_bar, saved
from fretting.cli.sweeps import sweep_info, sweep_plot
from fretting.engine.recorder import (
    CYCLE_FIELDS_EXPECTED,
    CYCLE_FIELDS_STORED,
    RECORD_ALL_STEPS,
    RECORDED_ENDS,
    CycleFields,
)
from fretting.engine.runner import CHECKPOINT_SECONDS, run_file
from fretting.errors import GrossSlipError
from fretting.loading.examples import copy_example, examples, resolve_history
from fretting.loading.history_file import read_history_source
from fretting.models import Grid, Mesh
from fretting.models.collocation import DEFAULT_NODES
from fretting.models.galerkin import DEFAULT_RTOL, MAX_DEFAULT_MESH, MAX_DEFAULT_WORK
from fretting.results.io import ResultError, load
from fretting.results.tables import cycle_table, step_table, write_csv
from fretting.studies.sweeps import is_sweep_file


def add_parsers(commands, common, figures):
    """The subcommands ``run``, ``validate``, ``info``, ``plot``, ``export`` and ``examples``."""
    run = commands.add_parser("run", parents=[common], help="run a history file and write its result")
    run.add_argument("file", metavar="HISTORY", help="history file (TOML), or the name of a shipped example")
    run.add_argument(
        "-o", "--output", metavar="OUT", help="result file (default: <history stem>.h5 in the current folder)"
    )
    run.add_argument("--resume", action="store_true", help="continue an interrupted run from its checkpoint")
    model = run.add_mutually_exclusive_group()
    model.add_argument(
        "--nodes",
        type=at_least(4, int),
        help=f"solve on a fixed grid of this many Gauss-Chebyshev collocation nodes instead (e.g. {DEFAULT_NODES})",
    )
    model.add_argument(
        "--rtol",
        type=positive_number,
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
        type=at_least(0, float),
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

    info = commands.add_parser("info", parents=[common], help="describe a result or sweep file")
    info.add_argument("file", metavar="RESULT", help="result file written by `fretting run`, or of `fretting sweep`")
    info.set_defaults(command=_info)

    plot = commands.add_parser("plot", parents=[common, figures], help="draw a result or sweep as figure files")
    plot.add_argument("file", metavar="RESULT", help="result file written by `fretting run`, or of `fretting sweep`")
    plot.add_argument("-o", "--output", metavar="DIR", help="directory of the figures (default: the result's)")
    plot.add_argument(
        "--body",
        type=int,
        choices=(1, 2),
        help="body of the surface-stress figure: 1 (traction q) or 2 (-q) "
        "(default: the specimen, with its bulk stress)",
    )
    plot.set_defaults(command=_plot)

    export = commands.add_parser(
        "export", parents=[common], help="write a result's per-cycle (or per-step) table as CSV"
    )
    export.add_argument("file", metavar="RESULT", help="result file written by `fretting run`")
    export.add_argument(
        "-o", "--output", metavar="FILE", help="CSV file (default: <result stem>_cycles.csv, or _steps.csv, beside it)"
    )
    export.add_argument(
        "--steps", action="store_true", help="the loads and scalars of each recorded step instead of each cycle"
    )
    export.set_defaults(command=_export)

    listing = commands.add_parser(
        "examples", parents=[common], help="list the shipped example histories, or copy one to edit"
    )
    listing.add_argument(
        "--copy", metavar="NAME", help="copy the example NAME, with the tables it names, into DIR to edit"
    )
    listing.add_argument("folder", nargs="?", metavar="DIR", help="folder of the copies (default: the current one)")
    listing.set_defaults(command=_examples, file="examples", usage_error=listing.error)


def _model(args):
    """The model spec the arguments ask for (None: the default)."""
    if args.nodes is not None:
        return Grid(args.nodes)
    return None if args.rtol is None else Mesh(rtol=args.rtol)


def _examples(args):
    if args.copy is not None:
        for path in copy_example(args.copy, args.folder or "."):
            print(path)
        return
    if args.folder is not None:
        args.usage_error(f"DIR {args.folder!r}: a folder is for --copy NAME")
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
    with progress_bar("step", args.interrupts) as progress:
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
    if is_sweep_file(args.file):
        return sweep_info(args)
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
    if is_sweep_file(args.file):
        return sweep_plot(args)
    Figure = figure_class()

    from fretting import plots

    result = load(args.file)
    directory = Path(args.output) if args.output else Path(args.file).parent
    directory.mkdir(parents=True, exist_ok=True)
    for name in plots.figures_for(result):
        figure = Figure(figsize=args.size, layout="constrained")
        options = {"body": args.body} if name == "surface_stress" else {}
        plots.FIGURES[name](result, ax=figure.subplots(), **options)
        saved(figure, directory / f"{Path(args.file).stem}_{name}", args)


def _export(args):
    result = load(args.file)
    kind = "steps" if args.steps else "cycles"
    try:
        table = step_table(result) if args.steps else cycle_table(result)
    except ValueError as error:
        raise ResultError(f"{args.file}: {error}") from None
    output = Path(args.output or Path(args.file).with_name(f"{Path(args.file).stem}_{kind}.csv"))
    write_csv(table, output, f"fretting export of {Path(args.file).name}")
    print(f"{output}: {table.sizes[next(iter(table.dims))]} {kind}, {len(table.data_vars) + 1} columns")


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
