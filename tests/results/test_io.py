"""Result files: round trip, compression, atomic replacement, and results joined bit for bit."""

import datetime
import itertools
import json

import h5py
import numpy as np
import pytest
import xarray as xr

import fretting as fr
from fretting.physics.profiles import profile_class, recorded_profile
from fretting.results import io
from fretting.results.io import (
    CYCLE_CHUNK_ROWS,
    WRITTEN_ATTRIBUTES,
    ResultError,
    join_results,
    load,
    save,
    save_joined,
)

NODES = 48


@pytest.fixture(scope="module")
def history():
    """Non-proportional, with a ramp, cycles, a pause between cycles and random amplitudes."""
    contact = _contact()
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    waves = fr.History.sinusoidal(0.5 * fP, 0.6 * fp0, phase_deg=90, cycles=2, steps_per_cycle=24)
    random = fr.History.random_amplitude(3, 0.6 * fP, 0.5 * fp0, seed=11, steps_per_segment=5, start=waves.end)
    return fr.History.concatenate([waves, random])


@pytest.fixture(scope="module")
def whole(history):
    return fr.simulate(_contact(), history, nodes=NODES)


def _contact():
    return fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), 0.7, 1e5)


def without_provenance(result):
    """`result` without the attributes that `save` adds."""
    copy = result.copy()
    copy.attrs = {name: value for name, value in result.attrs.items() if name not in WRITTEN_ATTRIBUTES}
    return copy


def test_round_trip_is_identical(tmp_path, whole):
    assert whole.sizes["zone"] > 1 and whole.cycle_dissipation.size == 5
    path = tmp_path / "result.h5"
    save(whole, path)
    loaded = load(path)
    xr.testing.assert_identical(without_provenance(loaded), whole)
    assert loaded.stick.dtype == bool
    assert loaded.cycle.dims == ("step",) and loaded.cycle_dissipation.dims == whole.cycle_dissipation.dims


def test_file_is_compressed_hdf5_with_provenance(tmp_path, whole):
    path = tmp_path / "result.h5"
    save(whole, path)
    with h5py.File(path, "r") as file:
        assert file["q"].compression == "gzip" and file["stick"].compression == "gzip"
        np.testing.assert_array_equal(file["Q"][:], whole.Q.values)
    attrs = load(path).attrs
    created = datetime.datetime.fromisoformat(attrs["created"])
    assert abs(datetime.datetime.now(datetime.UTC) - created) < datetime.timedelta(minutes=5)
    versions = json.loads(attrs["versions"])
    assert versions["numpy"] == np.__version__ and versions["fretting"] == fr.__version__
    assert {"xarray", "h5netcdf", "h5py", "scipy", "hdf5", "python"} <= set(versions)


def test_load_closes_the_file(tmp_path, whole):
    path = tmp_path / "result.h5"
    save(whole, path)
    load(path)
    h5py.File(path, "w").close()  # HDF5 refuses to truncate a file that is still open


@pytest.mark.parametrize("failure", [OSError("disk full"), KeyboardInterrupt()])
def test_failed_write_leaves_the_old_file(tmp_path, whole, monkeypatch, failure):
    path = tmp_path / "result.h5"
    path.write_bytes(b"the previous result")

    def half_written(image, temporary, *arguments):
        temporary.write_bytes(bytes(image[: len(image) // 2]))
        raise failure

    monkeypatch.setattr(io, "_put", half_written)
    with pytest.raises(type(failure)):
        save(whole, path)
    assert path.read_bytes() == b"the previous result"
    assert [child.name for child in tmp_path.iterdir()] == ["result.h5"]


def test_load_rejects_other_files(tmp_path):
    other = tmp_path / "other.nc"
    xr.Dataset({"Q": ("step", [1.0])}).to_netcdf(other, engine="h5netcdf")
    with pytest.raises(ResultError, match="found no variable sigma, expected a result of fretting"):
        load(other)
    text = tmp_path / "text.h5"
    text.write_text("not HDF5")
    with pytest.raises(ResultError, match="text.h5: found no netCDF-4 data"):
        load(text)
    with pytest.raises(FileNotFoundError):
        load(tmp_path / "none.h5")


@pytest.mark.parametrize("splits", [[1], [24, 25], [7, 30, 31, 58], list(range(3, 79, 9))])
def test_run_in_parts_equals_the_whole_run(history, whole, splits):
    """Bit for bit, including the sub-grid stick ends, the vertices and the cycle energies."""
    contact = _contact()
    bounds = [0, *splits, len(history) - 1]
    parts = [fr.simulate(contact, history[: bounds[1] + 1], nodes=NODES)]
    for start, stop in itertools.pairwise(bounds[1:]):
        parts.append(fr.simulate(contact, history[start : stop + 1], nodes=NODES, state=fr.final_state(parts[-1])))
    xr.testing.assert_identical(join_results(parts), whole)


@pytest.mark.parametrize("splits", [[8], [9, 40], [3, 4, 17, 29, 30, 77], list(range(5, 96, 13))])
def test_periodic_run_in_parts_equals_the_whole_run(splits):
    """Cycles whose state repeats give equal rows, which the joiner holds once: cut into parts
    inside and between such runs of rows, and between parts that each solve their first cycles
    anew, the join is still the whole run bit for bit (but for which cycles were copied)."""
    contact = _contact()
    history = fr.History.sinusoidal(0.4 * contact.f * contact.P, cycles=12, steps_per_cycle=8)
    whole = fr.simulate(contact, history, nodes=NODES)
    assert whole.cycle_copied.values.sum() >= 9  # the state became periodic
    bounds = [0, *splits, len(history) - 1]
    parts = [fr.simulate(contact, history[: bounds[1] + 1], nodes=NODES)]
    for start, stop in itertools.pairwise(bounds[1:]):
        parts.append(fr.simulate(contact, history[start : stop + 1], nodes=NODES, state=fr.final_state(parts[-1])))
    joined = join_results(parts)
    xr.testing.assert_identical(joined.drop_vars("cycle_copied"), whole.drop_vars("cycle_copied"))


def test_join_of_one_part_and_of_a_repeated_end(whole):
    xr.testing.assert_identical(join_results([whole]), whole)
    last = fr.History(whole.Q.values[-1:], whole.sigma.values[-1:], [0], whole.cycle.values[-1:])
    repeated = fr.simulate(_contact(), last, nodes=NODES, state=fr.final_state(whole))
    xr.testing.assert_identical(join_results([whole, repeated]), whole)


def test_join_rejects_parts_that_do_not_continue(history):
    first = fr.simulate(_contact(), history[:11], nodes=NODES)
    elsewhere = fr.simulate(_contact(), history[20:31], nodes=NODES)
    with pytest.raises(ResultError, match="not where the previous one ends"):
        join_results([first, elsewhere])
    with pytest.raises(ResultError, match="no results"):
        join_results([])


@pytest.mark.parametrize("record", [[], [0], [5, 33, 34, 78], "every fifth"])
def test_parts_recording_some_steps_join_into_the_whole_run(history, record):
    """Each part records its share of the steps; energy and slip range per cycle still cover every step."""
    contact = _contact()
    steps = np.arange(0, len(history), 5) if record == "every fifth" else np.array(record, dtype=int)
    whole = fr.simulate(contact, history, nodes=NODES, record=steps)
    bounds = [0, 7, 30, 31, 58, len(history) - 1]
    parts = []
    for start, stop in itertools.pairwise(bounds):
        mine = steps[(steps >= start) & (steps <= stop)] - start
        state = fr.final_state(parts[-1]) if parts else None
        parts.append(fr.simulate(contact, history[start : stop + 1], nodes=NODES, state=state, record=mine))
    xr.testing.assert_identical(join_results(parts), whole)


@pytest.mark.slow
@pytest.mark.parametrize("splits", [[24, 25], [7, 30, 31, 58]])
def test_parts_saved_and_joined_on_disk_equal_the_join_in_memory(tmp_path, history, whole, splits):
    """`save_joined` appends the per-cycle rows part by part (a cycle that spans parts rewritten by
    the later part's row) and gives the file `join_results` would: bit for bit, with an unlimited,
    chunked ``cycle_number`` that h5py sees."""
    contact = _contact()
    bounds = [0, *splits, len(history) - 1]
    parts = [fr.simulate(contact, history[: bounds[1] + 1], nodes=NODES)]
    for start, stop in itertools.pairwise(bounds[1:]):
        parts.append(fr.simulate(contact, history[start : stop + 1], nodes=NODES, state=fr.final_state(parts[-1])))
    paths = [tmp_path / f"{k}.h5" for k in range(len(parts))]
    for part, path in zip(parts, paths, strict=True):
        save(part, path)
    assert sum(part.sizes["cycle_number"] for part in parts) > whole.sizes["cycle_number"]  # cycles span parts
    save_joined(paths, tmp_path / "joined.h5", {"note": "joined"})
    joined = load(tmp_path / "joined.h5")
    assert joined.attrs["note"] == "joined"
    xr.testing.assert_identical(without_provenance(joined).drop_attrs(), whole.drop_attrs())
    with h5py.File(tmp_path / "joined.h5", "r") as file:
        assert file["w"].maxshape == (None, NODES) and file["w"].shape == (5, NODES)
        assert file["cycle_dissipation"].chunks == (CYCLE_CHUNK_ROWS,) and file["w"].compression == "gzip"
        np.testing.assert_array_equal(file["cycle_dissipation"][:], whole.cycle_dissipation.values)


@pytest.mark.parametrize(
    ("contact_table", "facts"),
    [
        ('profile = "rounded_flat"\nb = 2e-3\nR = 0.05\nE = 210e9\nnu = 0.28', {"b": 2e-3, "R": 0.05}),
        ('profile = "gap"\ntable = "gap.csv"\nbreakpoints = [-1e-4, 1e-4]\nE_star = 115e9', {}),
    ],
    ids=["rounded_flat", "gap_table"],
)
def test_a_result_file_records_the_profile_and_nu_as_facts(tmp_path, contact_table, facts):
    """The class, each parameter and nu, read back from the file, rebuild the contact's profile bit for bit;
    nu is recorded where the history file gives it, and absent where it gives E_star alone."""
    x = np.linspace(-1e-3, 1e-3, 41).tolist()
    rows = [f"{v!r},{max(abs(v) - 1e-4, 0.0) ** 2 / 0.1!r}\n" for v in x]  # a flat of half-width 0.1 mm
    (tmp_path / "gap.csv").write_text("x,h0\n" + "".join(rows))
    path = tmp_path / "run.toml"
    loading = "[[loading]]\nkind = 'linear'\nQ = [3e3]\nsteps_per_segment = 2\n"
    path.write_text(f"[contact]\n{contact_table}\nf = 0.6\nP = 2e4\n\n{loading}")
    contact = fr.read_history(path)[0]
    fr.run_file(path, tmp_path / "run.h5", fr.models.Grid(16))
    attrs = load(tmp_path / "run.h5").attrs
    name, parameters = recorded_profile(attrs)
    assert name == attrs["profile_class"] == type(contact.profile).__name__
    assert repr(profile_class(name).from_parameters(parameters)) == repr(contact.profile) == attrs["profile"]
    assert {key: parameters[key] for key in facts} == facts
    assert attrs.get("nu") == (0.28 if "nu" in contact_table else None)
