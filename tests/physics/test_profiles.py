"""Normal contact of each profile against its closed form or an independent solution."""

import re

import numpy as np
import pytest
from scipy import integrate, interpolate

import fretting as fr
from fretting.physics.profiles import profile_class, recorded_profile

E_STAR, P = 115e9, 3e5


def test_hertz_closed_form():
    contact = fr.Contact(fr.Hertz(0.05), E_STAR, 0.5, P)
    assert contact.a == pytest.approx(np.sqrt(4 * P * 0.05 / (np.pi * E_STAR)), rel=1e-15)
    assert contact.p0 == pytest.approx(np.sqrt(P * E_STAR / (np.pi * 0.05)), rel=1e-14)
    x = np.linspace(-1.5, 1.5, 31) * contact.a
    p = contact.pressure(x)
    assert np.all(p[np.abs(x) >= contact.a] == 0)
    # Normal equilibrium, eq (2).
    load, _ = integrate.quad(contact.pressure, -contact.a, contact.a, epsabs=0, epsrel=1e-13)
    assert load == pytest.approx(P, rel=1e-12)


def test_rounded_flat_load_round_trip():
    """a solves P = E_star a^2 (pi - 2 phi0 - sin 2 phi0) / (4R) to 1e-10 relative."""
    profile = fr.RoundedFlat(b=1e-3, R=0.02)
    contact = fr.Contact(profile, E_STAR, 0.5, P)
    phi0 = np.arcsin(profile.b / contact.a)
    load = E_STAR * contact.a**2 * (np.pi - 2 * phi0 - np.sin(2 * phi0)) / (4 * profile.R)
    assert load == pytest.approx(P, rel=1e-12)


@pytest.mark.parametrize("P", [1e3, 3e5, 3e7])
def test_rounded_flat_against_general_gap_solver(P):
    """The closed form of Ciavarella, Hills & Monno against the Chebyshev solution of eq (1)."""
    b, R = 1e-3, 0.02
    gap = fr.Gap(
        lambda x: np.maximum(np.abs(x) - b, 0) ** 2 / (2 * R), lambda x: np.sign(x) * np.maximum(np.abs(x) - b, 0) / R
    )
    closed = fr.Contact(fr.RoundedFlat(b, R), E_STAR, 0.5, P)
    general = fr.Contact(gap, E_STAR, 0.5, P)
    assert general.a == pytest.approx(closed.a, rel=1e-6)
    x = np.linspace(-0.99, 0.99, 199) * closed.a
    np.testing.assert_allclose(general.pressure(x), closed.pressure(x), rtol=0, atol=2e-3 * closed.p0)
    assert general.p0 == pytest.approx(closed.p0, rel=2e-3)


def test_gap_solver_reproduces_shifted_hertz():
    """An off-centre cylinder: the contact centres on the minimum of the gap."""
    R, x0 = 0.05, 3e-4
    gap = fr.Gap(lambda x: (x - x0) ** 2 / (2 * R))
    hertz = fr.Contact(fr.Hertz(R), E_STAR, 0.5, P)
    shifted = fr.Contact(gap, E_STAR, 0.5, P)
    assert shifted.a == pytest.approx(hertz.a, rel=1e-10)
    assert shifted.centre == pytest.approx(x0, rel=1e-10)
    x = np.linspace(-0.99, 0.99, 41) * hertz.a
    np.testing.assert_allclose(shifted.pressure(x + x0), hertz.pressure(x), rtol=0, atol=1e-9 * hertz.p0)


def test_gap_from_table_matches_hertz():
    R = 0.05
    x = np.linspace(-2e-3, 2e-3, 401)
    contact = fr.Contact(fr.Gap.from_table(x, x**2 / (2 * R)), E_STAR, 0.5, P)
    assert contact.a == pytest.approx(np.sqrt(4 * P * R / (np.pi * E_STAR)), rel=1e-10)


def test_flat_punch_pressure():
    contact = fr.Contact(fr.FlatPunch(2e-3), E_STAR, 0.5, P)
    assert contact.a == 2e-3
    assert contact.p0 == pytest.approx(P / (np.pi * 2e-3))
    assert contact.pressure(np.array([0.0]))[0] == pytest.approx(contact.p0)


@pytest.mark.parametrize(
    ("factory", "message"), [(lambda: fr.Hertz(-1), "R must be > 0"), (lambda: fr.RoundedFlat(0, 1), "b must be > 0")]
)
def test_bad_profile(factory, message):
    with pytest.raises(ValueError, match=message):
        factory()


@pytest.mark.parametrize("profile", [fr.Hertz(0.05), fr.RoundedFlat(1e-3, 0.02)])
@pytest.mark.parametrize("P", [1e-1, 3e5, 1e7])
def test_load_slope_is_the_derivative_of_the_load(profile, P):
    """``dP/da`` against central differences of `half_width` (relative step 1e-4), to 1e-6; for
    the rounded flat the smallest load has its contact 7e-9 m beyond the flat (measured: 1e-8)."""
    E_star, h = 115e9, 1e-4
    a = profile.half_width(P, E_star)[0]
    lower, upper = (profile.half_width(P * (1 + side * h), E_star)[0] for side in (-1, 1))
    assert profile.load_slope(a, E_star) == pytest.approx(2 * h * P / (upper - lower), rel=1e-6)


def test_x_minus_sin_keeps_its_relative_precision():
    """``x - sin x`` of the rounded flat's load, against its Taylor series summed in 60 decimal
    digits: within 1e-15 below x = 0.5 (the series; measured 3.3e-16) and 5e-15 above (the
    difference; measured 1.7e-15); computed directly, ``x - sin x`` is off by 3e-8 at x = 1e-4."""
    from decimal import Decimal, localcontext

    from fretting.physics.profiles import _x_minus_sin

    def reference(x):
        with localcontext() as context:
            context.prec = 60
            x = Decimal(float(x))
            term, total, n = x**3 / 6, Decimal(0), 3
            while abs(term) >= Decimal(10) ** -55 * abs(total):
                total, term, n = total + term, -term * x * x / ((n + 1) * (n + 2)), n + 2
            return float(total)

    x = np.concatenate([np.geomspace(1e-8, 0.5, 200, endpoint=False), np.linspace(0.5, 3.0, 200)])
    error = np.abs(_x_minus_sin(x) / np.array([reference(v) for v in x]) - 1)
    assert error[x < 0.5].max() < 1e-15 and error[x >= 0.5].max() < 5e-15


@pytest.mark.parametrize(
    ("E", "nu", "words"),
    [
        (np.nan, 0.3, "E must be finite"),
        (-1.0, 0.3, "E must be > 0"),
        (210e9, 1.0, "nu must be in (-1, 0.5]"),
        (210e9, -1.0, "nu must be in (-1, 0.5]"),
        (210e9, np.nan, "nu must be finite"),
    ],
)
def test_plane_strain_modulus_refuses_what_no_material_has(E, nu, words):
    with pytest.raises(ValueError, match=re.escape(words)):
        fr.plane_strain_modulus(E, nu)


def test_plane_strain_modulus_of_the_incompressible_limit():
    assert fr.plane_strain_modulus(3e6, 0.5) == 3e6 / 1.5


def test_a_tabulated_gap_says_its_table():
    """repr of a table reads back to the same profile, every value to the last bit."""
    x = np.linspace(-1e-3, 1e-3, 21) + 1e-7 / 3
    profile = fr.Gap.from_table(x, x**2 / 0.1, breakpoints=[1e-4 / 3])
    again = eval(repr(profile), {"Gap": fr.Gap})  # noqa: S307 - our own repr
    np.testing.assert_array_equal(again.table[0], x)
    np.testing.assert_array_equal(again.table[1], x**2 / 0.1)
    assert again.breakpoints == profile.breakpoints and "object at" not in repr(profile)
    result = fr.simulate(fr.Contact(profile, E_STAR, 0.5, 1e5), fr.History.piecewise_linear([0.0, 1e4], None, 1))
    assert result.attrs["profile"] == repr(profile)


def test_a_hollow_pad_is_refused_where_its_pressure_is_negative():
    """Hertz R = 50 mm with a 3 um central hollow, as functions: the pressure is negative near x = 0."""
    h0 = lambda x: x**2 / 0.1 + 3e-6 * np.exp(-((x / 1.5e-4) ** 2))  # noqa: E731
    slope = lambda x: x / 0.05 - 6e-6 * x / 1.5e-4**2 * np.exp(-((x / 1.5e-4) ** 2))  # noqa: E731
    with pytest.raises(ValueError, match=r"^the pressure is negative at x = -?\d.*e-05 m \(-.* Pa\) in the contact"):
        fr.Contact(fr.Gap(h0, slope), fr.plane_strain_modulus(74e9, 0.33), 0.75, 9.3e4)


@pytest.mark.parametrize("specimen", [0, 3, True, "2"])
def test_contact_specimen_is_body_1_or_2(specimen):
    with pytest.raises(ValueError, match="specimen must be 1"):
        fr.Contact(fr.Hertz(0.05), E_STAR, 0.5, P, specimen=specimen)


# What a profile must give, and its facts


def _user_profile(*omitted, **flags):
    """A user's Hertz-like profile of R = 50 mm lacking the methods `omitted`, with the class attributes `flags`."""
    R = 0.05
    methods = {
        "half_width": lambda self, P, E_star: (np.sqrt(4 * P * R / (np.pi * E_star)), 0.0),
        "pressure": lambda self, t, a, centre, P, E_star: 2 * P / (np.pi * a) * np.sqrt(1 - t**2),
        "load": lambda self, a, E_star: np.pi * E_star * np.square(a) / (4 * R),
        "load_slope": lambda self, a, E_star: np.pi * E_star * np.asarray(a) / (2 * R),
    }
    body = {name: method for name, method in methods.items() if name not in omitted}
    return type("Cylinder", (fr.Profile,), {"SYMMETRIC": True} | body | flags)


def test_a_symmetric_profile_without_its_load_slope_is_refused_when_constructed():
    """The user's profile fails at once, in one line naming what it lacks, what it returns and its units, not
    deep in the exact model with an AttributeError."""
    with pytest.raises(TypeError) as refused:
        _user_profile("load_slope")()
    assert str(refused.value) == (
        "Cylinder lacks load_slope(a, E_star) -> dP/da [N/m^2], which a symmetric profile whose contact grows "
        "with the load (SYMMETRIC and VANISHING_EDGES) must give"
    )
    with pytest.raises(TypeError, match=r"^Cylinder lacks pressure\(t, a, centre, P, E_star\) -> p \[Pa\], which"):
        _user_profile("pressure")()


def test_what_a_profile_must_give_follows_its_kind():
    """Given whole, the user's profile runs on the exact model as Hertz does (by quadrature of its gap, not
    the closed form: to 1e-9 f p0); an asymmetric one, or a symmetric one whose contact keeps its width (as
    the flat punch's), needs no load; the base defines none, so that a profile has `load` only where it
    gives it."""
    contact = fr.Contact(_user_profile()(), E_STAR, 0.5, P)
    history = fr.History.piecewise_linear([0.0, 0.5 * contact.f * P, 0.0], None, 4)
    hertz = fr.simulate(fr.Contact(fr.Hertz(0.05), E_STAR, 0.5, P), history, fr.models.Exact(32))
    on_user = fr.simulate(contact, history, fr.models.Exact(32))
    np.testing.assert_allclose(on_user.q, hertz.q, rtol=0, atol=1e-9 * contact.f * contact.p0)
    _user_profile("load", "load_slope", SYMMETRIC=False)()
    _user_profile("load", "load_slope", VANISHING_EDGES=False)()
    assert not hasattr(fr.FlatPunch(1e-3), "load") and not hasattr(fr.Profile, "load_slope")


GAP_X = np.linspace(-1e-3, 1e-3, 21) + 1e-7 / 3

PROFILES = [
    fr.Hertz(0.05),
    fr.FlatPunch(1e-3),
    fr.RoundedFlat(b=2e-3, R=0.05),
    fr.Gap.from_table(GAP_X, GAP_X**2 / 0.1, breakpoints=[1e-4 / 3]),
    fr.Gap.from_table(GAP_X, GAP_X**2 / 0.1),
]


@pytest.mark.parametrize("profile", PROFILES, ids=repr)
def test_facts_rebuild_the_profile(profile):
    """The class's name and the parameters rebuild the same profile, every value to the last bit; a result
    written before they were recorded states the same facts in its repr."""
    name, parameters = recorded_profile(profile.attributes())
    assert name == type(profile).__name__
    again = profile_class(name).from_parameters(parameters)
    assert repr(again) == repr(profile)
    before = recorded_profile({"profile": repr(profile)})
    assert before[0] == name and before[1].keys() == parameters.keys()
    for key, value in before[1].items():
        np.testing.assert_array_equal(value, parameters[key])


def test_a_gap_of_functions_records_what_it_can():
    profile = fr.Gap(lambda x: x**2 / 0.1, breakpoints=[1e-4])
    name, parameters = recorded_profile(profile.attributes())
    assert name == "Gap" and parameters.keys() == {"breakpoints"}
    with pytest.raises(ValueError, match="found only breakpoints: a Gap of functions h0.x. records none"):
        fr.Gap.from_parameters(parameters)
    assert recorded_profile({"profile": repr(profile)}) == ("Gap", {})
    assert recorded_profile({"profile": "<mine.Pad object at 0x7f>"}) == (None, {})


def test_a_class_is_found_by_its_name_only_where_it_is_one():
    assert profile_class("RoundedFlat") is fr.RoundedFlat and profile_class("Pad") is None
    twins = _user_profile(), _user_profile()  # two classes of one name: neither is the one meant
    assert profile_class("Cylinder") is None and twins[0] is not twins[1]


def test_contact_nu_is_a_poisson_ratio_or_unknown():
    assert fr.Contact(fr.Hertz(0.05), E_STAR, 0.5, P).nu is None
    contact = fr.Contact(fr.Hertz(0.05), E_STAR, 0.5, P, nu=0.3)
    assert contact.nu == 0.3 and repr(contact).endswith("specimen=2, nu=0.3)")
    with pytest.raises(ValueError, match=re.escape("nu must be in (-1, 0.5]")):
        fr.Contact(fr.Hertz(0.05), E_STAR, 0.5, P, nu=0.7)


def test_contacts_and_profiles_take_quantities_with_units():
    """``fr.Hertz(R=50 * ureg.mm)`` (issue 37): a pint quantity is converted to the SI unit of its
    parameter, bit for bit the contact of the SI numbers; a quantity of another dimension is refused."""
    import pint  # of the test extra: the package itself does not need it

    ureg = pint.UnitRegistry()
    given = fr.Contact(fr.Hertz(R=50 * ureg.mm), E_star=115 * ureg.GPa, f=0.6, P=100 * ureg.N / ureg.mm)
    si = fr.Contact(fr.Hertz(R=0.05), E_star=115e9, f=0.6, P=1e5)
    assert (given.a, given.p0, given.P, given.E_star) == (si.a, si.p0, si.P, si.E_star)
    flat = fr.RoundedFlat(b=1 * ureg.mm, R=20 * ureg.mm)
    assert (flat.b, flat.R) == (1e-3, 0.02)
    with pytest.raises(
        ValueError, match=r"R must be a number in m \(SI\) or a quantity in units of m, found 5 megapascal"
    ):
        fr.Hertz(R=5 * ureg.MPa)
    with pytest.raises(ValueError, match="f must be a dimensionless number"):
        fr.Contact(fr.Hertz(0.05), 115e9, 0.6 * ureg.m, 1e5)


# Cusps and curvature jumps: the pressure next to them, and a table's breakpoints


def power_law(n, A=2.0):
    """The gap ``A |x|^n`` [m] with its slope, a cusp at x = 0 for 1 < n < 2 (a breakpoint)."""
    return fr.Gap(lambda x: A * np.abs(x) ** n, lambda x: n * A * np.abs(x) ** (n - 1) * np.sign(x), [0.0])


def power_law_closed_form(n, A=2.0):
    """``a`` [m] and ``p(0)`` [Pa] of the contact of ``A |x|^n`` under `P`: with ``B_k = B(k/2, 1/2)``,
    ``P = E_star n A a^n B_(n+1) / 2`` (eq 2 with ``P = pi a E_star b_1 / 4``) and ``p(0) = P B_(n-1) /
    (pi a B_(n+1))`` (eq 1 bounded at both ends, at the centre); n = 2 is Hertz's."""
    from scipy import special

    B_plus, B_minus = special.beta((n + 1) / 2, 0.5), special.beta((n - 1) / 2, 0.5)
    a = (2 * P / (E_STAR * n * A * B_plus)) ** (1 / n)
    return a, P * B_minus / (np.pi * a * B_plus)


def pressure_by_quad(slope, a, centre, t):
    """``(E_star / 2 pi) sin(theta) int_0^pi (h0'(c + a cos u) - h0'(c + a t)) / (cos u - t) du`` by scipy's
    adaptive quadrature, split at theta and at x = 0: an independent computation of eq (1)."""
    theta, g = np.arccos(t), float(slope(centre + a * t))
    points = sorted({theta, float(np.arccos(np.clip(-centre / a, -1, 1)))})
    integrand = lambda u: (float(slope(centre + a * np.cos(u))) - g) / (np.cos(u) - t)  # noqa: E731
    part = integrate.quad(integrand, 0, np.pi, points=points, epsabs=0, epsrel=1e-12, limit=400)[0]
    return E_STAR / (2 * np.pi) * np.sin(theta) * part


def test_the_power_law_closed_form_is_hertz_at_n_2_and_the_quadrature_of_eq_1():
    a, p_centre = power_law_closed_form(2.0, A=1 / (2 * 0.05))
    hertz = fr.Contact(fr.Hertz(0.05), E_STAR, 0.5, P)
    assert a == pytest.approx(hertz.a, rel=1e-14) and p_centre == pytest.approx(hertz.p0, rel=1e-14)
    a, p_centre = power_law_closed_form(1.5)
    slope = power_law(1.5)._slope
    assert pressure_by_quad(slope, a, 0.0, 0.0) == pytest.approx(p_centre, rel=1e-10)  # measured 5e-15


@pytest.mark.parametrize(("n", "rtol"), [(1.5, 1e-8), (1.8, 1e-8), (1.2, 1e-3)])
def test_the_pressure_at_a_cusp_is_the_closed_form(n, rtol):
    """``|x|^n`` with its cusp as a breakpoint: ``a``, the centre pressure and ``p0`` (the peak, at the cusp)
    against the closed form within `rtol` (measured 6e-9 at n = 1.5, 1e-14 at 1.8, 3.9e-4 at 1.2, whose
    integrand ``|u|^(n - 2)`` is the least smooth), and the pressure elsewhere against scipy's quadrature of
    eq (1) within 1e-7 p0 (measured 2.6e-8 at n = 1.2, 3.5e-10 at 1.8, 5e-16 at 1.5). Without the breakpoint
    the sine series would be 1.28 % low at the cusp (n = 1.5): the contact is refused, naming it."""
    a, p_centre = power_law_closed_form(n)
    contact = fr.Contact(power_law(n), E_STAR, 0.5, P)
    assert contact.a == pytest.approx(a, rel=1e-7) and abs(contact.centre) < 1e-12 * a  # b_0, b_1 by the DCT
    assert contact.pressure(0.0) == pytest.approx(p_centre, rel=rtol)
    assert contact.p0 == pytest.approx(p_centre, rel=rtol)
    t = np.array([-0.9, -0.3, 1e-4, 0.05, 0.6])
    expected = [pressure_by_quad(contact.profile._slope, contact.a, contact.centre, u) for u in t]
    np.testing.assert_allclose(contact.pressure(contact.a * t), expected, rtol=0, atol=1e-7 * p_centre)
    undeclared = fr.Gap(contact.profile.h0, contact.profile._slope)
    with pytest.raises(ValueError, match=r"unbounded at x = 0 m .*declare it, Gap\(h0, slope, breakpoints=\[0\]\)"):
        fr.Contact(undeclared, E_STAR, 0.5, P)


def test_an_undeclared_cusp_off_the_centre_is_found_and_smooth_gaps_pass():
    """A weak cusp at 10 um on a Hertz gap, and a cusp by central differences (no slope given), are refused
    naming their position; Hertz's gap with its slope or by central differences, a quartic, and the shipped
    asymmetric pad table (curvature jumps, declared by the table) pass, and the curvature of each stays bounded."""
    R, where = 0.05, 1e-5
    weak = fr.Gap(
        lambda x: x**2 / (2 * R) + 1e-3 * np.abs(x - where) ** 1.5,
        lambda x: x / R + 1.5e-3 * np.sqrt(np.abs(x - where)) * np.sign(x - where),
    )
    for gap in (weak, fr.Gap(lambda x: 2 * np.abs(x - 3 * where) ** 1.5)):
        with pytest.raises(ValueError, match=r"unbounded at x = ([13])e-05 m .*breakpoints=\[\1e-05\]"):
            fr.Contact(gap, E_STAR, 0.5, P)
    declared = fr.Gap(weak.h0, weak._slope, [where])
    assert fr.Contact(declared, E_STAR, 0.5, P).a > 0
    from fretting.loading.examples import EXAMPLES

    pad = np.loadtxt(EXAMPLES / "asymmetric_pad_gap.csv", delimiter=",", skiprows=3)
    smooth = (
        fr.Gap(lambda x: x**2 / (2 * R), lambda x: x / R),
        fr.Gap(lambda x: x**2 / (2 * R)),
        fr.Gap(lambda x: 1e6 * x**4 + x**2 / 10, lambda x: 4e6 * x**3 + x / 5),
        fr.Gap.from_table(*pad.T),
    )
    for gap in smooth:
        contact = fr.Contact(gap, E_STAR, 0.5, P)
        assert gap.undeclared_cusp(contact.a, contact.centre) is None


def asymmetric_flat_table(rows=121, span=3e-3, breakpoints=None, seed=None):
    """The asymmetric flat of `harness.asymmetric_flat` (corners at +-0.5 mm of radii 10 and 40 mm) tabulated
    at `rows` positions over +-`span`, equally spaced or, with a `seed`, at random."""
    from harness import asymmetric_flat

    h0, slope, corners = asymmetric_flat()
    x = np.linspace(-span, span, rows)
    if seed is not None:
        x = np.sort(np.random.default_rng(seed).uniform(-span, span, rows))
    return fr.Gap.from_table(x, h0(x), breakpoints), fr.Gap(h0, slope, corners), corners


@pytest.mark.parametrize(("rows", "seed"), [(121, None), (33, None), (200, 3)])
def test_a_table_shows_its_curvature_jumps(rows, seed):
    """The corners of the flat, found from the rows alone (tables of parabolas: to rounding), and none in
    tables of smooth gaps; the asymmetric pad example's jump at a row, x = 0, from its 7-digit rows."""
    table, _, corners = asymmetric_flat_table(rows, seed=seed)
    np.testing.assert_allclose(table.breakpoints, corners, rtol=0, atol=1e-12)
    x = np.linspace(-1e-3, 1e-3, 41)
    for h0 in (x**2 / 0.1, 1e6 * x**4, 1e-3 * np.cosh(1e3 * x), 1e-3 * (np.sqrt(1 + (1e3 * x) ** 2) - 1)):
        assert fr.Gap.from_table(x, h0).breakpoints == ()
    from fretting.loading.examples import EXAMPLES

    pad = np.loadtxt(EXAMPLES / "asymmetric_pad_gap.csv", delimiter=",", skiprows=3)
    assert fr.Gap.from_table(*pad.T).breakpoints == (0.0,)


@pytest.mark.parametrize("declared", [None, "corners"])
def test_a_table_with_curvature_jumps_gives_the_traction_of_its_profile(declared):
    """On one fixed grid (the profile's representation is all that differs), the flat's table of 121 rows,
    its jumps found or declared, gives the traction of the analytic flat within 1e-6 f p0 at every step and
    node (measured 4e-14), where one spline over the table (which `Gap.from_table` with ``breakpoints=[]``
    refuses, so a `Gap` of the spline's functions) rings across each jump and errs by more than 1e-3 f p0
    (measured 4.1e-2)."""
    found, analytic, corners = asymmetric_flat_table()
    table = found if declared is None else fr.Gap.from_table(*found.table, corners)
    spline = interpolate.CubicSpline(*found.table)
    smooth = fr.Gap(spline, spline.derivative())
    history = fr.History.piecewise_linear([0.0, 0.5 * 0.5 * P, -0.3 * 0.5 * P], None, [2, 2])
    q = {}
    for name, profile in (("analytic", analytic), ("found", table), ("smooth", smooth)):
        contact = fr.Contact(profile, E_STAR, 0.5, P)
        q[name] = fr.simulate(contact, history, fr.models.Grid(192)).q.values
    fp0 = 0.5 * fr.Contact(analytic, E_STAR, 0.5, P).p0
    assert np.abs(q["found"] - q["analytic"]).max() < 1e-6 * fp0
    assert np.abs(q["smooth"] - q["analytic"]).max() > 1e-3 * fp0


@pytest.mark.parametrize("declared", [[], [-5e-4], [5e-4]])
def test_an_undeclared_jump_of_a_tables_curvature_is_refused_naming_it(declared):
    """The flat's table with none or one of its two corners declared: the Contact is refused with the
    position of the first undeclared one and how to declare it; both declared (or found), it is built."""
    table, _, corners = asymmetric_flat_table(breakpoints=declared)
    missing = next(corner for corner in corners if corner not in declared)
    message = rf"^the table's curvature jumps at x = {missing:g} m in the contact .* declare it, Gap.from_table"
    with pytest.raises(ValueError, match=message):
        fr.Contact(table, E_STAR, 0.5, P)
    assert fr.Contact(asymmetric_flat_table(breakpoints=corners)[0], E_STAR, 0.5, P).a > 0


def test_smooth_tables_given_without_breakpoints_are_not_refused():
    """Hertz sampled finely and coarsely, a smooth polynomial and a smooth curve, each one spline
    (``breakpoints=[]``): no jump is reported over nine tenths of the table, and the Contact is built."""
    for rows in (41, 2001):
        x = np.linspace(-1e-3, 1e-3, rows)
        for h0 in (x**2 / 0.1, x**2 / 0.1 + 1e6 * x**4, 1e-3 * np.cosh(1e3 * x)):
            gap = fr.Gap.from_table(x, h0, [])
            assert gap.undeclared_jump(0.9e-3, 0.0) is None
            assert fr.Contact(gap, E_STAR, 0.5, 1e5).a > 0


def test_breakpoints_of_a_table_leave_rows_for_each_spline():
    x = np.linspace(-1e-3, 1e-3, 21)
    lonely = r"^breakpoints: fewer than 2 rows of the table lie in \[0\.0001, 0\.00015\] m"
    with pytest.raises(ValueError, match=lonely):
        fr.Gap.from_table(x, x**2 / 0.1, breakpoints=[1e-4, 1.5e-4])


@pytest.mark.parametrize(
    ("scale", "message"),
    [
        (1e8, r"^the contact \[.*\] m is narrower than 0\.01 of the spacing 2e-05 m of the table's rows there"),
        (1e200, r"^profile: no contact solution found for P = 300000 N/m: the load does not converge"),
    ],
)
def test_a_table_too_steep_for_its_rows_is_one_line(scale, message):
    """The asymmetric pad times `scale`: its contact lies within one interval of the table, where the
    spline's slope is lost to rounding; times 1e200 the solve itself fails (it was brentq's traceback)."""
    from fretting.loading.examples import EXAMPLES

    x, h0 = np.loadtxt(EXAMPLES / "asymmetric_pad_gap.csv", delimiter=",", skiprows=3).T
    with pytest.raises(ValueError, match=message):
        fr.Contact(fr.Gap.from_table(x, scale * h0), E_STAR, 0.5, P)


def test_a_load_too_small_to_form_a_contact_is_one_line():
    """P = 5e-324 N/m (the smallest float) on Hertz: the half-width rounds to zero; a ValueError
    naming P, not a ZeroDivisionError in the peak pressure (issue 38). 1e-300 still forms one."""
    with pytest.raises(ValueError, match="P = 5e-324 N/m gives a contact half-width a = 0.0 m"):
        fr.Contact(fr.Hertz(0.05), 115e9, 0.6, 5e-324)
    tiny = fr.Contact(fr.Hertz(0.05), 115e9, 0.6, 1e-300)
    assert tiny.a > 0 and np.isfinite(tiny.p0) and tiny.p0 > 0
