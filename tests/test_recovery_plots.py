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
    solid = [line for line in ax.lines if line.get_label().startswith("Y(λ₁)")][0]
    interior = gen.solution_class == "1"
    np.testing.assert_allclose(solid.get_ydata(), gen.luminance_factor[interior])
