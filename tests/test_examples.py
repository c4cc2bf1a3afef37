"""The shipped example histories: listed by name, found by name from any directory, a path wins over a name,
copied to be edited."""

from pathlib import Path

import pytest
from conftest import HERTZ_TOML

from fretting import cli
from fretting.loading.examples import EXAMPLES, example_path, examples, resolve_history
from fretting.results.io import load


@pytest.fixture
def empty(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_every_example_has_a_one_sentence_description():
    listed = examples()
    assert list(listed) == sorted(path.stem for path in EXAMPLES.glob("*.toml"))
    assert "hertz_shear_cycling" in listed
    for name, description in listed.items():
        assert description.endswith(".") and description.count(". ") == 0, name


def test_example_path_with_or_without_suffix():
    assert example_path("hertz_random") == example_path("hertz_random.toml") == EXAMPLES / "hertz_random.toml"


@pytest.mark.parametrize("name", ["no_such_example", "sweeps/hertz_fretting_map", "../examples/hertz_random"])
def test_unknown_name_lists_the_names(name):
    with pytest.raises(FileNotFoundError, match="expected a history file or one of: asymmetric_pad") as caught:
        example_path(name)
    assert caught.value.filename == name


def test_an_existing_path_wins_over_a_name(empty):
    (empty / "hertz_random").write_text(HERTZ_TOML)
    assert resolve_history("hertz_random").resolve() == empty / "hertz_random"
    assert resolve_history("hertz_shear_cycling") == EXAMPLES / "hertz_shear_cycling.toml"


def test_command_lists_the_examples(capsys):
    assert cli.main(["examples"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in lines] == list(examples())
    assert all(line.split(maxsplit=1)[1] == examples()[line.split()[0]] for line in lines)


def test_run_an_example_by_name_from_an_empty_directory(empty, capsys):
    assert cli.main(["run", "hertz_shear_cycling", "-o", "out.h5"]) == 0
    result = load(empty / "out.h5")
    assert result.attrs["history_toml"] == example_path("hertz_shear_cycling").read_text()
    assert result.attrs["steps"] == 673


def test_unknown_name_is_a_one_line_input_error(empty, capsys):
    assert cli.main(["validate", "no_such_example"]) == cli.EXIT_INPUT
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert err.startswith("fretting: error: no_such_example: No such file or directory, nor a shipped example")


def test_copy_writes_an_editable_copy_with_its_tables(empty, capsys):
    assert cli.main(["examples", "--copy", "asymmetric_pad_measured_cycle", "mine"]) == 0
    written = capsys.readouterr().out.split()
    assert written == [
        "mine/asymmetric_pad_measured_cycle.toml",
        "mine/asymmetric_pad_gap.csv",
        "mine/measured_cycle.csv",
    ]
    for name in written:
        assert (empty / name).read_bytes() == (EXAMPLES / Path(name).name).read_bytes()
    edited = empty / written[0]
    edited.write_text(edited.read_text().replace("count = 3", "count = 2"))
    assert cli.main(["validate", str(edited)]) == 0
    assert "2 cycles" in capsys.readouterr().out


def test_copy_into_the_current_folder_runs_by_path(empty, capsys):
    assert cli.main(["examples", "--copy", "hertz_random.toml"]) == 0
    assert capsys.readouterr().out.split() == ["hertz_random.toml"]
    assert resolve_history("hertz_random.toml") == Path("hertz_random.toml")


def test_copy_overwrites_nothing(empty, capsys):
    (empty / "measured_cycle.csv").write_text("mine")
    assert cli.main(["examples", "--copy", "asymmetric_pad_measured_cycle"]) == cli.EXIT_INPUT
    err = capsys.readouterr().err
    assert err == "fretting: error: measured_cycle.csv: File exists, not overwritten by the example\n"
    assert sorted(path.name for path in empty.iterdir()) == ["measured_cycle.csv"]
    assert (empty / "measured_cycle.csv").read_text() == "mine"


def test_copy_of_an_unknown_name_is_a_one_line_input_error(empty, capsys):
    assert cli.main(["examples", "--copy", "no_such_example"]) == cli.EXIT_INPUT
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no_such_example: No such file or directory, nor a shipped example" in err
    assert list(empty.iterdir()) == []


def test_a_folder_without_copy_is_a_usage_error(empty, capsys):
    with pytest.raises(SystemExit) as exited:
        cli.main(["examples", "somewhere"])
    assert exited.value.code == 2
    assert capsys.readouterr().err.splitlines()[-1].endswith("DIR 'somewhere': a folder is for --copy NAME")
