"""The displacement `delta` in `csv`, `sine` and `random` blocks of a history file: the same path as the
block of Q with its numbers, read as delta; and the one-line errors naming the file and the key."""

import numpy as np
import pytest
from conftest import HERTZ_TOML

import fretting as fr
from fretting.loading.history_file import HistoryFileError

CONTACT = HERTZ_TOML + "datum = 5e-3\n"


def read(tmp_path, *blocks, table="delta\n5e-7\n-5e-7\n1e-6\n"):
    (tmp_path / "d.csv").write_text(table)
    path = tmp_path / "moved.toml"
    path.write_text(CONTACT + "".join(f"\n[[loading]]\n{block}\n" for block in blocks))
    return fr.read_history(path)


def as_Q(tmp_path, block):
    """The history of `block` with ``delta`` read as ``Q`` (the same numbers)."""
    return read(tmp_path, block.replace("delta", "Q").replace('"d.csv"', '"q.csv"'), table="Q\n5e-7\n-5e-7\n1e-6\n")[1]


@pytest.mark.parametrize(
    "block",
    [
        'kind = "sine"\ndelta_amplitude = 2e-6\ndelta_mean = 1e-7\ncycles = 2\nsteps_per_cycle = 16',
        'kind = "random"\ndelta_amplitude = 1e-6\ncycles = 3\nseed = 4',
        'kind = "csv"\nfile = "d.csv"\nsteps_per_segment = 3',
    ],
    ids=["sine", "random", "csv"],
)
def test_a_block_of_delta_is_the_block_of_Q_read_as_delta(tmp_path, block):
    (tmp_path / "q.csv").write_text("Q\n5e-7\n-5e-7\n1e-6\n")
    _, moved = read(tmp_path, block)
    forced = as_Q(tmp_path, block)
    assert np.isnan(moved.Q).all()
    assert np.array_equal(moved.delta, forced.Q)
    assert np.array_equal(moved.vertex_step, forced.vertex_step)
    assert (moved.cycle is None) == (forced.cycle is None)


def test_blocks_of_delta_follow_each_other_and_run(tmp_path):
    contact, history = read(
        tmp_path,
        'kind = "linear"\ndelta = [1e-6]',
        'kind = "sine"\ndelta_amplitude = 3e-6\ndelta_mean = 1e-6\ncycles = 1\nsteps_per_cycle = 16',
        'kind = "csv"\nfile = "d.csv"',
    )
    assert history.delta[0] == 0 and history.delta[-1] == 1e-6
    result = fr.simulate(contact, history)
    assert set(np.unique(result.regime.values)) == {0, 1, 2}  # the sine reaches gross slip


@pytest.mark.parametrize(
    "blocks,message",
    [
        (['kind = "sine"\nQ_amplitude = 1e3\ndelta_amplitude = 1e-6'], r"loading\[1\]\.delta_amplitude.*both"),
        (['kind = "random"\nQ_mean = 1e3\ndelta_mean = 1e-6\ncycles = 2\nseed = 1'], r"loading\[1\]\.delta_mean.*both"),
        (['kind = "linear"\ndelta = [1e-6]', 'kind = "sine"\nsigma_amplitude = 1e6'], r"loading\[2\].*neither Q nor"),
        (['kind = "linear"\nQ = [1e3]', 'kind = "sine"\ndelta_amplitude = 1e-6'], r"loading\[2\]\.delta_amplitude.*Q"),
        (
            ['kind = "linear"\nQ = [1e3]', 'kind = "csv"\nfile = "d.csv"'],
            r"loading\[2\]\.file.*column delta after a block of Q",
        ),
    ],
)
def test_bad_blocks_are_one_line_errors_naming_file_and_key(tmp_path, blocks, message):
    with pytest.raises(HistoryFileError, match=message) as caught:
        read(tmp_path, *blocks)
    assert "moved.toml" in str(caught.value) and "\n" not in str(caught.value)


def test_a_table_of_both_Q_and_delta_is_an_error(tmp_path):
    with pytest.raises(HistoryFileError, match=r"moved.toml.*loading\[1\]\.file.*both column Q and column delta"):
        read(tmp_path, 'kind = "csv"\nfile = "d.csv"', table="Q,delta\n1,1e-7\n2,2e-7\n")
