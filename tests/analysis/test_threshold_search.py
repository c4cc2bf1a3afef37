"""The threshold search over any quantity of a test (`fretting.analysis.fatigue.threshold_of`), its cache of runs,
and El Haddad's critical length.

Under ``Q`` alone cycling between ``+-Q*`` the edge of a Hertz contact carries a fully reversed uniaxial stress of
amplitude ``S = 2 f p0 sqrt(Q* / (f P))`` (tests/test_threshold.py), so Findley's parameter at that hot spot reaches
its limit at ``S = f_-1``: for a given ``Q*`` and ``P``, at the peak pressure ``p0* = f_-1 / (2 f sqrt(Q* / (f
P)))``, i.e. the radius ``R* = P E_star / (pi p0*^2)`` (``p0 = sqrt(P E_star / (pi R))``).
"""

import math

import pytest

import fretting as fr
from fretting.analysis import fatigue
from fretting.analysis.fatigue import BracketError, Material, read_last_cycle, threshold, threshold_of
from fretting.models import Grid

NU, F, P = 0.3, 0.6, 3.5e5
E_STAR = fr.plane_strain_modulus(210e9, NU)
#: Fatigue limits low enough for the contacts below to reach them at moderate loads.
WEAK = Material(E=210e9, nu=NU, sigma_limit=300e6, tau_limit=200e6, sigma_f=900e6, b=-0.1, critical_distance=20e-6)
GRID = Grid(64)  # Q with sigma: a fixed grid keeps the runs short; the searches below compare like with like


def contact(R=0.05):
    return fr.Contact(fr.Hertz(R), E_STAR, F, P)


def cycles(Q_a, sigma_a=0.0):
    return fr.History.sinusoidal(Q_a, sigma_a, cycles=2, steps_per_cycle=16)


def test_the_radius_at_which_findley_reaches_its_limit_is_the_closed_form():
    """A search over the pad radius, at fixed ``P`` and ``Q*``, finds ``R*`` of the module docstring."""
    Q_star = 0.3 * F * P
    p0_star = WEAK.sigma_limit / (2 * F * math.sqrt(Q_star / (F * P)))
    R_star = P * E_STAR / (math.pi * p0_star**2)
    found = threshold_of(
        lambda R: (contact(R), cycles(Q_star)), (0.2 * R_star, 5 * R_star), "findley", WEAK, at="hot spot", nu=NU
    )
    assert found.amplitude == pytest.approx(R_star, rel=1e-5)
    assert float(found.values.parameter) == pytest.approx(WEAK.findley_limit(), rel=1e-5)


def test_sigma_and_Q_searches_meet_on_the_same_boundary_point():
    """The bulk stress amplitude found at a ``Q_a``, given back, makes the ``Q`` search find that ``Q_a``."""
    fP, fp0 = F * P, F * contact().p0
    Q_a = 0.2 * fP
    sigma = threshold_of(
        lambda s: (contact(), cycles(Q_a, s)), (0.01 * fp0, fp0), "crossland", WEAK, at="hot spot", nu=NU, model=GRID
    )
    back = threshold(
        contact(), lambda q: cycles(q, sigma.amplitude), "crossland", WEAK, at="hot spot", nu=NU, model=GRID
    )
    assert 0 < sigma.amplitude < fp0
    assert back.amplitude == pytest.approx(Q_a, rel=1e-4)


def test_a_shared_cache_runs_no_value_twice_and_changes_no_result():
    """Two lives on one cache: the bracket's ends run once; each result is the one found without the cache."""
    cache = {}
    searches = [
        threshold(contact(), cycles, "crossland", WEAK, life=life, at="hot spot", nu=NU, cache=cache)
        for life in (1e5, 1e6)
    ]
    assert len(cache) == sum(found.runs for found in searches) - 2
    alone = threshold(contact(), cycles, "crossland", WEAK, life=1e6, at="hot spot", nu=NU)
    assert searches[1].amplitude == alone.amplitude
    assert searches[0].amplitude > searches[1].amplitude  # a shorter life needs a larger load


def test_read_last_cycle_reads_what_the_search_read():
    found = threshold(contact(), cycles, "crossland", WEAK, at="point", nu=NU)
    again = read_last_cycle(contact(), cycles(found.amplitude), "crossland", WEAK, at="point", nu=NU)
    assert float(again.parameter) == float(found.values.parameter)
    assert float(fatigue.life(again, WEAK)) == float(fatigue.life(found.values, WEAK))


def test_a_bracket_the_criterion_does_not_cross_says_on_which_side_it_stays():
    with pytest.raises(BracketError, match=r"bracket: the criterion less its limit is -[\d.e+]+ at R = ") as below:
        threshold_of(
            lambda R: (contact(R), cycles(0.05 * F * P)), (0.04, 0.05), "findley", WEAK, at="hot spot", nu=NU, name="R"
        )
    assert below.value.ends[0] < 0 and below.value.ends[1] < 0
    with pytest.raises(ValueError, match=r"bracket: found \(0.05, 0.04\), expected a low end below the high end"):
        threshold_of(lambda R: (contact(R), cycles(0.1)), (0.05, 0.04), "findley", WEAK, at="hot spot")


def test_el_haddad_length_from_the_threshold_and_the_fatigue_limit():
    """``L = (1/pi) (Delta K_th / (2 f_-1))^2``; a given critical distance wins; neither is an error naming both."""
    material = Material(E=74e9, nu=0.33, sigma_limit=124e6, delta_K_th=5e6)
    assert material.critical_length() == pytest.approx((5e6 / 248e6) ** 2 / math.pi, rel=1e-15)
    given = Material(E=74e9, nu=0.33, sigma_limit=124e6, delta_K_th=5e6, critical_distance=3e-5)
    assert given.critical_length() == 3e-5
    with pytest.raises(ValueError, match=r"material: threshold needs critical_distance, found None \(or delta_K_th"):
        threshold(contact(), cycles, "findley", Material(E=74e9, nu=0.33, sigma_limit=124e6, tau_limit=80e6))
    with pytest.raises(ValueError, match="delta_K_th must be > 0"):
        Material(E=74e9, nu=0.33, delta_K_th=-1.0)


def test_the_shipped_materials_load_and_name_their_source():
    shipped = fatigue.materials()
    assert {"al2024_t351", "ti6al4v_sta", "aisi4340_qt650", "steel"} <= set(shipped)
    for name, (path, description) in shipped.items():
        material = Material.from_file(path)
        assert material.E > 0 and description
        assert description.endswith(".")  # the whole first paragraph, not its first line cut mid-sentence
        if name != "steel":
            assert "Source:" in path.read_text(encoding="utf-8")
    assert fatigue.material_path("al2024_t351") == shipped["al2024_t351"][0]
    with pytest.raises(FileNotFoundError, match="nor a shipped material: expected a material file or one of: "):
        fatigue.material_path("unobtainium")
