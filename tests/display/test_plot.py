"""Chromaticity diagrams and spectrum plots: structure and pixel colours checked independently."""

from __future__ import annotations

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.plot import horseshoe_image, planckian_locus_xy

pytest.importorskip("matplotlib")


def _pixel(image, extent, point):
    left, right, bottom, top = extent
    h, w = image.shape[:2]
    col = int(round((point[0] - left) / (right - left) * (w - 1)))
    row = int(round((top - point[1]) / (top - bottom) * (h - 1)))
    return image[row, col]


def test_horseshoe_colours_inside_srgb_are_exact():
    colour = pytest.importorskip("colour")
    image, extent = horseshoe_image("xy", resolution=300)
    left, right, bottom, top = extent
    h, w = image.shape[:2]
    for point in [(0.3127, 0.3290), (0.4, 0.4), (0.25, 0.3), (0.5, 0.35)]:
        col = int(round((point[0] - left) / (right - left) * (w - 1)))
        row = int(round((top - point[1]) / (top - bottom) * (h - 1)))
        x = left + col * (right - left) / (w - 1)
        y = top - row * (top - bottom) / (h - 1)
        XYZ = colour.xyY_to_XYZ([x, y, 1.0])
        npm = colour.models.normalised_primary_matrix(
            colour.RGB_COLOURSPACES["sRGB"].primaries, colour.RGB_COLOURSPACES["sRGB"].whitepoint
        )
        rgb = np.linalg.inv(npm) @ XYZ
        assert rgb.min() >= 0
        expected = colour.models.eotf_inverse_sRGB(rgb / rgb.max())
        np.testing.assert_allclose(image[row, col, :3], expected, atol=1e-9)
        assert image[row, col, 3] == 1.0  # exact: alpha is set to 1 inside the locus


def test_horseshoe_outside_srgb_is_on_the_gamut_boundary_and_outside_locus_is_transparent():
    image, extent = horseshoe_image("xy", resolution=300)
    green = _pixel(image, extent, (0.1, 0.7))  # outside sRGB, inside the locus
    assert green[3] == 1.0  # exact: alpha is set to 1 inside the locus
    assert green[:3].max() == pytest.approx(1.0) and green[:3].min() == pytest.approx(0.0)
    # exact: alpha is set to 0 outside the locus
    assert _pixel(image, extent, (0.7, 0.1))[3] == 0.0  # below the purple line
    assert _pixel(image, extent, (0.01, 0.01))[3] == 0.0  # exact: alpha is set to 0 outside the locus


def test_planckian_locus_against_colour_science():
    colour = pytest.importorskip("colour")
    ours = planckian_locus_xy([2000, 6504], "1931")
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    for t, xy in zip([2000, 6504], ours, strict=True):
        sd = colour.sd_blackbody(t, colour.SpectralShape(360, 830, 1))
        ref = colour.XYZ_to_xy(colour.sd_to_XYZ(sd, cmfs, method="Integration"))
        np.testing.assert_allclose(xy, ref, atol=2e-5)


@pytest.mark.parametrize("kind", ["xy", "uv"])
@pytest.mark.slow
def test_chromaticity_diagram_draws_everything(kind, artifacts_dir):
    ax = sc.chromaticity_diagram(
        kind=kind,
        spaces=("sRGB", "Display P3"),
        points=[[0.3, 0.5], [0.5, 0.3]],
        labels=["p1", "p2"],
        curves=[np.array([[0.2, 0.2], [0.3, 0.3], [0.4, 0.3]])],
        curve_labels=["a curve"],
    )
    texts = {t.get_text() for t in ax.texts}
    assert {"520", "580", "620", "D65", "p1", "p2", "6500 K"} <= texts
    legend = {t.get_text() for t in ax.get_legend().get_texts()}
    assert {"sRGB", "Display P3", "purple line", "Planckian locus", "a curve"} <= legend
    ax.figure.savefig(artifacts_dir / f"test_diagram_{kind}.png", dpi=80)


def test_spectrum_plot_bars_are_tinted():
    s = sc.Spectrum(np.arange(400.0, 701.0, 10.0), np.linspace(1, 2, 31), names=["ramp"])
    ax = sc.spectrum_plot(s)
    bars = ax.patches
    assert len(bars) == 31
    np.testing.assert_allclose(
        np.array([b.get_facecolor()[:3] for b in bars]),
        sc.wavelength_tint(s.wavelengths_nm) / 255,
        atol=1e-12,
    )
    assert ax.get_title() == "ramp"
    area = sc.spectrum_plot(s, style="area")
    assert len(area.collections) > 100


def test_errors():
    with pytest.raises(sc.ColorimetryError, match="kind must be"):
        sc.chromaticity_diagram(kind="Lab")
    with pytest.raises(sc.ColorimetryError, match="labels must name"):
        sc.chromaticity_diagram(points=[[0.3, 0.3]], labels=["a", "b"], fill=False)
    batch = sc.Spectrum(np.arange(400.0, 701.0, 10.0), np.ones((2, 31)))
    with pytest.raises(sc.ColorimetryError, match="index="):
        sc.spectrum_plot(batch)


def _text_boxes(ax):
    """Drawn text boxes of the axes' texts (text only, not leader lines), display units."""
    from matplotlib.text import Text

    ax.figure.draw_without_rendering()
    texts = [t for t in ax.texts if t.get_visible() and t.get_text()]
    return texts, [Text.get_window_extent(t) for t in texts]


def _overlapping_pairs(texts, boxes):
    return [(texts[i].get_text(), texts[j].get_text())
            for i in range(len(boxes)) for j in range(i + 1, len(boxes))
            if boxes[i].overlaps(boxes[j])]


@pytest.mark.slow
def test_uv_temperature_labels_keep_off_the_white_point():
    ax = sc.chromaticity_diagram(kind="uv", spaces=("sRGB", "SPECTRA 7000K"))
    texts, boxes = _text_boxes(ax)
    by_text = dict(zip([t.get_text() for t in texts], boxes, strict=True))
    d65 = ax.transData.transform(sc.uv_1976(XYZ=sc.white_point("D65")))
    for name, box in by_text.items():
        if name.endswith(" K"):
            assert not box.overlaps(by_text["D65"]), name
            assert not box.contains(*d65), name
    assert "6500 K" in by_text  # there is room for it on the other side of the locus
    assert _overlapping_pairs(texts, boxes) == []


@pytest.mark.parametrize("kind", ["xy", "uv"])
@pytest.mark.slow
def test_colorchecker_labels_do_not_overlap(kind):
    from importlib.resources import files

    spectra = sc.read_spectra(files("spectrocolor") / "data/reflectances_colorchecker_babel.csv")
    XYZ = sc.tristimulus(spectra, observer="1931", illuminant="D65")
    ax = sc.chromaticity_diagram(kind=kind, points=XYZ, labels=list(spectra.names),
                                 whites={"D65": sc.white_point("D65")})
    texts, boxes = _text_boxes(ax)
    assert _overlapping_pairs(texts, boxes) == []
    drawn = [t.get_text() for t in texts]
    # the six neutrals sit at one spot: one label for them, the merge stated in the legend
    neutral = [t for t in drawn if t.startswith("white_9.5")]
    assert neutral == ["white_9.5_(.05_D) +5"]
    legend = "\n".join(t.get_text() for t in ax.get_legend().get_texts())
    assert "24 points" in legend and "'+n': n more at the same spot" in legend
    named = [n for n in spectra.names if n in drawn or f"{n} +5" in drawn]
    omitted = 24 - 5 - len(named)
    assert omitted == 0 or f"{omitted} labels left out" in legend
    assert "D65" in drawn
