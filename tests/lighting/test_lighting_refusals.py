"""Light metrics that refuse to guess (issue 27, part 4).

A light with no power, negative power, values that are not finite, or a spectrum that does not
cover the quantity's range is never given a number: NaN and a reason per light in a batch (the
other lights computed as if alone), a clear error for one light. A grid the colour metrics do
not take is refused with a hint the caller can act on (the command line names ``--resample``).
"""

from __future__ import annotations

import numpy as np
import pytest

from spectrocolor import Spectrum, illuminant, wavelength_grid, write_spectra
from spectrocolor.cli import main
from spectrocolor.errors import SpectrumError
from spectrocolor.lighting import (
    alpha_opic,
    alpha_opic_irradiance,
    colour_fidelity,
    colour_rendering_index,
    light_report,
    luminous_efficacy_of_radiation,
    luminous_quantity,
    summary,
)
from spectrocolor.lighting.spectra import light_refusals

FL2 = illuminant("FL2")  # 380–780 nm at 5 nm
GRID = FL2.wavelengths_nm
#: A batch and a single light differ only in the order of the sums: a few ulps of the result
#: times the K = 81 terms summed, far below this (and the metrics print 1–4 decimals).
SAME = 1e-9


def _batch(*rows, names=None):
    return Spectrum(GRID, np.stack(rows), names)


def _single_metrics():
    return {
        "LER": lambda s: luminous_efficacy_of_radiation(s),
        "illuminance": lambda s: luminous_quantity(s),
        "alpha-opic irradiance": lambda s: alpha_opic_irradiance(s),
        "alpha-opic": lambda s: alpha_opic(s),
        "CRI": lambda s: colour_rendering_index(s),
        "fidelity": lambda s: colour_fidelity(s),
        "summary": lambda s: summary(s),
    }


AT_550NM = GRID == 550.0  # exact: 550 nm is a sample of the whole-nanometre grid


@pytest.mark.parametrize("name, values, reason", [
    ("all-negative", -FL2.values, "negative power"),
    ("zero", 0.0 * FL2.values, "no power"),
    ("not finite", np.where(AT_550NM, np.nan, FL2.values), "not finite"),
])
def test_a_single_refused_light_raises_for_every_metric(name, values, reason):
    """Before: the all-negative light had LER 336 lm/W (a ratio of two negative sums)."""
    light = Spectrum(GRID, values)
    for compute in _single_metrics().values():
        with pytest.raises(SpectrumError, match=f"spd: {reason}"):
            compute(light)


def test_a_light_measured_over_less_than_the_range_is_refused_not_2_7_percent_high():
    short = FL2.restrict(400, 700)
    for compute in _single_metrics().values():
        with pytest.raises(SpectrumError, match="measured over less than the range: sampled 400–700 nm"):
            compute(short)
    # in a batch: NaN and the reason for every light (the grid is theirs)
    batch = Spectrum(short.wavelengths_nm, np.stack([short.values, 2 * short.values]))
    assert np.all(np.isnan(luminous_efficacy_of_radiation(batch)))
    reasons = light_refusals(batch, "photometry")
    assert reasons.shape == (2,) and all(r.startswith("measured over less than the range") for r in reasons)
    assert np.all(np.isnan(colour_rendering_index(batch).Ra))


def test_a_batch_returns_nan_and_a_reason_for_its_bad_lights_and_computes_the_others():
    """Before: one NaN light made the whole batch raise."""
    noisy = FL2.values.copy()
    noisy[[0, 1]] = -1e-3 * FL2.values.max()  # measurement noise: kept, the light is computed
    rows = [FL2.values, -FL2.values, 0.0 * FL2.values, np.where(GRID > 700.0, np.nan, FL2.values),
            np.where(AT_550NM, np.inf, FL2.values), noisy]
    batch = _batch(*rows, names=("fl2", "negative", "dark", "short", "inf", "noisy"))
    good = [0, 5]
    expected = ["", "negative power", "no power", "measured over less than the range: values only over 380–700 nm",
                "not finite", ""]

    ler = luminous_efficacy_of_radiation(batch)
    alpha = alpha_opic(batch)
    cri, fidelity = colour_rendering_index(batch), colour_fidelity(batch)
    for i, start in enumerate(expected):
        ok = i in good
        for values, reason in ((ler[i], light_refusals(batch, "photometry")[i]),
                               (alpha.der[i], alpha.reason[i]), (cri.Ra[i], cri.reason[i]),
                               (fidelity.Rf[i], fidelity.reason[i])):
            assert np.all(np.isfinite(values)) == ok
            assert reason.startswith(start) if start else reason == ""
    # the lights computed are computed as alone
    for i in good:
        light = Spectrum(GRID, rows[i])
        assert ler[i] == pytest.approx(float(luminous_efficacy_of_radiation(light)), rel=SAME)
        assert cri.Ra[i] == pytest.approx(float(colour_rendering_index(light).Ra), abs=SAME)
        assert fidelity.Rf[i] == pytest.approx(float(colour_fidelity(light).Rf), abs=SAME)
        np.testing.assert_allclose(alpha.der[i], alpha_opic(light).der, rtol=SAME)
    # the report says the same, per light
    report = light_report(batch)
    reasons = report.reasons()
    assert [bool(r) for r in reasons] == [i not in good for i in range(len(rows))]
    assert reasons[1].startswith("negative power") and np.isnan(report.headline()["Ra"][1])


def test_a_negative_luminous_sum_is_refused_even_with_positive_power():
    # positive power in the infrared, negative in the green: Σ S Δλ > 0 but Σ S V Δλ < 0
    grid = wavelength_grid(380, 830, 5)
    values = np.where(grid > 760, 50.0, 0.0) - np.exp(-0.5 * ((grid - 555) / 10) ** 2)
    assert values @ np.full(grid.size, 5.0) > 0
    light = Spectrum(grid, values)
    with pytest.raises(SpectrumError, match="negative power: the photopic luminous sum"):
        luminous_efficacy_of_radiation(light)
    batch = Spectrum(grid, np.stack([values, illuminant("D65", grid).values]))
    assert np.isnan(luminous_efficacy_of_radiation(batch)[0]) and np.isfinite(luminous_efficacy_of_radiation(batch)[1])
    assert light_refusals(batch, "photometry")[0] == ""  # the input check passes; the luminous sum refuses
    assert alpha_opic(batch).reason[0].startswith("negative power")


def test_2_nm_data_are_refused_with_a_hint_in_python_and_with_resample_from_the_command_line(tmp_path, capsys):
    grid = wavelength_grid(380, 780, 2)
    light = Spectrum(grid, np.interp(grid, GRID, FL2.values), ("fl2",))
    with pytest.raises(SpectrumError, match=r"2 nm steps; resample it, e\.g\. spd\.resample"):
        colour_rendering_index(light)
    assert np.isfinite(luminous_efficacy_of_radiation(light))  # photometry takes any grid
    source = write_spectra(light, tmp_path / "fl2_2nm.csv")
    assert main(["light", str(source), "--out", str(tmp_path / "r.json")]) == 2
    error = capsys.readouterr().err
    assert "2 nm steps" in error and "--resample sprague" in error and "spd.resample" not in error
    assert main(["light", str(source), "--out", str(tmp_path / "r.json"), "--resample", "sprague"]) == 0


def test_the_command_line_reports_refused_lights_with_their_reason(tmp_path, capsys):
    import json

    source = write_spectra(_batch(FL2.values, -FL2.values, names=("fl2", "inverted")), tmp_path / "two.csv")
    assert main(["light", str(source), "--out", str(tmp_path / "r.json")]) == 0
    assert "not computed for 1 (e.g. inverted: negative power" in capsys.readouterr().out
    lights = json.loads((tmp_path / "r.json").read_text())["lights"]
    assert lights[0]["not_computed"] is None and lights[0]["Ra"] is not None
    assert lights[1]["not_computed"].startswith("negative power") and lights[1]["LER_lm_per_W"] is None


def test_an_irregular_spectrometer_grid_gets_the_option_that_works(tmp_path, capsys):
    """An OceanView export (2048 pixels at irregular wavelengths): the hint names --resample linear,
    since Sprague needs uniform data, and that option then gives CIE A's indices (A is its own reference)."""
    from pathlib import Path

    source = Path(__file__).parents[1] / "data" / "io" / "oceanview_flame.txt"
    out = str(tmp_path / "r.json")
    assert main(["light", str(source), "--out", out]) == 2
    error = capsys.readouterr().err
    assert "irregular" in error and "--resample linear" in error and "--resample sprague" not in error
    assert main(["light", str(source), "--out", out, "--resample", "sprague"]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "--resample sprague" in error and "--resample linear" in error
    assert main(["light", str(source), "--out", out, "--resample", "linear"]) == 0
    assert "FLMS01234" in capsys.readouterr().out
