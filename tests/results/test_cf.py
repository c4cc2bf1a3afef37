"""The files of `fretting` as the tools of its users read them: CF-1.11 (no fill values on
coordinates, ``Conventions``, ``title``, ``history``, axes that cf_xarray finds), units that pint
parses, no path of the machine that wrote them; and files of fretting 0.1.0 (units ``m2``,
``Pa2``, ``J/m2``) read with today's spelling."""

import datetime
from pathlib import Path

import cf_xarray  # noqa: F401 (the accessor ds.cf)
import h5py
import numpy as np
import pint
import pytest
import xarray as xr
from conftest import SINE_TOML as SINE

import fretting as fr
from fretting import cli
from fretting.analysis import nucleation
from fretting.loading.examples import EXAMPLES
from fretting.results.io import CONVENTIONS, LEGACY_UNITS, load, recorded_path, save, save_joined
from fretting.results.variables import VARIABLES
from fretting.studies import sweeps

UNITS = pint.UnitRegistry()


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """Kind -> a file of each kind, written as a user writes them: a result of ``fretting run`` (its
    parts joined) and one written again by `fretting.save`, a stress field with a criterion's maps, and
    a sweep over two keys of the contact; every path given absolute."""
    folder = tmp_path_factory.mktemp("files")
    history, sweep = folder / "sine.toml", folder / "map.toml"
    history.write_text(SINE)
    sweep.write_text('history = "sine.toml"\n[grid]\ncontact.f = [0.6, 0.7]\ncontact.P = [1e5, 1.2e5]\n')
    found = {kind: folder / f"{kind}.h5" for kind in KINDS}
    material = EXAMPLES / "materials" / "steel.toml"
    for command in [
        ["run", str(history), "-o", str(found["result"]), "--nodes", "32"],
        [
            "stress",
            str(found["result"]),
            "-o",
            str(found["stress"]),
            *"--nx 21 --nz 6 --material".split(),
            str(material),
        ],
        ["sweep", str(sweep), "-o", str(found["sweep"])],
    ]:
        assert cli.main(command) == 0
    save(load(found["result"]), found["saved"])
    return found


KINDS = ("result", "saved", "stress", "sweep")


def _opened(path):
    return xr.open_dataset(path, engine="h5netcdf")


@pytest.mark.parametrize("kind", KINDS)
def test_coordinates_have_no_fill_value(files, kind):
    with _opened(files[kind]) as dataset:
        coordinates = [name for name in dataset.dims if name in dataset.variables]
    assert coordinates
    with h5py.File(files[kind], "r") as file:
        for name in coordinates:
            assert "_FillValue" not in file[name].attrs, name


@pytest.mark.parametrize("kind", KINDS)
def test_global_attributes_say_conventions_title_source_and_history(files, kind):
    with _opened(files[kind]) as dataset:
        attrs = dataset.attrs
    assert attrs["Conventions"] == CONVENTIONS == "CF-1.11"
    assert attrs["title"].startswith("fretting ") and attrs["source"] == f"fretting {fr.__version__}"
    lines = attrs["history"].split("\n")
    assert len(lines) == (2 if kind in ("result", "saved") else 1) + (kind == "saved")  # a line per write
    for line in lines:
        time, wrote = line.split(" ", 1)
        assert datetime.datetime.fromisoformat(time).tzinfo == datetime.UTC
        assert wrote.startswith("fretting.") and wrote.endswith(f"(fretting {fr.__version__})")


@pytest.mark.parametrize("kind", KINDS)
def test_every_unit_parses_in_pint(files, kind):
    with _opened(files[kind]) as dataset:
        units = {
            name: variable.attrs["units"] for name, variable in dataset.variables.items() if "units" in variable.attrs
        }
    assert units
    for name, text in units.items():
        assert UNITS.parse_units(text) is not None, name


@pytest.mark.parametrize(("kind", "axes"), [("result", ["X"]), ("saved", ["X"]), ("stress", ["X", "Z"])])
def test_cf_xarray_finds_the_axes(files, kind, axes):
    with _opened(files[kind]) as dataset:
        assert sorted(dataset.cf.axes) == axes
        assert dataset.cf["X"].name == "x" and dataset.x.attrs["axis"] == "X"
        if "Z" in axes:
            assert dataset.cf["Z"].name == "z" and dataset.z.attrs["positive"] == "down"


@pytest.mark.parametrize("kind", KINDS)
def test_no_path_of_the_machine_in_the_file(files, kind):
    folder = str(files[kind].parent)
    with _opened(files[kind]) as dataset:
        texts = [value for value in dataset.attrs.values() if isinstance(value, str)]
        texts += [v for variable in dataset.variables.values() for v in variable.attrs.values() if isinstance(v, str)]
        recorded = dataset.attrs.get("history_file")
    assert texts and not [text for text in texts if folder in text]
    if kind != "stress":
        assert recorded == "sine.toml"


def test_a_recorded_path_is_relative_as_given_or_the_name_alone(tmp_path):
    assert recorded_path("runs/shear.toml") == "runs/shear.toml"
    assert recorded_path(tmp_path / "runs" / "shear.toml") == "shear.toml"
    assert recorded_path(Path("shear.toml")) == "shear.toml"


@pytest.fixture(scope="module")
def contact():
    return fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), 0.7, 1e5)


@pytest.fixture(scope="module")
def result(contact):
    """Two cycles of Q and sigma out of phase: every per-cycle field and peak."""
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    history = fr.History.sinusoidal(0.5 * fP, 0.4 * fp0, phase_deg=90, cycles=2, steps_per_cycle=16)
    return fr.simulate(contact, history, fr.models.Grid(32))


def _unit_strings():
    """Every units string that a file of fretting may hold, by where it is declared."""
    declared = {f"VARIABLES[{name!r}]": units for name, (_, units, _) in VARIABLES.items()}
    declared |= {f"sweeps.VARIABLES[{name!r}]": units for name, (units, _, _) in sweeps.VARIABLES.items()}
    declared |= {f"sweeps.UNITS[{name!r}]": units for name, units in sweeps.UNITS.items()}
    return declared


@pytest.mark.parametrize(("where", "units"), _unit_strings().items())
def test_every_declared_unit_parses_in_pint(where, units):
    UNITS.parse_units(units)  # raises pint.UndefinedUnitError for "m2"


@pytest.mark.parametrize(("old", "new"), LEGACY_UNITS.items())
def test_legacy_units_fail_in_pint_and_their_replacements_are_the_same_unit(old, new):
    with pytest.raises(pint.UndefinedUnitError):
        UNITS.parse_units(old)
    assert UNITS.parse_units(new) == UNITS.parse_units(old.replace("2", "^2"))


def test_the_units_of_the_analysis_parse_in_pint(result):
    analysed = [nucleation.ruiz(result), nucleation.fouvry(result), nucleation.peak_dissipation_density(result)]
    analysed += [
        nucleation.dissipation_density(result).to_dataset(),
        nucleation.accumulated_dissipation_density(result).to_dataset(),
    ]
    for dataset in analysed:
        for variable in dataset.variables.values():
            if "units" in variable.attrs:
                UNITS.parse_units(variable.attrs["units"])


def _as_written_by_0_1_0(path):
    """Spell the units of the file at `path` as fretting 0.1.0 did; `path`."""
    old = {new: old for old, new in LEGACY_UNITS.items()}
    with h5py.File(path, "r+") as file:
        for variable in file.values():
            units = variable.attrs.get("units")
            units = units.decode() if isinstance(units, bytes) else units
            if units in old:
                variable.attrs["units"] = old[units]
    return path


def test_a_file_of_0_1_0_loads_with_todays_units_and_goes_on(tmp_path, contact, result):
    path = tmp_path / "old.h5"
    save(result, path)
    _as_written_by_0_1_0(path)
    with h5py.File(path, "r") as file:
        assert file["w"].attrs["units"] == "J/m2" and file["delta_sigma"].attrs["units"] == "m2"
    loaded = load(path)
    for name, variable in result.variables.items():
        assert loaded[name].attrs["units"] == variable.attrs["units"], name
    np.testing.assert_array_equal(loaded.w.values, result.w.values)
    Q, sigma = float(result.state_Q), float(result.state_sigma)
    more = fr.History.piecewise_linear([Q, Q + 10e3], [sigma, sigma], 4)
    go_on = [fr.simulate(contact, more, fr.models.Grid(32), state=fr.final_state(done)) for done in (loaded, result)]
    np.testing.assert_array_equal(go_on[0].q.values, go_on[1].q.values)


def test_parts_of_0_1_0_join_into_a_file_of_todays_units(tmp_path, contact, result):
    history = fr.History.sinusoidal(20e3, 40e6, phase_deg=90, cycles=2, steps_per_cycle=16)
    first = fr.simulate(contact, history[:21], fr.models.Grid(32))
    second = fr.simulate(contact, history[20:], fr.models.Grid(32), state=fr.final_state(first))
    parts = [tmp_path / "part0.h5", tmp_path / "part1.h5"]
    for part, path in zip([first, second], parts, strict=True):
        save(part, path)
        _as_written_by_0_1_0(path)
    joined = tmp_path / "joined.h5"
    save_joined(parts, joined, {})
    with h5py.File(joined, "r") as file:
        assert file["w"].attrs["units"] == "J/m^2" and file["sigma_xx_q_peak"].attrs["units"] == "Pa^2"
    assert load(joined).delta_sigma.attrs["units"] == "m^2"
