"""The speed-against-error benchmark of benchmarks/: its baseline, its ratio at equal error and a quick run."""

import argparse
import csv

import harness
import numpy as np
import pytest
import speed_vs_error

import fretting as fr


@pytest.fixture(scope="module")
def hertz():
    return harness.hertz_contact()


# -- Baseline ----------------------------------------------------------------------------------


@pytest.mark.parametrize("nodes", [24, 48])
def test_baseline_gives_the_engines_increments(hertz, nodes):
    """Same discretisation, independent code: the same slip, traction, zones and energy to rounding."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    histories = [
        harness.baseline_history(hertz, steps_per_segment=3),
        fr.History.sinusoidal(0.5 * fP, 0.8 * fp0, 90.0, cycles=2, steps_per_cycle=16, ramp_steps=4),
    ]
    for history in histories:
        engine = fr.simulate(hertz, history, nodes=nodes)
        baseline = harness.baseline_simulate(hertz, history, nodes)
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
        return row | dict(zip(harness.ERRORS, errors, strict=True))

    rows = [
        row("default", "default", 1.0, 1e-3, 1e-4, 1e-3),
        row("baseline", "N=64", 0.5, 1e-2, 1e-3, 1e-2),
        row("baseline", "N=128", 2.0, 2e-3, 1e-4, 2e-3),
        row("baseline", "N=256", 5.0, 1e-3, 1e-4, 1e-3),
        row("baseline", "N=512", 9.0, 1e-4, 1e-5, 1e-4),
    ]
    ratio = harness.baseline_ratio(rows)
    assert ratio["low"] == ("N=256", 5.0) and ratio["high"] == ("N=256", 5.0)
    rows[3] = row("baseline", "N=256", 5.0, 1e-3, 1e-4, 1.1e-3)  # the default beats it, not the other way round
    ratio = harness.baseline_ratio(rows)
    assert ratio["low"] == ("N=256", 5.0) and ratio["high"] == ("N=512", 9.0)


# -- The whole benchmark, quick ----------------------------------------------------------------


@pytest.mark.slow
def test_quick_benchmark_writes_its_files(tmp_path, monkeypatch):
    monkeypatch.setattr(harness, "long_targets", lambda quick=False: [_short(t) for t in _LONG(quick)])
    monkeypatch.setattr(harness, "LONG_RUNS", ("out_of_phase_long",))  # one child process: a few seconds
    parser = speed_vs_error.add_arguments(argparse.ArgumentParser())
    args = parser.parse_args(["--quick", "--any-threads", "--out", str(tmp_path / "out"), "--long-timeout", "30"])
    assert speed_vs_error.run(args) == 0
    out = tmp_path / "out"
    assert sorted(p.name for p in out.iterdir()) == ["speed_vs_error.csv", "speed_vs_error.md", "speed_vs_error.png"]
    with open(out / "speed_vs_error.csv") as file:
        rows = list(csv.DictReader(file))
    scenes = {row["scene"] for row in rows}
    assert scenes == {s.name for s in harness.scenes(quick=True)}
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
    for error in harness.ERRORS:
        assert float(baseline[error]) == pytest.approx(float(_engine(rows, 64)[error]), rel=1e-6)
    text = (out / "speed_vs_error.md").read_text()
    assert "## Baseline" in text and "## Long runs" in text
    assert "out_of_phase_long" in text


_LONG = harness.long_targets


def _short(target):
    """The long target, shorter still: the smoke test checks the plumbing, not the targets."""
    from dataclasses import replace

    return replace(target, cycles=min(target.cycles, 6))


def _engine(rows, nodes):
    return next(r for r in rows if r["scene"] == "baseline_random" and r["label"] == f"chebyshev N={nodes}")
