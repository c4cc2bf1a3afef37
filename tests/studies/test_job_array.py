"""Sweeps without a cluster: the cases of a job array (``--list-cases``, ``--case K``) joined by a sweep
that runs none of them, the case key (the release, the tables' contents), list values, CF names,
``fretting info`` and ``fretting plot`` of sweep files, shipped sweeps by name."""

import hashlib
import json
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr
from conftest import HERTZ_TOML
from conftest import SINE_TOML as SINE
from matplotlib.figure import Figure

import fretting as fr
from fretting import cli
from fretting.results.io import save
from fretting.studies import sweeps
from fretting.studies.sweeps import SWEEPS, case_file, figures_for, load_sweep, read_sweep, run_one, summarize

#: f P = 70 kN/m in `SINE` (60 kN/m at f = 0.6), so Q = 80 kN/m slides.
GRID = '[grid]\ncontact.f = [0.6, 0.7]\n"loading[1].Q_amplitude" = [20e3, 80e3]\n'
DIMS = {"contact_f": "contact.f", "loading_1_Q_amplitude": "loading[1].Q_amplitude"}


def sweep_folder(folder):
    """`folder`, holding ``sine.toml`` and the sweep ``map.toml`` of it over `GRID`."""
    (folder / "sine.toml").write_text(SINE)
    (folder / "map.toml").write_text(f'history = "sine.toml"\n{GRID}')
    return folder


@pytest.fixture
def folder(tmp_path, monkeypatch):
    """A `sweep_folder`, the current folder."""
    monkeypatch.chdir(tmp_path)
    return sweep_folder(tmp_path)


@pytest.fixture
def no_dask(monkeypatch):
    """dask.distributed made unimportable: what runs then starts no cluster."""
    monkeypatch.setitem(sys.modules, "distributed", None)


@pytest.fixture(scope="module")
def joined(tmp_path_factory):
    """A `sweep_folder` whose every case ran by ``--case K``, then joined into results/map.h5: (folder, dataset)."""
    folder = sweep_folder(tmp_path_factory.mktemp("joined"))
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(folder)
        patch.setitem(sys.modules, "distributed", None)  # no cluster
        for k in range(4):
            assert cli.main(["sweep", "map.toml", "--case", str(k)]) == 0
        assert cli.main(["sweep", "map.toml"]) == 0
    return folder, xr.load_dataset(folder / "results" / "map.h5", engine="h5netcdf")


@pytest.fixture
def inside(joined, monkeypatch):
    """The dataset of `joined`, its folder the current one."""
    monkeypatch.chdir(joined[0])
    return joined[1]


def direct(text):
    """The case variables of the history file of `text`, run directly by `simulate`; or its GrossSlipError."""
    contact, history = fr.read_history(write("direct.toml", text))
    try:
        return summarize(fr.simulate(contact, history))
    except fr.GrossSlipError as error:
        return error


def write(path, text):
    with open(path, "w") as file:
        file.write(text)
    return path


def listed(capsys, *arguments):
    """The lines of ``fretting sweep map.toml --list-cases``, split at the tabs."""
    assert cli.main(["sweep", "map.toml", "--list-cases", *arguments]) == 0
    return [line.split("\t") for line in capsys.readouterr().out.splitlines()]


def test_a_job_array_runs_each_case_and_the_sweep_joins_them(folder, capsys, no_dask):
    lines = listed(capsys)
    values = ["contact.f = 0.6, loading[1].Q_amplitude = 20000.0", "contact.f = 0.6, loading[1].Q_amplitude = 80000.0"]
    values += ["contact.f = 0.7, loading[1].Q_amplitude = 20000.0", "contact.f = 0.7, loading[1].Q_amplitude = 80000.0"]
    assert [line[:2] for line in lines] == [[str(k), text] for k, text in enumerate(values)]
    files = [folder / line[2] for line in lines]
    assert len(set(files)) == 4 and all(file.parent == folder / "results" / "map.cases" for file in files)
    assert not any(file.exists() for file in files)
    regimes = ["partial slip", "gross slip"] * 2
    for k in (2, 0, 3, 1):  # a job array's tasks end in any order
        assert cli.main(["sweep", "map.toml", "--case", str(k)]) == 0
        assert capsys.readouterr().out == f"{lines[k][2]}: case {k} of 4, {values[k]}: {regimes[k]}\n"
        assert files[k].is_file()
    written = {file: file.stat().st_mtime_ns for file in files}
    assert cli.main(["sweep", "map.toml", "--case", "1"]) == 0  # a task run again (requeued) runs nothing
    assert capsys.readouterr().out.endswith("gross slip (its file was there: not run again)\n")
    assert cli.main(["sweep", "map.toml"]) == 0  # dask.distributed cannot be imported: nothing runs
    over = "4 cases over contact.f (2) x loading[1].Q_amplitude (2)"
    assert capsys.readouterr().out == f"results/map.h5: {over}: 0 stuck, 2 partial slip, 2 gross slip\n"
    assert {file: file.stat().st_mtime_ns for file in files} == written
    cases = xr.load_dataset(folder / "results" / "map.h5", engine="h5netcdf")
    partial = direct(SINE.replace("f = 0.7", "f = 0.6").replace("Q_amplitude = 30e3", "Q_amplitude = 20e3"))
    case = cases.sel(contact_f=0.6, loading_1_Q_amplitude=20e3)
    for name in sweeps.VARIABLES:
        np.testing.assert_array_equal(case[name].values, partial[name].values, err_msg=name)
    slid = direct(SINE.replace("Q_amplitude = 30e3", "Q_amplitude = 80e3"))
    assert int(cases.sel(contact_f=0.7, loading_1_Q_amplitude=80e3).gross_slip_step) == slid.step > 0


@pytest.mark.parametrize("k", [-1, 4])
def test_a_case_out_of_range_is_a_one_line_error(folder, capsys, k):
    assert cli.main(["sweep", "map.toml", "--case", str(k)]) == cli.EXIT_INPUT
    assert capsys.readouterr().err == (
        f"fretting: error: map.toml: --case: found {k}, expected a case from 0 to 3 (--list-cases lists them)\n"
    )


def test_a_scheduler_file_that_does_not_appear_is_a_one_line_error(folder, capsys, monkeypatch):
    monkeypatch.setattr(sweeps, "SCHEDULER_FILE_SECONDS", 0.2)
    assert cli.main(["sweep", "map.toml", "--scheduler-file", "missing.json"]) == cli.EXIT_INPUT
    assert capsys.readouterr().err == (
        "fretting: error: missing.json: no scheduler wrote it in 0.2 s (dask scheduler --scheduler-file FILE)\n"
    )


def test_progress_on_stderr_when_it_is_a_terminal(inside, capsys, monkeypatch, no_dask):
    monkeypatch.setattr(cli.common, "PROGRESS_DELAY", 0.0)
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    assert cli.main(["sweep", "map.toml"]) == 0
    assert "4/4" in capsys.readouterr().err
    monkeypatch.setattr(sys.stderr, "isatty", lambda: False)  # quiet when stderr is a file, as `fretting run`
    assert cli.main(["sweep", "map.toml"]) == 0
    assert capsys.readouterr().err == ""


def test_case_key_holds_the_release_and_the_tables_contents(folder):
    table = write("loads.csv", "Q,sigma\n0,0\n20e3,10e6\n-20e3,-10e6\n20e3,10e6\n")
    csv = HERTZ_TOML + '[[loading]]\nkind = "csv"\nfile = "loads.csv"\n'
    write("map.toml", f"{csv}[grid]\ncontact.f = [0.6, 0.7]\n")
    plan = read_sweep("map.toml")
    case = plan.case(plan.cases()[0])
    assert case.tables == (hashlib.sha256((folder / table).read_bytes()).hexdigest(),)
    first, summary, ran = run_one(plan, 0, "out.h5")
    assert ran and first == case_file("out.h5", plan.base, case)
    assert run_one(plan, 0, "out.h5")[2] is False  # reused: same table
    write(table, "Q,sigma\n0,0\n25e3,10e6\n-25e3,-10e6\n25e3,10e6\n")  # edited: the case is another one
    again, edited, ran = run_one(plan, 0, "out.h5")
    assert ran and again != first and float(edited.total_dissipation) > float(summary.total_dissipation)
    assert xr.load_dataset(again, engine="h5netcdf").attrs["tables_sha256"] == plan.case(plan.cases()[0]).tables[0]


def test_without_tables_a_case_keeps_the_file_name_of_earlier_releases(folder):
    """The name of a case file is the digest of its base, values and release: the cases of a sweep
    written before the tables' digests were added to the key are still found."""
    plan = read_sweep("map.toml")
    values = plan.cases()[3]
    earlier = {"base_sha256": plan.base.sha256, "case": json.dumps(values, sort_keys=True)}
    earlier["fretting_version"] = fr.__version__
    digest = hashlib.sha256(json.dumps(earlier, sort_keys=True).encode()).hexdigest()
    assert case_file("map.h5", plan.base, plan.case(values)).name == f"{digest[:24]}.h5"


def test_vertex_lists_are_swept_as_one_value(folder, capsys, no_dask):
    vertices = [[0.0, 20e3, -20e3, 20e3], [0.0, 30e3, -30e3, 30e3, -30e3]]
    linear = HERTZ_TOML + '[[loading]]\nkind = "linear"\nQ = [0.0, 1e3]\nsteps_per_segment = 8\n'
    write("linear.toml", linear)
    write("map.toml", f'history = "linear.toml"\n[grid]\n"loading[1].Q" = {json.dumps(vertices)}\n')
    for k in ("0", "1"):
        assert cli.main(["sweep", "map.toml", "--case", k]) == 0
    assert cli.main(["sweep", "map.toml"]) == 0
    cases = xr.load_dataset("results/map.h5", engine="h5netcdf")
    assert list(cases.loading_1_Q.values) == [json.dumps(Q) for Q in vertices]
    assert cases.loading_1_Q.attrs["key"] == "loading[1].Q"
    for k, Q in enumerate(vertices):
        expected = direct(linear.replace("Q = [0.0, 1e3]", f"Q = {Q}"))
        assert float(cases.total_dissipation[k]) == float(expected.total_dissipation) > 0
    assert list(figures_for(cases)) == ["total_dissipation"]  # no map of one key, no cycles: no last cycle
    ax = sweeps.curves(cases, "total_dissipation", Figure().subplots())
    assert [label.get_text() for label in ax.get_xticklabels()] == [json.dumps(Q) for Q in vertices]
    np.testing.assert_array_equal(ax.lines[0].get_ydata(), cases.total_dissipation.values)
    # the same sweep from Python, its values a NumPy array of rows: the cases above, run again by none
    grid = {"loading[1].Q": np.array(vertices[0])[None, :]}
    again = fr.sweep("linear.toml", grid, output="results/map.h5")
    assert float(again.total_dissipation[0]) == float(cases.total_dissipation[0])


def test_sweep_dimensions_are_cf_names_with_the_dotted_key_kept(joined):
    _, cases = joined
    assert list(cases.regime.dims) == list(DIMS)
    for dim, key in DIMS.items():
        assert cases[dim].attrs["key"] == cases[dim].attrs["long_name"] == key
    assert json.loads(cases.attrs["grid"]) == {"contact.f": [0.6, 0.7], "loading[1].Q_amplitude": [20e3, 80e3]}


def test_compliance_checker_finds_nothing_in_a_sweep_file(joined, tmp_path):
    """The IOOS compliance checker (CF-1.11, its packaged standard-name table: no network), run in a
    process of its own (netCDF4 and h5py each bring an HDF5 library)."""
    checked = tmp_path / "map.nc"  # the checker wants the suffix .nc
    checked.write_bytes((joined[0] / "results" / "map.h5").read_bytes())
    report = tmp_path / "report.json"
    run = (
        "import sys\n"
        "from compliance_checker.runner import CheckSuite, ComplianceChecker\n"
        "CheckSuite().load_all_available_checkers()\n"
        "ComplianceChecker.run_checker(sys.argv[1], ['cf:1.11'], 0, 'normal', output_filename=sys.argv[2], "
        "output_format='json')\n"
    )
    subprocess.run([sys.executable, "-c", run, str(checked), str(report)], check=False, capture_output=True)
    found = json.loads(report.read_text())["cf:1.11"]
    problems = [(item["name"], item["msgs"]) for item in found["all_priorities"] if item["value"][0] < item["value"][1]]
    assert (found["high_count"], found["medium_count"], problems) == (0, 0, [])
    assert found["scored_points"] == found["possible_points"] > 0


def test_info_of_a_sweep_file(inside, capsys):
    assert cli.main(["info", "results/map.h5"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "results/map.h5"
    assert lines[1].startswith("  history   sine.toml (base sha256 ")
    assert lines[2:5] == [
        "  grid      contact.f (2): 0.6, 0.7 [1]",
        "            loading[1].Q_amplitude (2): 2e+04, 8e+04 [N/m]",
        "  cases     4: 0 stuck, 2 partial slip, 2 gross slip",
    ]
    recorded = {line[12:].split(":")[0]: line for line in lines[5:-1]}
    assert list(recorded) == list(sweeps.VARIABLES)
    assert recorded["energy_per_cycle"].endswith("(2 NaN)") and "[J/m]" in recorded["energy_per_cycle"]
    assert recorded["f"].endswith(": 0.6 to 0.7")


def test_plot_of_a_sweep_file(inside, tmp_path, capsys):
    assert cli.main(["plot", "results/map.h5", "-o", str(tmp_path), "--format", "svg"]) == 0
    names = ["map", "energy_per_cycle", "w_max", "slip_amplitude_max", "total_dissipation"]
    assert capsys.readouterr().out.splitlines() == [f"{tmp_path}/map_{name}.svg" for name in names]
    cases = inside
    ax = Figure().subplots()
    figures_for(cases)["energy_per_cycle"](cases, ax=ax)
    assert [line.get_label() for line in ax.lines] == [f"loading[1].Q_amplitude = {Q}" for Q in ("2e+04", "8e+04")]
    x, y = ax.lines[0].get_data()
    np.testing.assert_array_equal(x, [0.6, 0.7])
    np.testing.assert_array_equal(y, cases.energy_per_cycle.isel(loading_1_Q_amplitude=0).values)


def test_a_sweep_file_of_an_earlier_release_reads(joined, tmp_path, capsys):
    """Written before the dimensions had CF names: the dotted keys are the dimensions."""
    _, cases = joined
    old = cases.rename({dim: key for dim, key in DIMS.items()})
    for key in DIMS.values():
        del old[key].attrs["key"]
    save(old, tmp_path / "old.h5")
    loaded = load_sweep(tmp_path / "old.h5")
    assert sweeps.keys(loaded) == {key: key for key in DIMS.values()}
    assert cli.main(["info", str(tmp_path / "old.h5")]) == 0
    assert "  grid      contact.f (2): 0.6, 0.7 [1]\n" in capsys.readouterr().out
    assert list(figures_for(loaded)) == ["map", *sweeps.CURVES]
    ax = sweeps.fretting_map(loaded, Figure().subplots())
    assert ax.get_xlabel() == "contact.f [1]" and ax.get_ylabel().startswith("loading[1].Q_amplitude / (f P")


def test_a_result_is_not_a_sweep(folder):
    with pytest.raises(fr.FrettingError, match="expected a sweep of fretting"):
        load_sweep(write("not.h5", "text"))


def test_a_shipped_sweep_runs_by_name_from_an_empty_folder(tmp_path, monkeypatch, capsys, no_dask):
    monkeypatch.chdir(tmp_path)
    assert cli.main(["sweep", "hertz_fretting_map", "--list-cases"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 64 and lines[9].startswith("9\tloading[1].Q_amplitude = 10000.0, loading[1].sigma_amplitude")
    assert cli.main(["sweep", "hertz_fretting_map", "--case", "0"]) == 0
    assert capsys.readouterr().out.startswith(f"{lines[0].split(chr(9))[2]}: case 0 of 64, ")
    assert read_sweep(sweeps.resolve_sweep("hertz_fretting_map")).origin == SWEEPS / "hertz_fretting_map.toml"


def test_an_unknown_sweep_name_lists_the_shipped_ones(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert cli.main(["sweep", "no_such_sweep"]) == cli.EXIT_INPUT
    assert capsys.readouterr().err == (
        "fretting: error: no_such_sweep: No such file or directory, nor a shipped sweep: "
        "expected a sweep file or one of: hertz_fretting_map, hertz_running_map\n"
    )
