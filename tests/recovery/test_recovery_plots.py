"""Plots for reflectance recovery: they draw what they are given (matplotlib, Agg)."""

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.recovery import plots
from spectrocolor.recovery.metamers import metamer_mismatch_region
from spectrocolor.recovery.validity import domain_of_validity

GRID = (400.0, 700.0, 10.0)
GRID_NM = sc.wavelength_grid(*GRID)

pytest.importorskip("matplotlib")


def test_reflectance_curves_draw_recovered_and_measured(tmp_path):
    measured = sc.Spectrum(GRID_NM, np.linspace(0.1, 0.6, 31)[None].repeat(2, 0) * [[1], [0.5]],
                           names=("a", "b"))
    ax = plots.reflectance_curves(measured * 0.9, measured)
    assert len(ax.lines) == 4
    np.testing.assert_allclose(ax.lines[1].get_ydata(), measured.values[0])
    ax.figure.savefig(tmp_path / "c.png")
    assert (tmp_path / "c.png").stat().st_size > 1000
    with pytest.raises(sc.SpectrumError, match="measured"):
        plots.reflectance_curves(measured, sc.Spectrum(GRID_NM, measured.values[0]))


@pytest.mark.slow
def test_domain_and_mismatch_plots(tmp_path):
    d = domain_of_validity("D65", wavelengths=GRID)
    ax = plots.domain_of_validity_plot(d)
    outline = [line for line in ax.lines if line.get_label() == "ρ ≥ 0 region"][0]
    np.testing.assert_allclose(outline.get_xydata()[:-1], d.region_xy)
    W = np.asarray(sc.weights(GRID_NM, observer="1931", illuminant="D65"))
    region = metamer_mismatch_region(0.4 * W.sum(axis=0), wavelengths=GRID, directions=30)
    ax = plots.mismatch_region_plot(region, sample_XYZ100_second=region.boundary_XYZ100.mean(0))
    ax.figure.savefig(tmp_path / "m.png")
    ax = plots.macadam_limits_plot((20, 60), wavelengths=GRID)
    assert len([line for line in ax.lines if line.get_label().startswith("Y = ")]) == 2


def test_van_trigt_structure_plots_draw_their_data():
    from spectrocolor.recovery.validity import boundary_locus, generating_functions

    loc = boundary_locus("D65", wavelengths=GRID)
    gen = generating_functions("D65", wavelengths=GRID)
    ax = plots.boundary_locus_plot(loc, gen)
    left = [line for line in ax.lines if line.get_label().startswith("left branch")][0]
    np.testing.assert_allclose(left.get_xydata(), loc.left_xy)
    ax = plots.generating_luminance_plot(gen)
    # one solid Y(λ₁) line per family: class 2, then class 1 at λ_b and at λ_e (Figs. 9–10)
    solid = [line for line in ax.lines if line.get_label().startswith("Y(λ₁)")]
    assert [line.get_label().split(", ", 1)[1] for line in solid] == [
        "class 2 (interior zero at λ₁)", "class 1 (zero at 400 nm)", "class 1 (zero at 700 nm)"]
    for line, rows in zip(solid, (gen.family("2"), gen.family("1", 400.0), gen.family("1", 700.0)),
                          strict=True):
        y = line.get_ydata()
        # exact: the plot holds the generating functions' own numbers (a copy, no arithmetic)
        np.testing.assert_array_equal(y[np.isfinite(y)], gen.luminance_factor[rows])


def test_classes_plot_marks_regions_end_points_and_given_points():
    """Van Trigt Figs. 7–8: class regions (fans from the white), their end points and marked
    chromaticities (``points=``)."""
    d = domain_of_validity("D65", wavelengths=GRID)
    points = {"9": (0.55, 0.32), "1": (0.35, 0.34)}
    ax = plots.domain_of_validity_plot(d, luminance=False, points=points, points_label="test colours")
    marked = [line for line in ax.lines if line.get_label() == "test colours"][0]
    np.testing.assert_array_equal(marked.get_xydata(), list(points.values()))  # exact: the points given
    assert [t.get_text() for t in ax.texts if t.get_text() in points] == list(points)
    ends = [line for line in ax.lines if line.get_label() == "end points of the classes"][0]
    pieces = d.boundary_pieces()
    expected = np.unique(np.round([p.xy[i] for p in pieces for i in (0, -1)], 12), axis=0)
    np.testing.assert_array_equal(ends.get_xydata(), expected)  # exact: the same pieces, rounded alike
    assert {t.get_text() for t in ax.texts} >= {"1: ρ(400) = 0", "1: ρ(700) = 0", "2"}
    with pytest.raises(sc.SpectrumError, match="points"):
        plots.domain_of_validity_plot(d, points=[[0.3, 0.3, 0.4]])
