"""The speed-against-error benchmark: its references, its error metrics, its baseline and a quick run."""

import argparse
import csv
import math

import numpy as np
import pytest
from scipy import integrate

import fretting as fr
from fretting import bench
from fretting.physics import closed_forms as cf


@pytest.fixture(scope="module")
def hertz():
    return bench.hertz_contact()


# -- Closed forms ------------------------------------------------------------------------------


@pytest.mark.parametrize("psi", [0.01, 0.2, 0.6, 0.95])
def test_compliance_is_the_mean_slip_of_cattaneo_mindlin(hertz, psi):
    """``delta_Q = (1/pi) int_0^pi s(a cos th) dth``, by quadrature of the slip of closed_forms."""
    Q = psi * hertz.f * hertz.P
    kink = math.acos(float(cf.stick_half_width(hertz, Q)) / hertz.a)
    slip = lambda th: float(cf.cattaneo_mindlin_slip(hertz, Q, hertz.a * math.cos(th)))  # noqa: E731
    mean = integrate.quad(slip, 0, math.pi, points=[kink, math.pi - kink], epsabs=0, epsrel=1e-13, limit=200)[0]
    assert bench.mindlin_compliance(hertz, Q) == pytest.approx(mean / math.pi, rel=1e-12)
    assert bench.mindlin_compliance(hertz, -Q) == -bench.mindlin_compliance(hertz, Q)


@pytest.mark.parametrize("psi", [0.001, 0.1, 0.2499, 0.25, 0.7, 0.99])
def test_cycle_energy_is_four_monotonic_dissipations(hertz, psi):
    """Mindlin-Deresiewicz ``W = 4 Q* dv(Q*) - 8 int dv``, the loop area, equals the dissipation of the
    two Masing branches, ``4 int f p s_CM(Q*) dx``: two derivations, one number."""
    Q = psi * hertz.f * hertz.P
    W = bench.cycle_energy(hertz, Q)
    assert W == pytest.approx(4 * bench.monotonic_dissipation(hertz, Q), rel=1e-11)
    assert W == pytest.approx(4 * bench._slip_work(hertz, Q, 0.0), rel=1e-9)


@pytest.mark.parametrize("psi", [1e-4, 1e-2])
def test_small_loops_dissipate_as_the_cube_of_the_amplitude(hertz, psi):
    """``W = (pi (f p0 a)^2 / E_star) psi^3 / 6 (1 + psi / 2 + ...)``."""
    scale = math.pi * (hertz.f * hertz.p0 * hertz.a) ** 2 / hertz.E_star
    W = bench.cycle_energy(hertz, psi * hertz.f * hertz.P)
    assert W == pytest.approx(scale * psi**3 / 6 * (1 + psi / 2), rel=psi**2)


def test_masing_walk_keeps_and_erases_turning_points():
    """0 -> 6 -> -4 -> 2 -> -4 (loop closed) -> -6 (past -Q_1: virgin again) -> 0."""
    Q = [0, 3, 6, 1, -4, 2, -1, -4, -6, 0]
    stacks, segments = bench.masing_walk(Q)
    assert stacks == [(), (), (), (6,), (6,), (6, -4), (6, -4, 2), (6,), (), (-6,)]
    assert segments[1] == [(0.0, 1, 0, 3)]
    assert segments[4] == [(6, 2, 1, -4)]
    assert segments[7] == [(2, 2, -1, -4), (6, 2, -4, -4)]  # reaches -4: the minor loop closes there
    assert segments[8] == [(6, 2, -4, -6), (0.0, 1, -6, -6)]


def test_masing_reference_of_constant_cycles(hertz):
    """Q cycling between +-Q*: stick zones of Cattaneo-Mindlin and Mindlin-Deresiewicz, energies per cycle."""
    fP = hertz.f * hertz.P
    history = fr.History.piecewise_linear(np.array([0, 0.6, -0.6, 0.6, -0.6]) * fP, None, 4).as_cycle()
    reference = bench.masing_reference(hertz, history)
    a = hertz.a
    np.testing.assert_allclose(reference.zones[4], [[-a * math.sqrt(0.4), a * math.sqrt(0.4)]], rtol=1e-14)
    c = a * math.sqrt(1 - 0.3 / 2)  # step 5: unloaded by 0.3 fP from the peak
    np.testing.assert_allclose(reference.zones[5], [[-c, c]], rtol=1e-14)
    x = np.linspace(-a, a, 9)
    np.testing.assert_allclose(
        reference.tractions(5, x), cf.mindlin_deresiewicz_traction(hertz, 0.6 * fP, 0.3 * fP, x), atol=1e-9 * hertz.p0
    )
    W = bench.cycle_energy(hertz, 0.6 * fP)
    D = bench.monotonic_dissipation
    first = D(hertz, 0.6 * fP) + 2 * W / 4 + 2 * W / 4 + 2 * W / 4  # virgin rise, then three half loops
    assert reference.cycle_energy == pytest.approx([first], rel=1e-12)


def test_in_phase_reference_matches_nowell_hills(hertz):
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    history = fr.History.piecewise_linear([0, 0.6 * fP], [0, 0.6 * fp0], 3).as_cycle()
    reference = bench.masing_reference(hertz, history)
    x = np.linspace(-hertz.a, hertz.a, 11)
    np.testing.assert_allclose(reference.tractions(3, x), cf.nowell_hills_traction(hertz, 0.6 * fP, 0.6 * fp0, x))
    e, b = cf.nowell_hills_offset(hertz, 0.6 * fp0), cf.stick_half_width(hertz, 0.6 * fP)
    np.testing.assert_allclose(reference.zones[3], [[e - b, e + b]])
    with pytest.raises(ValueError, match="proportional"):
        bench.masing_reference(hertz, fr.History.piecewise_linear([0, fP / 2, 0], [0, 0, fp0], 2).as_cycle())


# -- Error metrics -----------------------------------------------------------------------------


def test_zone_distance():
    zones = [[-0.5, 0.2], [0.4, 0.6]]
    assert bench.zone_distance(zones, [[0.41, 0.6], [-0.5, 0.17]]) == pytest.approx(0.03)
    assert bench.zone_distance([[-0.5, 0.2]], zones) == pytest.approx(0.1)  # [0.4, 0.6] closes up
    assert bench.zone_distance([[-0.5, 0.6]], zones) == pytest.approx(0.1)  # the slip zone (0.2, 0.4) closes up
    assert bench.zone_distance([[-0.5, 0.25]], zones) == pytest.approx(0.1)
    nucleated = [[-0.405, 0.547], [0.549, 0.918]]  # a slip zone one node wide appears
    assert bench.zone_distance([[-0.405, 0.918]], nucleated) == pytest.approx(0.001)
    assert bench.zone_distance(np.zeros((0, 2)), zones) == pytest.approx(0.35)
    assert bench.zone_distance(np.zeros((0, 2)), np.zeros((0, 2))) == 0


def test_energy_error():
    assert bench.energy_error([1.0, 2.004], [1.0, 2.0]) == pytest.approx(2e-3)
    with pytest.raises(ValueError):
        bench.energy_error([1.0], [0.0])


def test_traction_error_leaves_out_the_bands():
    x = np.linspace(-1, 1, 201)
    q_ref = np.sqrt(1 - x**2)
    q = q_ref.copy()
    q[np.isclose(x, 0.3)] += 0.5  # next to a kink: left out
    q[np.isclose(x, -0.6)] += 0.1
    assert bench.traction_error(x, q, q_ref, [0.31, -1, 1], 0.02) == pytest.approx(0.1)
    assert bench.traction_error(x, q, q_ref, [0.31, -0.6], 0.02) == pytest.approx(0.0)
    assert bench.traction_error(x, q, q_ref, [], 0.02) == pytest.approx(0.5)
    q[np.isclose(x, 0.3)] = np.nan
    assert bench.traction_error(x, q, q_ref, [], 0.02) == pytest.approx(0.1)


def test_memory_kinks_mark_where_old_slip_meets_newer():
    """Nodes 0-5; step 1 slips 0-1 and 4-5, step 2 slips 5 only, step 3 nothing."""
    x = np.arange(6.0)
    stick = np.array(
        [
            [1, 1, 1, 1, 1, 1],
            [0, 0, 1, 1, 0, 0],
            [1, 1, 1, 1, 1, 0],
            [1, 1, 1, 1, 1, 1],
        ],
        dtype=bool,
    )
    kinks = bench.memory_kinks(x, stick)
    np.testing.assert_array_equal(kinks[0], [])
    np.testing.assert_array_equal(kinks[1], [1.5, 3.5])  # slipped at 1 against never
    np.testing.assert_array_equal(kinks[2], [1.5, 3.5])  # 4 stuck one step after 5: no kink between them
    np.testing.assert_array_equal(kinks[3], [1.5, 3.5])


def test_a_reference_scores_zero_against_itself(hertz):
    history = bench.baseline_history(hertz, steps_per_segment=2)
    result = fr.simulate(hertz, history, nodes=32)
    errors = bench.score(result, bench.run_reference(result, "itself"))
    assert errors == {"stick_ends_a": 0.0, "energy_rel": 0.0, "traction_fp0": 0.0}


# -- Baseline ----------------------------------------------------------------------------------


@pytest.mark.parametrize("nodes", [24, 48])
def test_baseline_gives_the_engines_increments(hertz, nodes):
    """Same discretisation, independent code: the same slip, traction, zones and energy to rounding."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    histories = [
        bench.baseline_history(hertz, steps_per_segment=3),
        fr.History.sinusoidal(0.5 * fP, 0.8 * fp0, 90.0, cycles=2, steps_per_cycle=16, ramp_steps=4),
    ]
    for history in histories:
        engine = fr.simulate(hertz, history, nodes=nodes)
        baseline = bench.baseline_simulate(hertz, history, nodes)
        np.testing.assert_allclose(baseline.x, engine.x, rtol=0, atol=1e-15 * hertz.a)
        slip = np.abs(engine.slip.values).max()
        np.testing.assert_allclose(baseline.slip, engine.slip, rtol=0, atol=1e-10 * slip)
        np.testing.assert_allclose(baseline.q, engine.q, rtol=0, atol=1e-10 * fp0)
        for name in ("stick_start", "stick_end"):
            np.testing.assert_allclose(baseline[name], engine[name], rtol=0, atol=1e-10 * hertz.a)
        np.testing.assert_allclose(baseline.dissipation, engine.dissipation, rtol=1e-10, atol=0)
        np.testing.assert_allclose(baseline.cycle_dissipation, engine.cycle_dissipation, rtol=1e-10)


def test_baseline_ratio_picks_the_baselines_at_equal_error():
    def row(role, label, seconds, *errors):
        row = {"role": role, "scene": "s", "label": label, "total_s": seconds, "ms_per_step": seconds}
        return row | dict(zip(bench.ERRORS, errors, strict=True))

    rows = [
        row("default", "default", 1.0, 1e-3, 1e-4, 1e-3),
        row("baseline", "N=64", 0.5, 1e-2, 1e-3, 1e-2),
        row("baseline", "N=128", 2.0, 2e-3, 1e-4, 2e-3),
        row("baseline", "N=256", 5.0, 1e-3, 1e-4, 1e-3),
        row("baseline", "N=512", 9.0, 1e-4, 1e-5, 1e-4),
    ]
    ratio = bench.baseline_ratio(rows)
    assert ratio["low"] == ("N=256", 5.0) and ratio["high"] == ("N=256", 5.0)
    rows[3] = row("baseline", "N=256", 5.0, 1e-3, 1e-4, 1.1e-3)  # the default beats it, not the other way round
    ratio = bench.baseline_ratio(rows)
    assert ratio["low"] == ("N=256", 5.0) and ratio["high"] == ("N=512", 9.0)


# -- The whole benchmark, quick ----------------------------------------------------------------


def test_quick_benchmark_writes_its_files(tmp_path, monkeypatch):
    monkeypatch.setattr(bench, "long_targets", lambda quick=False: [_short(t) for t in _LONG(quick)])
    monkeypatch.setattr(bench, "LONG_RUNS", ("out_of_phase_long",))  # one child process: a few seconds
    parser = bench.add_arguments(argparse.ArgumentParser())
    args = parser.parse_args(["--quick", "--any-threads", "--out", str(tmp_path / "out"), "--long-timeout", "30"])
    assert bench.run(args) == 0
    out = tmp_path / "out"
    assert sorted(p.name for p in out.iterdir()) == ["speed_vs_error.csv", "speed_vs_error.md", "speed_vs_error.png"]
    with open(out / "speed_vs_error.csv") as file:
        rows = list(csv.DictReader(file))
    scenes = {row["scene"] for row in rows}
    assert scenes == {s.name for s in bench.scenes(quick=True)}
    roles = {row["role"] for row in rows}
    assert roles == {"default", "engine", "baseline", "reference"}
    for row in rows:
        assert float(row["ms_per_step"]) > 0 and float(row["peak_MB"]) > 0
    # The closed-form references hold the default's errors where the engine's tests do.
    for row in rows:
        if row["role"] == "default" and row["scene"] in ("hertz_Q", "hertz_in_phase"):
            assert float(row["stick_ends_a"]) < 2e-3 and float(row["energy_rel"]) < 1e-3
            assert float(row["traction_fp0"]) < 2e-3
    # Same discretisation, same errors.
    baseline = next(row for row in rows if row["label"] == "baseline N=64")
    for error in bench.ERRORS:
        assert float(baseline[error]) == pytest.approx(float(_engine(rows, 64)[error]), rel=1e-6)
    text = (out / "speed_vs_error.md").read_text()
    assert "## Baseline" in text and "## Long runs" in text
    assert "out_of_phase_long" in text


_LONG = bench.long_targets


def _short(target):
    """The long target, shorter still: the smoke test checks the plumbing, not the targets."""
    from dataclasses import replace

    return replace(target, cycles=min(target.cycles, 6))


def _engine(rows, nodes):
    return next(r for r in rows if r["scene"] == "baseline_random" and r["label"] == f"chebyshev N={nodes}")
