"""The worked fretting-fatigue map of docs/guide/size-effect.md: the size effect of a cylinder on a flat.

Imported by scripts/make_validation.py (``--only size-effect``), which stamps and writes the page and its
figure. For contact half-widths ``a`` from `SIZES` times the material's critical distance ``L``, at the
same peak pressure ``p0``, ``Q/(f P)`` and bulk stress amplitude, it runs one steady cycle of shear force
and bulk stress in phase, maps the Smith-Watson-Topper parameter over the specimen
(`fretting.analysis.stress.field`, `fretting.analysis.fatigue.apply`) and reads it at the surface hot spot, by the point
method and by the line method (Araujo & Nowell 2002, who observed the size effect this shows).
"""

import time

import matplotlib.pyplot as plt
import numpy as np

import fretting as fr
from fretting.analysis import fatigue, stress
from fretting.loading.examples import EXAMPLES

#: The material: the illustrative steel shipped with the package (its critical distance L = 50 um).
MATERIAL = EXAMPLES / "materials" / "steel.toml"
#: Peak Hertz pressure p0 [Pa], coefficient of friction f, shear force amplitude Q/(f P), and the specimen's
#: bulk stress amplitude sigma_a / (f p0), in phase with Q: the same for every size.
P0, F, LOAD, BULK = 500e6, 0.6, 0.5, 0.4
#: Contact half-widths a / L.
SIZES = (0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0)
#: Steps per segment of the history 0 -> Q* -> -Q* -> Q* (the last two segments the cycle mapped).
STEPS = 16
#: Grid of the maps: NX points over |x| <= SPAN a, NZ depths from 0 to 2 L (the line method's reach).
NX, NZ, SPAN = 441, 41, 1.1


def cylinder(a, material):
    """The Hertz contact of half-width `a` [m] at the peak pressure `P0`.

    ``p0 = 2 P / (pi a)`` and ``a = sqrt(4 P R / (pi E_star))`` (eq 6 of the seed) give ``R = a E_star /
    (2 p0)``: at constant ``p0``, ``R``, ``P`` and ``a`` scale together.
    """
    E_star = fr.plane_strain_modulus(material.E, material.nu)
    R = a * E_star / (2 * P0)
    return fr.Contact(fr.Hertz(R), E_star, F, float(fr.Hertz(R).load(a, E_star)))


def case(a, material):
    """SWT [Pa] at the hot spot, by the point and line methods, of the contact of half-width `a` [m]."""
    contact = cylinder(a, material)
    Q, sigma = LOAD * F * contact.P, BULK * F * contact.p0
    history = fr.History.piecewise_linear([0.0, Q, -Q, Q], [0.0, sigma, -sigma, sigma], STEPS)
    result = fr.simulate(contact, history)
    cycle = list(range(int(history.vertex_step[1]), len(history)))
    L = material.critical_distance
    x, z = SPAN * a * np.linspace(-1, 1, NX), np.linspace(0, 2 * L, NZ)
    maps = fatigue.apply(stress.field(result, x, z, step=cycle, nu=material.nu), "swt", material)
    point = fatigue.point_method(maps.parameter, L)
    hot = float(maps.parameter.sel(z=0.0, x=point.x_hot))
    line = fatigue.line_method(maps.parameter, L, x_hot=point.x_hot)
    return {"a": a, "R": contact.profile.R, "P": contact.P, "hot": hot, "point": point.value, "line": line.value}


def bulk_alone(material):
    """SWT [Pa] of the bulk stress alone, ``sigma_xx = sigma_a sin(t)`` (the field far from any contact)."""
    sigma_a = BULK * F * P0
    t = np.linspace(0, 2 * np.pi, 4 * STEPS + 1)[:, None]
    return float(fatigue.swt(sigma_a * np.sin(t), 0 * t, 0 * t, material).parameter[0])


def figure(rows, material):
    """SWT and life against ``a / L``: at the hot spot, at ``L/2`` below it and averaged over ``2 L``, and
    that of the bulk stress alone."""
    L = material.critical_distance
    size = np.array([row["a"] for row in rows]) / L
    fig, (parameter, life) = plt.subplots(1, 2, figsize=(10, 4))
    for key, label, marker in (
        ("hot", "hot spot", "s"),
        ("point", "point method, L/2", "o"),
        ("line", "line method, 2L", "^"),
    ):
        values = np.array([row[key] for row in rows])
        parameter.semilogx(size, values / 1e3, marker=marker, label=label)
        life.loglog(size, fatigue.swt_life(values, material), marker=marker, label=label)
    parameter.set(xlabel="contact half-width a / L", ylabel="SWT parameter [kPa]", title="SWT on the critical plane")
    life.set(xlabel="contact half-width a / L", ylabel="cycles to failure N_f", title="life from SWT (steel.toml)")
    bulk = bulk_alone(material)
    parameter.axhline(bulk / 1e3, color="grey", linestyle="--", label="bulk stress alone")
    life.axhline(fatigue.swt_life(bulk, material), color="grey", linestyle="--", label="bulk stress alone")
    for ax in (parameter, life):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    return fig


def body(table, save_figure):
    """The page's text below its stamp; ``table(header, rows)`` writes a markdown table, ``save_figure(fig,
    name)`` saves a figure into docs/validation/figures."""
    material = fatigue.Material.from_file(MATERIAL)
    began = time.perf_counter()
    rows = [case(size * material.critical_distance, material) for size in SIZES]
    seconds = time.perf_counter() - began
    save_figure(figure(rows, material), "size_effect.png")
    L = material.critical_distance
    lines = []
    for row in rows:
        lives = fatigue.swt_life(np.array([row["hot"], row["point"], row["line"]]), material)
        lines.append(
            [f"{row['a'] / L:g}", f"{row['a'] * 1e3:.4g}", f"{row['R'] * 1e3:.4g}", f"{row['P'] / 1e3:.4g}"]
            + [f"{row[key] / 1e3:.4g}" for key in ("hot", "point", "line")]
            + [f"{life:.3g}" for life in lives]
        )
    header = ["a / L", "a [mm]", "R [mm]", "P [kN/m]", "SWT hot spot [kPa]", "SWT point [kPa]", "SWT line [kPa]"]
    header += ["N_f hot spot", "N_f point", "N_f line"]
    hot = np.array([row["hot"] for row in rows])
    spread = np.ptp(hot) / hot.max()
    return f"""
A cylinder of radius `R` pressed on a flat specimen by `P` per unit length, then a steady cycle of the shear
force `Q` between `+-Q*` with the specimen's bulk stress between `+-sigma_a` in phase (the set-up of a
fretting-fatigue test rig): the contact half-width `a` varies over {SIZES[0]:g} to {SIZES[-1]:g} times the
critical distance `L` = {L * 1e6:g} um of the material, at the same peak pressure `p0` = {P0 / 1e6:g} MPa,
`Q*/(f P)` = {LOAD:g} (`f` = {F:g}) and `sigma_a / (f p0)` = {BULK:g}, so that `R` and `P` scale with `a`. The
material is the illustrative steel of `histories/materials/steel.toml`
([multiaxial fatigue](fatigue.md#material-files)).

For each size the script runs the history with the default model, computes the specimen's stress field over
the cycle on {NX} x {NZ} points (`|x| <= {SPAN:g} a`, depth 0 to `2 L`; [stress under the surface](stress.md)),
maps the Smith-Watson-Topper parameter on its critical plane (`fretting.analysis.fatigue.apply`) and reads it at the
surface hot spot, at `L/2` below it (point method) and averaged over `2 L` below it (line method), with the
life of each from the strain-life curve (`swt_life`).

At constant `p0`, `Q*/(f P)` and `sigma_a / (f p0)` the stress field is a function of `x / a` and `z / a`
alone: the hot spot sees the same parameter for every size (here the largest and smallest differ by
{spread:.1e} of it, rounding), so a criterion read at the surface predicts no size effect. The critical distance reads
the field `L/2` (or over `2 L`) deep, which is a larger part of a small contact: there the parameter has
fallen further from its peak, and the life is longer. As `a / L` falls toward 0 the critical distance
leaves the contact's field and the parameter tends to that of the bulk stress alone, {bulk_alone(material) / 1e3:.4g}
kPa (`sigma_a^2 (1 - nu^2) / E` in plane strain; the dashed line); near `a ~ L` the contact's compression
below its trailing edge can hold it under that value. This is the size effect that Araujo & Nowell (2002)
measured at constant `p0`, `Q/(f P)` and bulk stress, and that critical distances account for.

{table(header, lines)}

![SWT and life against the contact size](../validation/figures/size_effect.png)

The study took {seconds:.0f} s. Its code is `scripts/size_effect.py`; the same maps for one result come from
the command line: `fretting stress RESULT --material steel.toml --criterion swt --depth D`, with `D a >= 2 L`
([the command line](cli.md#fretting-stress-result)).

## References

- J. A. Araujo and D. Nowell (2002), The effect of rapidly varying contact stress fields on fretting
  fatigue, *International Journal of Fatigue* 24, 763-775.
- D. Taylor (1999), Geometrical effects in fatigue: a unifying theoretical model, *International Journal of
  Fatigue* 21, 413-420.
- K. N. Smith, P. Watson and T. H. Topper (1970), A stress-strain function for the fatigue of metals,
  *Journal of Materials* 5, 767-778.
"""
