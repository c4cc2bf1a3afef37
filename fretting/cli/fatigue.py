"""The commands of a fretting-fatigue test programme: ``materials``, ``threshold`` and ``map``."""

import argparse
import dataclasses
from pathlib import Path

from fretting.analysis.fatigue import (
    CRITERIA,
    READINGS,
    BracketError,
    Material,
    MaterialFileError,
    material_path,
    materials,
    threshold_of,
)
from fretting.analysis.stress import BULK_STATES
from fretting.cli.common import at_least, figure_class, positive_number, saved
from fretting.errors import FrettingError, HistoryError
from fretting.loading.examples import resolve_history
from fretting.models import Grid
from fretting.results.io import save
from fretting.studies.maps import FileScene, nucleation_boundary


def add_parsers(commands, common, figures):
    """The subcommands of a test programme: ``materials``, ``threshold`` and ``map``."""
    listing = commands.add_parser(
        "materials", parents=[common], help="list the shipped material files and their sources"
    )
    listing.set_defaults(command=_materials, file="materials")

    search = argparse.ArgumentParser(add_help=False)
    search.add_argument(
        "file", metavar="HISTORY", help="history file (TOML), or a shipped example's name: the test's shape"
    )
    search.add_argument(
        "--bracket",
        nargs=2,
        type=float,
        required=True,
        metavar=("LOW", "HIGH"),
        help="the values searched between, in the units of the varied key (e.g. N/m for Q_amplitude)",
    )
    search.add_argument("--criterion", choices=tuple(CRITERIA), required=True, help="fatigue criterion")
    search.add_argument(
        "--material", required=True, metavar="FILE", help="material file (TOML), or a name of `fretting materials`"
    )
    length = search.add_mutually_exclusive_group()
    length.add_argument(
        "--critical-distance", type=positive_number, metavar="L", help="critical distance L [m] (overrides the file's)"
    )
    length.add_argument(
        "--delta-K-th",
        type=positive_number,
        metavar="DK",
        help="threshold range of the stress intensity factor [Pa m^0.5]: L = (1/pi) (DK / (2 sigma_limit))^2 "
        "(El Haddad)",
    )
    search.add_argument(
        "--at",
        choices=tuple(name.replace(" ", "-") for name in READINGS),
        default="point",
        help="where the criterion is read: point (L/2 below the hot spot, the default), line (mean over 2 L), hot-spot",
    )
    search.add_argument("--nu", type=float, help="Poisson's ratio for sigma_yy (default: the history's)")
    search.add_argument(
        "--bulk-state",
        choices=tuple(state.replace(" ", "-") for state in BULK_STATES),
        default="plane-strain",
        help="state of the specimen's bulk stress (as fretting stress)",
    )
    search.add_argument(
        "--nodes", type=at_least(4, int), help="solve on a fixed grid of this many nodes (default: the default model)"
    )

    threshold = commands.add_parser(
        "threshold",
        parents=[common, search],
        help="the value of a history key (Q or sigma amplitude, pad radius, P) at which a criterion reaches its limit "
        "or a life",
    )
    threshold.add_argument(
        "--vary",
        required=True,
        metavar="KEY",
        help="dotted key of the history file searched over, e.g. loading[1].Q_amplitude, contact.R",
    )
    threshold.add_argument(
        "--life",
        type=positive_number,
        nargs="+",
        metavar="N",
        help="target lives [cycles] (default: the criterion's fatigue limit)",
    )
    threshold.set_defaults(command=_threshold)

    fatigue_map = commands.add_parser(
        "map",
        parents=[common, search, figures],
        help="the nucleation boundary: the threshold Q amplitude for each bulk stress amplitude",
    )
    fatigue_map.add_argument(
        "--q-key",
        default="loading[1].Q_amplitude",
        metavar="KEY",
        help="key of the Q amplitude [N/m] (default loading[1].Q_amplitude)",
    )
    fatigue_map.add_argument(
        "--sigma-key",
        default="loading[1].sigma_amplitude",
        metavar="KEY",
        help="key of the bulk stress amplitude [Pa] (default loading[1].sigma_amplitude)",
    )
    fatigue_map.add_argument(
        "--sigma", type=float, nargs="+", required=True, metavar="S", help="bulk stress amplitudes [Pa] of the map"
    )
    fatigue_map.add_argument(
        "--life", type=positive_number, metavar="N", help="target life [cycles] (default: the fatigue limit)"
    )
    fatigue_map.add_argument(
        "--dask", metavar="SCHEDULER", choices=("processes", "threads"), help="run the points as dask tasks"
    )
    fatigue_map.add_argument(
        "-o", "--output", metavar="OUT", help="map file (default: <history stem>_map.h5 in the current folder)"
    )
    fatigue_map.add_argument("--figure", action="store_true", help="also draw the boundary as <OUT stem>.<format>")
    fatigue_map.set_defaults(command=_map)


def _materials(args):
    for name, (path, description) in materials().items():
        print(f"{name:<16} {description}")
        print(f"{'':<16} {path}")


def _search_inputs(args):
    """The material (with --critical-distance or --delta-K-th), model and reading of a threshold or map command."""
    path = material_path(args.material)
    material = Material.from_file(path)
    override = {"critical_distance": args.critical_distance} if args.critical_distance else {}
    if args.delta_K_th:
        override = {"critical_distance": None, "delta_K_th": args.delta_K_th}
    material = dataclasses.replace(material, **override)
    low, high = args.bracket
    if not low < high:
        raise HistoryError(f"{args.file}: --bracket: found {low:g} {high:g}, expected LOW < HIGH")
    return path, material, None if args.nodes is None else Grid(args.nodes), args.at.replace("-", " ")


def _searched(args, path, search):
    """`search()` with its errors as one line: a constant the material lacks, or a bracket with no crossing."""
    try:
        return search()
    except BracketError as error:
        raise HistoryError(f"{args.file}: --{error}") from None
    except FrettingError:
        raise
    except ValueError as error:
        raise MaterialFileError(path, None, str(error).removeprefix("material: ")) from None


def _threshold(args):
    path, material, model, at = _search_inputs(args)
    scene = FileScene(resolve_history(args.file), (args.vary,))
    cache = {}
    for life in args.life or [None]:
        found = _searched(
            args,
            path,
            lambda life=life: threshold_of(
                scene,
                tuple(args.bracket),
                args.criterion,
                material,
                life=life,
                at=at,
                nu=args.nu,
                bulk_state=args.bulk_state.replace("-", " "),
                model=model,
                cache=cache,
                name=args.vary,
            ),
        )
        target = "its fatigue limit" if life is None else f"a life of {life:.6g} cycles"
        units = found.values.parameter.attrs["units"]
        print(
            f"{args.criterion} at {at} reaches {target} at {args.vary} = {found.amplitude:.6g} "
            f"(parameter {float(found.values.parameter):.6g} {units}; {found.runs} values searched, "
            f"{len(cache)} runs in all)"
        )


def _map(args):
    path, material, model, at = _search_inputs(args)
    history = resolve_history(args.file)
    scene = FileScene(history, (args.q_key, args.sigma_key))
    boundary = _searched(
        args,
        path,
        lambda: nucleation_boundary(
            scene,
            args.sigma,
            tuple(args.bracket),
            args.criterion,
            material,
            life=args.life,
            at=at,
            nu=args.nu,
            bulk_state=args.bulk_state.replace("-", " "),
            model=model,
            scheduler=args.dask,
        ),
    )
    output = Path(args.output or f"{history.stem}_map.h5")
    save(boundary, output)
    print(f"{output}: {boundary.sizes['sigma_amplitude']} bulk stress amplitudes, {int(boundary.runs.sum())} runs")
    for sigma, Q, side in zip(
        boundary.sigma_amplitude.values, boundary.Q_threshold.values, boundary.side.values, strict=True
    ):
        where = {
            0: f"Q_a = {Q:.6g} N/m",
            1: "above the target over the bracket",
            -1: "below the target over the bracket",
        }
        print(f"  sigma_a = {sigma:.6g} Pa: {where[int(side)]}")
    if args.figure:
        Figure = figure_class()

        from fretting import plots_maps

        figure = Figure(figsize=args.size, layout="constrained")
        plots_maps.nucleation_boundary(boundary, figure.subplots())
        saved(figure, output.with_name(output.stem), args)
