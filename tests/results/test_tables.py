"""`fretting export`: a result's per-cycle and per-step tables as CSV that pandas and spreadsheets
read back to the values of the result, the fields a policy did not store left empty."""

import numpy as np
import pandas as pd
import pytest
from conftest import HERTZ_TOML, hertz_sine_toml

from fretting import cli
from fretting.results.io import load
from fretting.results.tables import cycle_table, write_csv

#: Four cycles of Q and sigma out of phase on the Hertzian contact of conftest.
CYCLES = hertz_sine_toml(cycles=4, steps_per_cycle=8, phase_deg=90)


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """Result files of `CYCLES`: with every cycle's fields, and with those of the first and last only."""
    folder = tmp_path_factory.mktemp("export")
    (folder / "cycles.toml").write_text(CYCLES)
    found = {"all": folder / "all.h5", "some": folder / "some.h5"}
    for policy, path in zip(("all", "first,last"), found.values(), strict=True):
        command = ["run", str(folder / "cycles.toml"), "-o", str(path), "--nodes", "16", "--cycle-fields", policy]
        assert cli.main(command) == 0
    return found


def _read(path):
    """The table of the CSV file at `path`, each number read by Python's float (exact: the parsers
    of pandas before 3.1 may drop the last digits), ``True``/``False`` as booleans, empty as NaN."""

    def column(texts):
        if set(texts) <= {"True", "False"}:
            return texts == "True"
        return texts.map(lambda text: float(text) if text else np.nan)

    return pd.read_csv(path, comment="#", dtype=str, keep_default_na=False).apply(column)


def test_the_cycle_table_reads_back_to_the_result(runs, capsys):
    assert cli.main(["export", str(runs["all"])]) == 0
    written = runs["all"].with_name("all_cycles.csv")
    assert capsys.readouterr().out == f"{written}: 4 cycles, 8 columns\n"
    table, result = _read(written), load(runs["all"])
    assert table.cycle_number.tolist() == [1, 2, 3, 4]
    np.testing.assert_array_equal(table.cycle_dissipation, result.cycle_dissipation)  # every digit kept
    assert table.cycle_copied.dtype == bool
    for name in ("w", "slip_amplitude", "q_peak", "sigma_xx_peak", "sigma_xx_q_peak"):
        largest = result[name].max("x").values  # float32, written in its shortest form
        np.testing.assert_array_equal(table[f"{name}_max"].to_numpy(np.float32), largest, err_msg=name)
    assert table.w_max.iloc[-1] > 0 and table.cycle_dissipation.iloc[-1] > 0


def test_the_comments_give_each_column_its_units(runs, tmp_path):
    path = tmp_path / "table.csv"
    assert cli.main(["export", str(runs["all"]), "-o", str(path)]) == 0
    lines = path.read_text().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    assert comments[0] == "# fretting export of all.h5: one row per cycle"
    assert "# cycle_dissipation [J/m]: energy dissipated in each load cycle" in comments
    assert "# w_max [J/m^2]: largest over x of: energy dissipated per unit area in each load cycle" in comments
    header = lines[len(comments)].split(",")
    assert [line.split()[1] for line in comments[1:]] == header


def test_cycles_whose_fields_were_not_stored_are_empty(runs, tmp_path):
    path = tmp_path / "some.csv"
    assert cli.main(["export", str(runs["some"]), "-o", str(path)]) == 0
    table, every = _read(path), cycle_table(load(runs["all"]))
    assert table.w_max.isna().tolist() == [False, True, True, False]
    for cycle in (0, 3):
        assert np.float32(table.w_max[cycle]) == every.w_max.values[cycle]  # the same run, the same fields
    np.testing.assert_array_equal(table.cycle_dissipation, every.cycle_dissipation)


def test_the_step_table_holds_the_loads_of_each_recorded_step(runs, tmp_path, capsys):
    path = tmp_path / "steps.csv"
    assert cli.main(["export", str(runs["all"]), "--steps", "-o", str(path)]) == 0
    table, result = _read(path), load(runs["all"])
    assert capsys.readouterr().out.startswith(f"{path}: {result.sizes['step']} steps, ")
    for name in ("step", "Q", "sigma", "dissipation", "delta_Q", "cycle"):
        np.testing.assert_array_equal(table[name], result[name], err_msg=name)
    assert "q" not in table and "x" not in table  # fields along x are not scalars of a step


def test_a_result_without_cycles_is_a_one_line_error(tmp_path, capsys):
    (tmp_path / "ramp.toml").write_text(HERTZ_TOML + '[[loading]]\nkind = "linear"\nQ = [20e3]\n')
    assert cli.main(["run", str(tmp_path / "ramp.toml"), "-o", str(tmp_path / "ramp.h5"), "--nodes", "16"]) == 0
    capsys.readouterr()
    assert cli.main(["export", str(tmp_path / "ramp.h5")]) == cli.EXIT_INPUT
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "ramp.h5: found no load cycles, expected a result of a history with cycles" in err
    assert not list(tmp_path.glob("*.csv"))
    assert cli.main(["export", str(tmp_path / "ramp.h5"), "--steps"]) == 0


def test_an_interrupted_write_leaves_no_file(runs, tmp_path, monkeypatch):
    path = tmp_path / "table.csv"
    path.write_text("kept\n")

    def interrupted(value):
        raise KeyboardInterrupt

    monkeypatch.setattr("fretting.results.tables._cell", interrupted)
    with pytest.raises(KeyboardInterrupt):
        write_csv(cycle_table(load(runs["all"])), path)
    assert [p.name for p in tmp_path.iterdir()] == ["table.csv"] and path.read_text() == "kept\n"
