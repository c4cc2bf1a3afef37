"""Fretting-fatigue maps (`fretting.studies.maps`), their figures (`fretting.plots_maps`) and the commands
``fretting materials | threshold | map``."""

import matplotlib
import numpy as np
import pytest
import xarray as xr
from conftest import HERTZ_TOML
from matplotlib.figure import Figure

import fretting as fr
from fretting import cli, plots_maps
from fretting.analysis.fatigue import Material, read_last_cycle
from fretting.loading.history_file import HistoryFileError
from fretting.models import Grid
from fretting.studies.maps import FileScene, life_against_size, nucleation_boundary

matplotlib.use("Agg")

NU = 0.3
#: Fatigue limits low enough for the contact of HERTZ_TOML (f P = 70 kN/m, p0 = 271 MPa) to reach them.
WEAK = Material(E=210e9, nu=NU, sigma_limit=200e6, tau_limit=130e6, sigma_f=900e6, b=-0.1, critical_distance=20e-6)
GRID = Grid(64)
HISTORY = (
    HERTZ_TOML
    + """
[[loading]]
kind = "sine"
Q_amplitude = 20e3
sigma_amplitude = 0.0
cycles = 2
steps_per_cycle = 16
"""
)
KEYS = ("loading[1].Q_amplitude", "loading[1].sigma_amplitude")


@pytest.fixture
def history(tmp_path):
    path = tmp_path / "rig.toml"
    path.write_text(HISTORY)
    return path


@pytest.fixture
def weak(tmp_path):
    path = tmp_path / "weak.toml"
    path.write_text("# weak\nE = 210e9\nnu = 0.3\nsigma_limit = 200e6\ntau_limit = 130e6\ncritical_distance = 20e-6\n")
    return path


def test_a_file_scene_sets_its_keys_and_names_a_bad_one(history):
    scene = FileScene(history, KEYS)
    contact, loads = scene(30e3, 50e6)
    assert contact.P == 1e5
    assert np.abs(loads.Q).max() == pytest.approx(30e3) and np.abs(loads.sigma).max() == pytest.approx(50e6)
    with pytest.raises(HistoryFileError, match=r"rig.toml: loading\[2\].Q_amplitude: found no such table"):
        FileScene(history, ("loading[2].Q_amplitude",))
    with pytest.raises(HistoryFileError, match="contact.R]: found a malformed key"):
        FileScene(history, ("contact.R]",))
    with pytest.raises(ValueError, match="values: found 1, expected one for each of"):
        scene(30e3)


def test_the_boundary_falls_as_the_bulk_stress_grows_and_each_point_is_a_threshold(history):
    """At each found point the criterion read there is its limit; above a bulk stress the whole bracket nucleates;
    threads give the same points."""
    scene = FileScene(history, KEYS)
    bracket = (0.02 * 70e3, 0.98 * 70e3)
    options = {"at": "hot spot", "nu": NU, "model": GRID}
    boundary = nucleation_boundary(scene, [0.0, 30e6, 150e6], bracket, "crossland", WEAK, **options)
    assert list(boundary.side.values) == [0, 0, 1]
    Q = boundary.Q_threshold.values
    assert Q[0] > Q[1] > 0 and np.isnan(Q[2])
    at_point = read_last_cycle(*scene(Q[1], 30e6), "crossland", WEAK, **options)
    assert float(at_point.parameter) == pytest.approx(WEAK.crossland_constants()[1], rel=1e-5)
    assert boundary.attrs["target"] == "fatigue limit" and boundary.Q_threshold.attrs["units"] == "N/m"
    threads = nucleation_boundary(scene, [30e6], bracket, "crossland", WEAK, scheduler="threads", **options)
    assert threads.Q_threshold.values[0] == Q[1]


def size_scene(a, p0=271e6, ratio=0.3):
    """A Hertz contact of half-width `a` [m] at the peak pressure `p0` and ``Q* / (f P)`` = `ratio`: the stress field
    is one of ``x / a`` and ``z / a`` alone."""
    E_star = fr.plane_strain_modulus(210e9, NU)
    R = E_star * a / (2 * p0)  # Hertz: p0 = a E_star / (2 R), P = pi a p0 / 2
    P = np.pi * a * p0 / 2
    contact = fr.Contact(fr.Hertz(R), E_star, 0.7, P)
    return contact, fr.History.sinusoidal(ratio * 0.7 * P, cycles=2, steps_per_cycle=16)


def test_life_against_size_shows_the_size_effect_only_at_a_critical_distance():
    """At constant ``p0`` and ``Q / (f P)`` the hot spot sees one life at every size; read at ``L/2`` the life grows
    as the contact shrinks, and the smallest contacts run out."""
    sizes = [0.02e-3, 0.05e-3, 0.2e-3, 1e-3]
    surface = life_against_size(size_scene, sizes, "crossland", WEAK, at="hot spot", nu=NU)
    assert np.ptp(surface.N_f.values) <= 1e-9 * surface.N_f.values.max()
    assert surface.a.values == pytest.approx(sizes, rel=1e-12)
    below = life_against_size(size_scene, sizes, "crossland", WEAK, at="point", nu=NU, runout=1e9)
    lives = below.N_f.values
    assert np.all(np.diff(lives) < 0) and lives[-1] > surface.N_f.values[0]
    assert list(below.run_out.values) == list(lives >= 1e9)
    assert below.run_out.values[0] and not below.run_out.values[-1]

    figure = Figure()
    ax = plots_maps.life_against_size(below, figure.subplots())
    assert ax.get_xlabel() == "contact half-width $a$ [mm]" and ax.get_yscale() == "log"
    assert any(line.get_ydata()[0] == 1e9 for line in ax.get_lines())  # the run-out line


def test_the_boundary_figure_is_vector_with_labelled_axes(tmp_path):
    boundary = xr.Dataset(
        {"Q_threshold": ("sigma_amplitude", [3e4, 2e4, np.nan]), "side": ("sigma_amplitude", np.int8([0, 0, 1]))},
        coords={"sigma_amplitude": [0.0, 5e7, 1e8]},
        attrs={"criterion": "crossland", "at": "point", "target": "fatigue limit", "bracket": [1e3, 6e4]},
    )
    figure = Figure()
    ax = plots_maps.nucleation_boundary(boundary, figure.subplots(), fP=7e4)
    assert ax.get_xlabel() == "shear force amplitude $Q_a$ [kN/m]"
    assert ax.get_ylabel() == r"bulk stress amplitude $\sigma_a$ [MPa]"
    figure.savefig(tmp_path / "map.svg")
    assert "<svg" in (tmp_path / "map.svg").read_text()


def test_materials_command_lists_names_and_files(capsys):
    assert cli.main(["materials"]) == 0
    out = capsys.readouterr().out
    for name in ("al2024_t351", "ti6al4v_sta", "aisi4340_qt650"):
        assert name in out and f"{name}.toml" in out


def test_threshold_command_finds_lives_on_one_cache(history, weak, capsys):
    args = ["threshold", str(history), "--vary", KEYS[0], "--bracket", "1.4e3", "68.6e3", "--criterion", "crossland"]
    code = cli.main([*args, "--material", str(weak), "--at", "hot-spot", "--nu", "0.3"])
    out = capsys.readouterr().out
    assert code == 0
    assert "crossland at hot spot reaches its fatigue limit at loading[1].Q_amplitude = " in out


@pytest.mark.parametrize(
    ("change", "expected"),
    [
        (["--vary", "loading[1].Q_amp"], None),
        (["--bracket", "1e3", "2e3"], "--bracket: the criterion less its limit is -"),
        (["--bracket", "2e3", "1e3"], "--bracket: found 2000 1000, expected LOW < HIGH"),
        (["--material", "al2024_t351"], "al2024_t351.toml: crossland needs sigma_limit, tau_limit, found None"),
        (["--material", "unobtainium"], "unobtainium: no such file, nor a shipped material"),
    ],
)
def test_threshold_command_refuses_bad_input_in_one_line(history, weak, capsys, change, expected):
    options = {"--vary": [KEYS[0]], "--bracket": ["1.4e3", "68.6e3"], "--material": [str(weak)]}
    options[change[0]] = change[1:]
    args = ["threshold", str(history), "--criterion", "crossland", "--at", "hot-spot", "--nu", "0.3"]
    code = cli.main(args + [word for key, values in options.items() for word in (key, *values)])
    err = capsys.readouterr().err
    assert code == 2
    assert len(err.strip().splitlines()) == 1 and err.startswith("fretting: error: ")
    assert (expected or "rig.toml:9: loading[1].Q_amp: unknown key, expected one of: ") in err


def test_map_command_writes_the_boundary_and_its_figure(history, weak, tmp_path, capsys):
    out = tmp_path / "map.h5"
    args = ["map", str(history), "--sigma", "0", "150e6", "--bracket", "1.4e3", "68.6e3", "--criterion", "crossland"]
    args += ["--material", str(weak), "--at", "hot-spot", "--nu", "0.3", "--nodes", "64", "-o", str(out)]
    assert cli.main([*args, "--figure", "--format", "pdf"]) == 0
    printed = capsys.readouterr().out
    assert "sigma_a = 1.5e+08 Pa: above the target over the bracket" in printed
    assert (tmp_path / "map.pdf").read_bytes().startswith(b"%PDF")
    saved = xr.load_dataset(out, engine="h5netcdf")
    assert list(saved.side.values) == [0, 1]
