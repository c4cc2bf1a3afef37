"""History files: the examples, every block kind, and a message naming file, line and key for each bad input."""

import numpy as np
import pytest
from conftest import HERTZ_TOML as CONTACT

import fretting as fr
from fretting.cli import main
from fretting.loading import examples, history_file
from fretting.loading.history import RAMP_STEPS
from fretting.loading.history_file import HistoryFileError, read_history, read_history_source

EXAMPLES = sorted(examples.EXAMPLES.glob("*.toml"))  # the installed package's, not a checkout's


SHEAR = """
[[loading]]
kind = "linear"
Q = [20e3, -20e3]
steps_per_segment = 4
"""


def write(tmp_path, text, name="history.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def read(tmp_path, text):
    return read_history(write(tmp_path, text))


def error_of(tmp_path, text):
    with pytest.raises(HistoryFileError) as caught:
        read(tmp_path, text)
    return caught.value


def test_at_least_seven_commented_examples():
    assert len(EXAMPLES) >= 7
    assert (EXAMPLES[0].parent / "hertz_shear_cycling.toml") in EXAMPLES
    assert all(path.read_text().lstrip().startswith("#") for path in EXAMPLES)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda path: path.stem)
def test_examples_stay_in_partial_slip(path):
    contact, history = read_history(path)
    assert 100 < len(history) <= 2000
    assert history.cycle_count >= 3
    assert np.abs(history.sigma).max() <= contact.f * contact.p0
    if history.displaced:  # Q is found as it runs, and may reach f P: gross slip, followed under delta
        assert np.isnan(history.Q).all() and (history.delta[0], history.sigma[0]) == (0.0, 0.0)
        return
    P = contact.P if history.P is None else history.P  # a varying normal load: f P of each step
    assert np.all(np.abs(history.Q) <= 0.8 * contact.f * P)
    assert (history.Q[0], history.sigma[0]) == (0.0, 0.0)


def test_contact_from_E_and_nu_as_the_seed(tmp_path):
    contact, _ = read(tmp_path, CONTACT + SHEAR)
    assert contact.E_star == 210e9 / (2 * (1 - 0.3**2))
    assert (contact.f, contact.P, contact.profile.R) == (0.7, 1e5, 0.05)


@pytest.mark.parametrize(
    ("profile", "kind"),
    [('profile = "flat"\na = 1e-3', fr.FlatPunch), ('profile = "rounded_flat"\nb = 5e-4\nR = 0.02', fr.RoundedFlat)],
)
def test_other_profiles(tmp_path, profile, kind):
    contact, _ = read(tmp_path, f"[contact]\n{profile}\nE_star = 115e9\nf = 0.6\nP = 1e5\n" + SHEAR)
    assert isinstance(contact.profile, kind) and contact.E_star == 115e9


def test_tabulated_gap_next_to_the_file(tmp_path):
    x = np.linspace(-1e-3, 1e-3, 41)
    rows = "\n".join(f"{a:.17g},{a * a / 0.1:.17g}" for a in x)
    write(tmp_path, f"# a Hertz gap, R = 50 mm\nx,h0\n{rows}\n", "gap.csv")
    text = CONTACT.replace('profile = "hertz"\nR = 0.05', 'profile = "gap"\ntable = "gap.csv"')
    contact, _ = read(tmp_path, text + SHEAR)
    hertz = fr.Contact(fr.Hertz(0.05), contact.E_star, 0.7, 1e5)
    assert contact.a == pytest.approx(hertz.a, rel=1e-6)
    assert contact.centre == pytest.approx(0, abs=1e-9 * hertz.a)


@pytest.mark.parametrize(
    ("value", "expected"),
    [("[5e-4, -5e-4]", (-5e-4, 5e-4)), ('"corners"', 'found "corners", expected a list of numbers')],
)
def test_tabulated_gap_breakpoints(tmp_path, value, expected):
    """Where the gap's curvature jumps: read into the profile, sorted; anything else is named."""
    x = np.linspace(-2e-3, 2e-3, 41)
    write(tmp_path, "x,h0\n" + "\n".join(f"{a:.17g},{a * a / 0.1:.17g}" for a in x), "gap.csv")
    table = f'profile = "gap"\ntable = "gap.csv"\nbreakpoints = {value}'
    text = CONTACT.replace('profile = "hertz"\nR = 0.05', table) + SHEAR
    if isinstance(expected, tuple):
        contact, _ = read(tmp_path, text)
        assert contact.profile.breakpoints == expected
    else:
        error = error_of(tmp_path, text)
        assert error.key == "contact.breakpoints" and expected in str(error)


def test_tabulated_gap_must_cover_the_contact(tmp_path):
    x = np.linspace(-1e-4, 1e-4, 11)
    write(tmp_path, "x,h0\n" + "\n".join(f"{a:.17g},{a * a / 0.1:.17g}" for a in x), "gap.csv")
    text = CONTACT.replace('profile = "hertz"\nR = 0.05', 'profile = "gap"\ntable = "gap.csv"')
    error = error_of(tmp_path, text + SHEAR)
    assert (
        error.line == 3 and error.key == "contact.table" and "leaves the table's x in [-0.0001, 0.0001] m" in str(error)
    )


@pytest.mark.parametrize(
    ("rows", "words"), [("0,0\n1,1\n", "found 2 rows, expected at least 4"), ("0,0\n1,1\n3,1\n2,4\n", "x = 2 after 3")]
)
def test_bad_gap_table(tmp_path, rows, words):
    write(tmp_path, "x,h0\n" + rows, "gap.csv")
    text = CONTACT.replace('profile = "hertz"\nR = 0.05', 'profile = "gap"\ntable = "gap.csv"')
    error = error_of(tmp_path, text + SHEAR)
    assert error.key == "contact.table" and words in str(error)


def test_linear_blocks_continue_and_hold_the_other_load(tmp_path):
    text = CONTACT + SHEAR + '\n[[loading]]\nkind = "linear"\nsigma = [50e6]\nsteps_per_segment = 2\ncycle = true\n'
    _, history = read(tmp_path, text)
    np.testing.assert_array_equal(history.Q, [0, 5e3, 10e3, 15e3, 20e3, 10e3, 0, -10e3, -20e3, -20e3, -20e3])
    np.testing.assert_array_equal(history.sigma[-3:], [0, 25e6, 50e6])
    np.testing.assert_array_equal(history.vertex_step, [0, 4, 8, 10])
    np.testing.assert_array_equal(history.cycle, [0] * 9 + [1, 1])


def test_steps_per_segment_for_each_vertex(tmp_path):
    _, history = read(tmp_path, CONTACT + SHEAR.replace("steps_per_segment = 4", "steps_per_segment = [1, 3]"))
    np.testing.assert_array_equal(history.vertex_step, [0, 1, 4])


def test_sine_block_matches_the_python_api(tmp_path):
    block = (
        '\n[[loading]]\nkind = "sine"\nQ_amplitude = 30e3\nsigma_amplitude = 80e6\nphase_deg = 90\n'
        "cycles = 2\nsteps_per_cycle = 16\nsigma_mean = 10e6\nramp_steps = 5\n"
    )
    _, history = read(tmp_path, CONTACT + block)
    expected = fr.History.sinusoidal(30e3, 80e6, 90, 2, 16, sigma_mean=10e6, ramp_steps=5)
    for name in ("Q", "sigma", "vertex_step", "cycle"):
        np.testing.assert_array_equal(getattr(history, name), getattr(expected, name))


def test_repeated_blocks_count_cycles_on(tmp_path):
    block = """
[[loading]]
kind = "repeat"
count = 3
    [[loading.blocks]]
    kind = "sine"
    Q_amplitude = 10e3
    cycles = 2
    steps_per_cycle = 8
    [[loading.blocks]]
    kind = "sine"
    Q_amplitude = 20e3
    Q_mean = 5e3
    steps_per_cycle = 8
    ramp_steps = 2
"""
    _, history = read(tmp_path, CONTACT + block)
    assert history.cycle_count == 9
    np.testing.assert_array_equal(np.unique(history.cycle), np.arange(10))
    # ramps: 2 steps to the shifted mean, RAMP_STEPS back to zero from the second pass on
    assert len(history) == 1 + (16 + 2 + 8) + 2 * (RAMP_STEPS + 16 + 2 + 8)
    assert np.all(np.abs(np.diff(history.Q)) <= 20e3 * np.sin(2 * np.pi / 8) + 1e-9)  # continuous path


def test_random_block_matches_the_python_api(tmp_path):
    block = '\n[[loading]]\nkind = "random"\nseed = 5\ncycles = 4\nQ_amplitude = 30e3\nsteps_per_segment = 3\n'
    _, history = read(tmp_path, CONTACT + SHEAR + block)
    expected = fr.History.random_amplitude(4, 30e3, seed=5, steps_per_segment=3, start=(-20e3, 0.0))
    np.testing.assert_array_equal(history.Q[8:], expected.Q)
    np.testing.assert_array_equal(history.cycle[9:], expected.cycle[1:])


def test_csv_time_series(tmp_path):
    write(tmp_path, "# measured\nQ,sigma\n1e3,2e6\n\n3e3, 4e6\n", "series.csv")
    block = '\n[[loading]]\nkind = "csv"\nfile = "series.csv"\n'
    _, history = read(tmp_path, CONTACT + SHEAR + block)
    np.testing.assert_array_equal(history.Q[-3:], [-20e3, 1e3, 3e3])
    np.testing.assert_array_equal(history.sigma[-3:], [0, 2e6, 4e6])


def test_source_keeps_text_and_digest(tmp_path):
    path = write(tmp_path, CONTACT + SHEAR)
    source = read_history_source(path)
    assert source.text == path.read_text()
    assert (
        len(source.sha256) == 64
        and source.sha256 != read_history_source(write(tmp_path, CONTACT + SHEAR + "\n")).sha256
    )


def test_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError):
        read_history(tmp_path / "nowhere.toml")


@pytest.mark.parametrize(
    ("text", "line", "key", "words"),
    [
        (CONTACT + "\n[[loading]]\nkind = sine\n", 10, None, "TOML syntax"),
        (
            CONTACT + SHEAR.replace("steps_per_segment", "step_per_segment"),
            12,
            "loading[1].step_per_segment",
            "unknown",
        ),
        (CONTACT.replace('"hertz"', '"herz"'), 2, "contact.profile", 'found "herz", expected one of "hertz"'),
        (CONTACT.replace("P = 1e5", "P = -1e5") + SHEAR, 7, "contact.P", "found -100000.0, expected a number > 0"),
        (CONTACT.replace("f = 0.7", 'f = "0.7"') + SHEAR, 6, "contact.f", 'found "0.7", expected a number > 0'),
        (CONTACT.replace("R = 0.05", 'R = "-5 cm"') + SHEAR, 3, "contact.R", 'found "-5 cm", expected a number > 0'),
        (CONTACT.replace("nu = 0.3", "nu = 0.7") + SHEAR, 5, "contact.nu", "Poisson"),
        (CONTACT.replace("R = 0.05\n", "") + SHEAR, 1, "contact", "missing key 'R'"),
        (CONTACT.replace("f = 0.7", "f = 0.7\nE_star = 1e11") + SHEAR, 7, "contact.E_star", "either E_star or"),
        (CONTACT.replace("f = 0.7", "f = 0.7\nb = 1e-3") + SHEAR, 7, "contact.b", "unknown key"),
        (CONTACT.replace("E = 210e9\nnu = 0.3\n", "") + SHEAR, 1, "contact", "expected E_star or both E and nu"),
        (CONTACT.replace("E = 210e9\n", "") + SHEAR, 1, "contact", "missing key 'E'"),
        (CONTACT, None, None, "no [[loading]] blocks"),
        ("loading = []\n" + CONTACT, 1, "loading", "expected at least one block"),
        (CONTACT + SHEAR.replace('"linear"', '"square"'), 10, "loading[1].kind", 'found "square"'),
        (CONTACT + SHEAR.replace("Q = [20e3, -20e3]", "Q = [20e3, inf]"), 11, "loading[1].Q", "finite numbers"),
        (CONTACT + SHEAR.replace("= 4", "= 0"), 12, "loading[1].steps_per_segment", "found 0, expected an integer"),
        (CONTACT + SHEAR.replace("= 4", "= [1, 2, 3]"), 12, "loading[1].steps_per_segment", "found 3 values"),
        (CONTACT + SHEAR.replace("Q = [20e3, -20e3]", "Q = [1.0]\nsigma = [1.0, 2.0]"), 12, "loading[1].sigma", ""),
        (CONTACT + SHEAR.replace("Q = [20e3, -20e3]", ""), 9, "loading[1]", "missing key 'Q', 'sigma' or 'P'"),
        (CONTACT + '[[loading]]\nkind = "sine"\ncycles = -2\n', 10, "loading[1].cycles", "found -2"),
        (CONTACT + '[[loading]]\nkind = "random"\nseed = 1\n', 8, "loading[1]", "missing key 'cycles'"),
        (CONTACT + SHEAR + "[other]\n", 13, "other", "unknown key, expected one of: contact, loading"),
    ],
)
def test_bad_input_names_file_line_and_key(tmp_path, text, line, key, words):
    error = error_of(tmp_path, text)
    assert (error.line, error.key) == (line, key)
    assert error.path == tmp_path / "history.toml"
    message = str(error)
    assert message.startswith(f"{tmp_path / 'history.toml'}{f':{line}' if line else ''}: ")
    assert words in message and "\n" not in message


def test_errors_inside_nested_blocks_point_at_their_line(tmp_path):
    text = CONTACT + '[[loading]]\nkind = "repeat"\ncount = 2\n  [[loading.blocks]]\n  kind = "sine"\n  cycle = 3\n'
    error = error_of(tmp_path, text)
    assert (error.line, error.key) == (13, "loading[1].blocks[1].cycle")


def test_inline_blocks_point_at_their_key(tmp_path):
    text = CONTACT + '[[loading]]\nkind = "repeat"\ncount = 2\nblocks = [{ kind = "sine", cycles = 0 }]\n'
    error = error_of(tmp_path, text)
    assert (error.line, error.key) == (11, "loading[1].blocks[1].cycles")


@pytest.mark.parametrize(
    ("table", "line", "words"),
    [
        (None, 16, "cannot read"),
        ("", None, "found no header row"),
        ("Q,time\n1,2\n", 1, "found columns Q, time, expected one or more of the columns Q, sigma"),
        ("Q\n", 1, "found no data rows"),
        ("Q,sigma\n1,2\n3\n", 3, "found 1 values, expected 2"),
        ("# loads\nQ,sigma\n1,2\n3,abc\n", 4, "sigma: found 'abc', expected a finite number"),
    ],
)
def test_bad_csv_names_its_line(tmp_path, table, line, words):
    if table is not None:
        write(tmp_path, table, "series.csv")
    error = error_of(tmp_path, CONTACT + SHEAR + '\n[[loading]]\nkind = "csv"\nfile = "series.csv"\n')
    assert error.line == line and words in str(error)
    assert error.path == tmp_path / ("history.toml" if table is None else "series.csv")


def test_a_table_that_is_not_a_regular_file_of_bounded_size_is_refused(tmp_path, monkeypatch):
    """A device or a pipe named as a table would hang the run, a huge file fill the memory (issue 38):
    one line naming the history file's key, the path and what was expected, the file not read."""
    block = '\n[[loading]]\nkind = "csv"\nfile = "{}"\n'
    error = error_of(tmp_path, CONTACT + SHEAR + block.format("/dev/zero"))
    assert "loading[2].file: /dev/zero is not a regular file, expected a regular file of at most" in str(error)
    write(tmp_path, "Q,sigma\n1,2\n", "series.csv")
    monkeypatch.setattr(history_file, "MAX_TABLE_BYTES", 8)
    error = error_of(tmp_path, CONTACT + SHEAR + block.format("series.csv"))
    assert "series.csv is 12 bytes, expected a regular file of at most 8 bytes" in str(error)


def test_not_utf8(tmp_path):
    path = tmp_path / "history.toml"
    path.write_bytes(b"# \xff\n" + CONTACT.encode())
    with pytest.raises(HistoryFileError, match="expected UTF-8"):
        read_history(path)


def wear_scar(path):
    """Issue 19's worn pad: Hertz R = 50 mm with a 3 um central hollow, 401 rows over +-1 mm, shifted to min 0."""
    x = np.linspace(-1e-3, 1e-3, 401)
    h0 = x**2 / 0.1 + 3e-6 * np.exp(-((x / 1.5e-4) ** 2))
    path.write_text("x,h0\n" + "\n".join(f"{u:.17g},{v:.17g}" for u, v in zip(x, h0 - h0.min(), strict=True)))


def test_a_gap_that_is_not_convex_where_it_touches_is_refused(tmp_path):
    """E = 74 GPa, nu = 0.33, P for p0 = 157 MPa of the hollow-free pad: exit 2 from the command line."""
    wear_scar(tmp_path / "gap.csv")
    E_star = fr.plane_strain_modulus(74e9, 0.33)
    a = 0.1 * 157e6 / E_star
    contact = (
        f'[contact]\nprofile = "gap"\ntable = "gap.csv"\nE = 74e9\nnu = 0.33\nf = 0.75\nP = {np.pi * a * 157e6 / 2!r}\n'
    )
    error = error_of(tmp_path, contact + SHEAR)
    assert error.line == 3 and error.key == "contact.table"
    assert "curvature is first negative at x = -9.5e-05 m, so the pressure is negative at x = -9.7" in str(error)
    assert "\n" not in str(error)
    assert main(["run", str(tmp_path / "history.toml"), "-o", str(tmp_path / "out.h5")]) == 2
    assert not (tmp_path / "out.h5").exists()


def test_a_concave_table_names_its_curvature(tmp_path):
    x = np.linspace(-1e-3, 1e-3, 41)
    write(tmp_path, "x,h0\n" + "\n".join(f"{u:.17g},{1e-5 - u * u / 0.1:.17g}" for u in x), "gap.csv")
    error = error_of(
        tmp_path, CONTACT.replace('profile = "hertz"\nR = 0.05', 'profile = "gap"\ntable = "gap.csv"') + SHEAR
    )
    assert error.key == "contact.table" and "the table's curvature is first negative at x = -0.001 m" in str(error)


def test_csv_with_a_byte_order_mark(tmp_path):
    """A spreadsheet's "CSV UTF-8" starts with U+FEFF: read as the same table."""
    block = '\n[[loading]]\nkind = "csv"\nfile = "series.csv"\n'
    (tmp_path / "series.csv").write_bytes("\ufeffQ,sigma\n1e3,2e6\n3e3,4e6\n".encode())
    _, marked = read(tmp_path, CONTACT + block)
    (tmp_path / "series.csv").write_bytes(b"Q,sigma\n1e3,2e6\n3e3,4e6\n")
    _, plain = read(tmp_path, CONTACT + block)
    np.testing.assert_array_equal(marked.Q, plain.Q)
    np.testing.assert_array_equal(marked.sigma, plain.sigma)


@pytest.mark.parametrize(("line", "specimen"), [("", 2), ("specimen = 1\n", 1), ("specimen = 2\n", 2)])
def test_the_specimen_is_named_in_the_contact(tmp_path, line, specimen):
    contact, _ = read(tmp_path, CONTACT + line + SHEAR)
    assert contact.specimen == specimen


@pytest.mark.parametrize("value", ["3", '"2"', "true"])
def test_a_bad_specimen(tmp_path, value):
    error = error_of(tmp_path, CONTACT + f"specimen = {value}\n" + SHEAR)
    assert error.key == "contact.specimen" and error.line == 8 and "expected one of 1, 2" in str(error)


def test_blocks_nested_beyond_what_can_be_read_are_one_line(tmp_path):
    """Repeat blocks 200 deep: the TOML reader and the block reader recurse per level; a one-line
    error, not a RecursionError (issue 38). 100 levels still read."""
    block = '{kind = "linear", Q = [1e4, 0], steps_per_segment = 2}'
    for depth in (100, 200):
        inner = block
        for _ in range(depth):
            inner = f'{{kind = "repeat", count = 1, blocks = [{inner}]}}'
        path = write(tmp_path, CONTACT + f'\n[[loading]]\nkind = "repeat"\ncount = 1\nblocks = [{inner}]\n')
        if depth == 100:
            assert len(read_history(path)[1]) == 5  # the block: 0 -> 1e4 -> 0, two steps a segment
        else:
            with pytest.raises(HistoryFileError, match="nested deeper than can be read"):
                read_history(path)


def test_a_file_that_is_no_table_has_its_first_line_said_not_shown(tmp_path):
    """A csv block naming a file that is no table (a key file, the environment) does not echo its
    first line; a header with a misspelt column name is still shown (issue 38)."""
    (tmp_path / "secret").write_text("token: 0123456789abcdef\n")
    (tmp_path / "typo.csv").write_text("Q,sigmaa\n1,2\n")
    cases = (("secret", "a first row of no column names", "0123456789"), ("typo.csv", "sigmaa", None))
    for name, said, hidden in cases:
        path = write(tmp_path, CONTACT + f'\n[[loading]]\nkind = "csv"\nfile = "{name}"\n')
        with pytest.raises(HistoryFileError) as error:
            read_history(path)
        assert said in str(error.value) and (hidden is None or hidden not in str(error.value))
