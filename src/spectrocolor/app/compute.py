"""What the explorer shows, computed with the library: one function per API answer.

Every number the page displays comes from here (or, for the interactive repaint of a drag,
from the weights and display matrix that :func:`model` serves, checked against :func:`evaluate`
by the tests). The page's distributions are bin levels 0..``FULL_LEVEL`` (SPECTRA: 0-30); a
distribution is the relative factor ``levels / FULL_LEVEL`` of a reference light: the equal-energy
spectrum E (settings 1, 2, 3 and 5, where the full spectrum is the white, Y = 100), or the
illuminant of setting 4 (the samples are reflectances; the perfect white has Y = 100).

Why this file is long: it holds one function per API answer of the explorer's main page (model,
evaluate with each card's XYZ, L M S, xy, CIELAB, λd and rendering, metamer, presets, import,
export, light metrics), each a thin call into the library, and they share the page's conventions
(levels 0-30, the 400-700 nm grid, the display chain, the exported units); split apart, each file
would have to restate them.
"""

from __future__ import annotations

from pathlib import Path
from typing import get_args

import numpy as np

from ..chromaticity import dominant_wavelength, spectral_locus
from ..colorimetry import tristimulus, weights
from ..cones import cone_responses
from ..coordinates import lab, xy
from ..differences import delta_e_2000
from ..display.chain import DEFAULT_CHAIN_NORMALISATION, DEFAULT_WHITE_ADAPTATION, DisplayChain, display_chain
from ..display.explain import out_of_gamut_channels
from ..display.gamut import DEFAULT_GAMUT, DEFAULT_TOLERANCE
from ..display.spaces import rgb_space
from ..display.transfer import LevelTable, PowerLaw, SRGBCurve
from ..display_emission import emission_sources, excitation_function, primary_emission
from ..errors import ColorimetryError, SpectrumError
from ..illuminants import illuminant
from ..io import read_spectra, write_spectra
from ..mixing import additive_mix
from ..observers import observer as observer_cmfs
from ..pictures import wavelength_tint
from ..recovery.smoothest import smoothest_reflectance
from ..registry import Registry
from ..spectrum import Spectrum, wavelength_grid
from ..temperature import cct
from . import presets as P
from .choices import ADAPTATIONS, DISPLAYS, GAMUTS, NORMALISATIONS, Step, observer_labels

__all__ = ["ADAPTATIONS", "DISPLAYS", "GAMUTS", "NORMALISATIONS", "DEFAULT_GAMUT", "DEFAULT_NORMALISE",
           "DEFAULT_ADAPTATION", "FULL_LEVEL", "STEPS_NM", "grid", "pipeline", "model", "evaluate",
           "metamer", "presets", "import_spectra", "export_spectra", "EXPORT_UNIT", "light_metrics"]

FULL_LEVEL = P.FULL_LEVEL
START_NM, STOP_NM = P.START_NM, P.STOP_NM
#: The bin widths, nm, from :data:`spectrocolor.app.choices.Step`.
STEPS_NM = tuple(float(s) for s in get_args(Step))
#: The observers offered, ``{key: label}`` (from the observer registry, read at import; the
#: request models and ``/api/options`` read the registry live).
OBSERVERS = observer_labels()
DEFAULT_NORMALISE, DEFAULT_ADAPTATION = DEFAULT_CHAIN_NORMALISATION, DEFAULT_WHITE_ADAPTATION
#: How an imported file's values become levels (:func:`import_spectra`), the default first.
IMPORT_SCALES = Registry("scale", "a scaling of imported values", SpectrumError)
IMPORT_SCALES.add("peak", "peak", "each spectrum scaled so that its peak in 400-700 nm is the full level",
                  label=f"peak → {FULL_LEVEL:g}")
IMPORT_SCALES.add("unit", "unit", f"the values are factors 0-1 (times {FULL_LEVEL:g})", label="factors 0–1")
IMPORT_SCALES.add("levels", "levels", f"the values are levels 0-{FULL_LEVEL:g} already",
                  label=f"levels 0–{FULL_LEVEL:g}")


def grid(step_nm: float) -> np.ndarray:
    """The explorer's wavelength grid, 400-700 nm at ``step_nm`` (10 nm = SPECTRA's 31 bins)."""
    return wavelength_grid(START_NM, STOP_NM, step_nm)


def step_label(step_nm: float) -> str:
    """The page's name of a bin width: ``"31 × 10 nm (SPECTRA)"``, ``"61 × 5 nm"``, ...

    Examples
    --------
    >>> step_label(10.0), step_label(1.0)
    ('31 × 10 nm (SPECTRA)', '301 × 1 nm')
    """
    text = f"{len(grid(step_nm))} × {step_nm:g} nm"
    return text + " (SPECTRA)" if len(grid(step_nm)) == 31 else text


def _reference(wavelengths_nm: np.ndarray, illuminant_levels):
    """The illuminant argument for the library: E, or the page's illuminant levels."""
    if illuminant_levels is None:
        return "E"
    return Spectrum(wavelengths_nm, np.asarray(illuminant_levels, dtype=float))


def _none_nan(v: float):
    return float(v) if np.isfinite(v) else None


def _transfer_description(space) -> dict:
    t = space.transfer
    if isinstance(t, SRGBCurve):
        return {"kind": "srgb", "threshold": t.threshold, "name": t.name}
    if isinstance(t, PowerLaw):
        return {"kind": "power", "gamma": t.gamma, "name": t.name}
    if isinstance(t, LevelTable):
        return {"kind": "levels", "levels": t.levels.tolist(), "name": t.name}
    return {"kind": "server", "name": getattr(t, "name", type(t).__name__)}


def pipeline(step_nm, observer, display, normalise, adaptation, illuminant_levels=None) -> DisplayChain:
    """The linear part of the display chain for one set of choices, shared by the API answers.

    The page's grid and lights made into summation weights (the page's light, and E), then
    :func:`spectrocolor.display.chain.display_chain`: its ``weights`` (K x 3, the reference white
    has Y = 100), ``to_display``, ``matrix_from_XYZ``, ``scale`` and ``space``.
    """
    wl = grid(step_nm)
    W = weights(wl, observer=observer, illuminant=_reference(wl, illuminant_levels))
    W_E = weights(wl, observer=observer, illuminant="E")
    return display_chain(rgb_space(display), W, W_E, normalise=normalise, adaptation=adaptation)


def model(step_nm: float, observer: str, display: str, illuminant_levels=None,
          normalise: str = DEFAULT_NORMALISE, adaptation: str = DEFAULT_ADAPTATION) -> dict:
    """Everything the page needs to draw and to repaint a drag without a round trip.

    ``weights`` (K x 3) and ``matrix_from_XYZ`` (3 x 3, the effective matrix: display matrix
    times the adaptation and SPECTRA's per-channel k where chosen) reproduce :func:`evaluate`'s
    XYZ and linear RGB; ``fixed_scale`` is the divisor of normalisation A (exact or SPECTRA's);
    ``transfer`` names the encoding. ``display_white`` gives the display's white point and
    CCT; ``emission`` the primaries' spectra (seed 002 Fig. 9, in levels per unit drive) and
    ``excitation`` the function γ (Fig. 10). The locus, gamut triangle, white and bar tints are
    for drawing only.
    """
    wl = grid(step_nm)
    chain = pipeline(step_nm, observer, display, normalise, adaptation, illuminant_levels)
    W, space = chain.weights, chain.space
    white_XYZ = np.ones(len(wl)) @ W
    locus = spectral_locus(observer)
    keep = (locus.wavelengths_nm >= 380) & (locus.wavelengths_nm <= 700)
    tints = np.asarray(wavelength_tint(wl), dtype=float) / 255.0  # rgb8 → 0–1 for the canvas
    temperature = cct(space.white_xy)
    codes, gamma = excitation_function(space)
    ybar = np.asarray(observer_cmfs("1931").resample(wl).values)[1]
    return {
        "wavelengths_nm": wl.tolist(),
        "full_level": FULL_LEVEL,
        "observer": observer,
        "display": space.name,
        "normalise": normalise,
        "adaptation": adaptation,
        "weights": (W / FULL_LEVEL).tolist(),
        "weights_per": "level",
        "matrix_from_XYZ": chain.matrix_from_XYZ.tolist(),
        "display_matrix_from_XYZ": np.asarray(space.matrix_from_XYZ).tolist(),
        "adaptation_matrix": chain.adaptation_matrix.tolist(),
        "channel_factors": chain.channel_factors.tolist(),
        "fixed_scale": chain.scale,
        "tolerance": DEFAULT_TOLERANCE,
        "transfer": _transfer_description(space),
        "bit_depth": 6 if isinstance(space.transfer, LevelTable) else 8,
        "white_XYZ": white_XYZ.tolist(),
        "white_xy": xy(white_XYZ).tolist(),
        "display_white_xy": np.asarray(space.white_xy).tolist(),
        "display_white": {"XYZ": np.asarray(space.white_XYZ).tolist(),
                          "xy": np.asarray(space.white_xy).tolist(),
                          "cct_K": _none_nan(float(temperature.cct_K)),
                          "duv": _none_nan(float(temperature.duv))},
        "primaries_xy": np.asarray(space.primaries_xy).tolist(),
        "luminance_row": np.asarray(space.luminance_row).tolist(),
        "emission": {"levels_per_drive": (FULL_LEVEL * primary_emission(space, wl).values)
                     .tolist(),
                     "sources": list(emission_sources(space, wl)),
                     "ybar": ybar.tolist()},
        "excitation": {"codes": codes.tolist(), "emission": gamma.tolist()},
        "locus": {"wavelengths_nm": locus.wavelengths_nm[keep].tolist(),
                  "xy": np.round(np.asarray(locus.xy)[keep], 6).tolist()},
        "tints": tints.tolist(),
    }


def _dominant(xy_: np.ndarray, white_xy: np.ndarray, observer: str, lit: np.ndarray):
    """Dominant wavelengths and purities, or None and the reason where they are undefined."""
    n = len(xy_)
    dom_nm, purity = np.full(n, np.nan), np.full(n, np.nan)
    dom_comp = np.zeros(n, bool)
    if not lit.any():
        return dom_nm, dom_comp, purity, None
    try:
        d = dominant_wavelength(xy_[lit], white_xy, observer)
    except ColorimetryError as exc:  # e.g. a single-line illuminant: its white is on the locus
        return dom_nm, dom_comp, purity, f"dominant wavelength undefined: {exc}"
    dom_nm[lit], dom_comp[lit], purity[lit] = d.wavelength_nm, d.complementary, \
        d.excitation_purity
    return dom_nm, dom_comp, purity, None


def evaluate(step_nm, observer, display, normalise, gamut, spectra, illuminant_levels=None,
             pairs=(), adaptation: str = DEFAULT_ADAPTATION, additive=()) -> dict:
    """Colorimetry and display rendering of up to a few distributions (bin levels).

    Returns per distribution: XYZ (CIE, Y = 100 for the full spectrum / perfect white), the cone
    responses ``LMS`` (CIE 2006 fundamentals of the observer's field, 100 each for the same white;
    None, with ``lms_note``, where the white leaves a cone unexcited), the
    ``XYZ_row`` the page shows (SPECTRA's one k per channel in "spectra-exact", else XYZ), xy,
    dominant or complementary wavelength and excitation purity relative to the reference
    white (None, with ``dominant_note``, where undefined), CIELAB, the XYZ the display is asked
    to show (after SPECTRA's per-channel k and the adaptation), the rendering (linear RGB,
    codes, flags, the gamut strategy applied and the library's explanation), the light the
    screen emits for those codes (seed 002 STEP 4) and a status line; per pair, ΔE00.

    ``additive`` lists pairs ``(a, b)`` of ``spectra``: each appends their overlap, the sum
    :func:`spectrocolor.mixing.additive_mix` (two spotlights on one screen, seed 002 "Serial and
    parallel composition"), after the spectra, so the answer has one colour more per pair and
    ``pairs`` may name it. A sum may pass the full level.
    """
    wl = grid(step_nm)
    reference = _reference(wl, illuminant_levels)
    levels = np.asarray(spectra, dtype=float)
    if len(additive):
        levels = np.vstack([levels, *(additive_mix(levels[a], levels[b]) for a, b in additive)])
    XYZ, white_XYZ, xy_, white_xy, lit, dominant = _cie_values(wl, levels, reference, observer)
    chain = pipeline(step_nm, observer, display, normalise, adaptation, illuminant_levels)
    shown_XYZ = chain.shown_XYZ(XYZ)
    # the X Y Z row: SPECTRA's step-1 values (one k per channel, the full spectrum 100/100/100)
    # in "spectra-exact", else CIE's (one k); xy, CIELAB and λd are always CIE's
    row_XYZ = XYZ * chain.channel_factors
    r = chain.render(XYZ, gamut)
    shown = _rendered(r, chain.space, wl, shown_XYZ, row_XYZ, gamut, normalise, lit)
    lab_, lab_note = _cielab(XYZ, white_XYZ)
    LMS, lms_note = _cone_values(wl, levels, reference, observer)
    colours = [{**_cie_row(i, XYZ, xy_, dominant, lit, lab_), "LMS": [_none_nan(v) for v in LMS[i]], **shown[i]}
               for i in range(len(levels))]
    delta = [_none_nan(float(delta_e_2000(lab_[a], lab_[b]))) if lab_note is None else None
             for a, b in pairs]
    # The lights as the display is asked to show them (after normalisation A or B, before any
    # gamut strategy), relative to the display's own white: what the split patch compares.
    shown_lab = lab(chain.space.XYZ_from_rgb_linear(r.rgb_unmapped), chain.space.white_XYZ)
    delta_shown = [float(delta_e_2000(shown_lab[a], shown_lab[b])) for a, b in pairs]
    return {
        "colours": colours,
        "delta_e_2000": delta,
        "delta_e_2000_shown": delta_shown,
        "white_XYZ": white_XYZ.tolist(),
        "white_xy": white_xy.tolist(),
        "XYZ_row_note": XYZ_ROW_NOTES["spectra-exact" if normalise == "spectra-exact" else "cie"],
        "lab_note": lab_note,
        "lms_note": lms_note,
        "normalise": normalise,
        "adaptation": adaptation,
        "gamut": r.gamut,
        "display": r.space,
        "bit_depth": r.bit_depth,
        "light_metrics": None if illuminant_levels is None else light_metrics(wl, illuminant_levels),
    }


def _cie_values(wl, levels, reference, observer):
    """XYZ, the white's XYZ, both xy, which distributions are lit, and :func:`_dominant`'s answer."""
    XYZ = tristimulus(Spectrum(wl, levels / FULL_LEVEL), observer=observer, illuminant=reference)
    white_XYZ = tristimulus(Spectrum.constant(1.0, wl), observer=observer, illuminant=reference)
    xy_, white_xy = xy(XYZ), xy(white_XYZ)
    lit = XYZ[:, 1] > 0
    return XYZ, white_XYZ, xy_, white_xy, lit, _dominant(xy_, white_xy, observer, lit)


def _cone_values(wl, levels, reference, observer):
    """L, M, S of each distribution (CIE 2006 cones of the observer's field, the reference's perfect
    white = 100 each), and None; or NaN and why, where the white leaves a cone unexcited."""
    try:
        return cone_responses(Spectrum(wl, levels / FULL_LEVEL), illuminant=reference, field=observer), None
    except ColorimetryError as exc:  # e.g. an illuminant with no short-wave light: S of the white is 0
        return np.full((len(levels), 3), np.nan), f"L M S undefined: {exc}"


def _cielab(XYZ, white_XYZ):
    """CIELAB of each XYZ relative to the white, and None; or NaN and why, where it is undefined."""
    if np.all(white_XYZ > 0):
        return lab(XYZ, white_XYZ), None
    # e.g. a single line beyond 650 nm: its white has Z = 0, CIELAB is undefined
    return np.full_like(XYZ, np.nan), (f"CIELAB and ΔE00 undefined: the reference white has X, Y, Z = "
                                       f"{np.round(white_XYZ, 3).tolist()} (CIELAB needs all three > 0)")


def _cie_row(i, XYZ, xy_, dominant, lit, lab_) -> dict:
    """The CIE part of :func:`evaluate`'s answer for distribution ``i``."""
    dom_nm, dom_comp, purity, dom_note = dominant
    return {
        "XYZ": XYZ[i].tolist(),
        "xy": [_none_nan(v) for v in xy_[i]],
        "dominant_nm": _none_nan(dom_nm[i]),
        "complementary": bool(dom_comp[i]),
        "purity": _none_nan(purity[i]),
        "dominant_note": dom_note if lit[i] else None,
        "lab": [_none_nan(v) for v in lab_[i]],
    }


def _rendered(r, space, wl, shown_XYZ, row_XYZ, gamut, normalise, lit) -> list[dict]:
    """The display part of :func:`evaluate`'s answer per distribution: the rendering ``r``, the
    light the screen emits for its codes (seed 002 STEP 4) and the status line."""
    explanations = r.explain()
    negative, over = out_of_gamut_channels(r)
    scales = np.broadcast_to(np.asarray(r.scale, dtype=float), (len(lit),))
    primaries = primary_emission(space, wl).values
    _, gamma = excitation_function(space)
    drive = gamma[r.codes]  # γ(code): the fraction of full emission of each primary
    emitted_levels = FULL_LEVEL * scales[:, None] * (drive @ primaries)
    emitted_XYZ = scales[:, None] * (drive @ np.asarray(space.matrix_to_XYZ).T)
    rows = []
    for i in range(len(lit)):
        if not lit[i]:
            status = "black"
        elif not r.in_gamut[i]:
            status = explanations[i]
        elif normalise == "per-colour":
            status = "Optimised!"
        else:
            status = "ok"
        rows.append({
            "XYZ_displayed": shown_XYZ[i].tolist(),
            "XYZ_row": row_XYZ[i].tolist(),
            "rgb_unmapped": r.rgb_unmapped[i].tolist(),
            "rgb_linear": r.rgb_linear[i].tolist(),
            "rgb_encoded": r.rgb_encoded[i].tolist(),
            "codes": [int(c) for c in r.codes[i]],
            "in_gamut": bool(r.in_gamut[i]),
            "negative": negative[i],
            "over": over[i],
            "gamut_applied": None if r.in_gamut[i] else gamut,
            "explanation": explanations[i],
            "scale": float(scales[i]),
            "emitted_levels": emitted_levels[i].tolist(),
            "emitted_XYZ": emitted_XYZ[i].tolist(),
            "status": status,
        })
    return rows


#: What the X Y Z row shows (``XYZ_row``), said once; the page shows the same as the row's tooltip.
XYZ_ROW_NOTES = {
    "cie": "CIE tristimulus values: one k = 100 / Σ ȳ for all three, so Y = 100 for the full spectrum",
    "spectra-exact": ("SPECTRA's step 1 (seed 002): one k per channel, X = 100 Σ f x̄ / (f_max Σ x̄) and so on, "
                      "so the full spectrum shows X = Y = Z = 100 as in SPECTRA; CIE's one k gives it "
                      "X 99.861, Z 99.709 (1931, 10 nm). x y, L*a*b* and λd are CIE's"),
}


#: How setting 4's light is extended for the lighting metrics, said once (the page shows it).
LIGHT_METRICS_NOTE = ("the explorer's lights have no energy outside 400–700 nm, so the light is taken as zero "
                      "from 380 to 400 and 700 to 780 nm (CIE 13.3 and CIE 224 need 380–780 nm)")


def light_metrics(wavelengths_nm, illuminant_levels) -> dict:
    """CCT, Duv, Ra, R9, Rf, Rg, LER and melanopic DER of setting 4's illuminant (plain floats).

    The page's light is linear between its bins over 400–700 nm and zero elsewhere
    (:data:`LIGHT_METRICS_NOTE`); :func:`spectrocolor.lighting.summary` computes the metrics on
    380–780 nm at 5 nm. NaN (undefined, e.g. no CCT for a single line) becomes None.

    Examples
    --------
    >>> metrics = light_metrics(grid(10.0), [30.0] * 31)   # equal energy over 400-700 nm
    >>> metrics["Ra"] > 80, metrics["note"].startswith("the explorer's lights")
    (True, True)
    """
    from ..lighting import summary

    fine = np.arange(380.0, 781.0, 5.0)
    inside = (fine >= wavelengths_nm[0]) & (fine <= wavelengths_nm[-1])
    values = np.zeros(fine.size)
    values[inside] = np.interp(fine[inside], wavelengths_nm, np.asarray(illuminant_levels, dtype=float))
    if not values.any():
        return {"note": "a light with no energy has no colour rendering"}
    metrics = summary(Spectrum(fine, values))
    plain = {k: (v if isinstance(v, bool) else _none_nan(v)) for k, v in metrics.items()}
    return {**plain, "note": LIGHT_METRICS_NOTE}


def metamer(step_nm, observer, target_levels, illuminant_levels=None) -> dict:
    """The smoothest distribution (0..full) with the same XYZ as ``target_levels``.

    Uses :func:`spectrocolor.smoothest_reflectance` with bounds 0 <= ρ <= 1 (van Trigt, seed 004)
    under E (or the given illuminant), on the page's grid.
    """
    wl = grid(step_nm)
    reference = _reference(wl, illuminant_levels)
    target = np.asarray(target_levels, dtype=float) / FULL_LEVEL
    XYZ = tristimulus(Spectrum(wl, target), observer=observer, illuminant=reference)
    result = smoothest_reflectance(XYZ, illuminant=reference, observer=observer,
                                      wavelengths=(START_NM, STOP_NM, float(step_nm)),
                                      bounds="unit")
    if not bool(result.certificate.converged):
        raise ColorimetryError(
            "target: the smoothest metamer of this distribution could not be found exactly "
            f"(residual {float(result.certificate.primal_residual):.3g} XYZ); try a finer step")
    rho = result.spectrum
    values = np.asarray(rho.values, dtype=float)
    if rho.wavelengths_nm.shape != wl.shape or not np.allclose(rho.wavelengths_nm, wl):
        values = rho.resample(wl).values
    levels = values * FULL_LEVEL
    got = tristimulus(Spectrum(wl, values), observer=observer, illuminant=reference)
    return {"levels": levels.tolist(), "XYZ_target": XYZ.tolist(), "XYZ_metamer": got.tolist()}


def level_step(wavelengths_nm: np.ndarray) -> float:
    """The smallest level change the page makes: 1 on SPECTRA's 31 bins, 0.1 on finer grids."""
    return 1.0 if len(wavelengths_nm) == 31 else 0.1


def quantise(levels, wavelengths_nm: np.ndarray) -> np.ndarray:
    """Levels rounded to the page's level step (SPECTRA: integers 0-30 at 10 nm)."""
    q = level_step(wavelengths_nm)
    return np.round(np.round(np.asarray(levels, dtype=float) / q) * q, 10)


def resolve(values, wavelengths_nm: np.ndarray) -> list:
    """A preset's levels on the grid: listed data (resampled if the grid is finer), or a
    named generated distribution (CIE D65/A scaled to a peak of 30 and rounded to the level
    step, E, a constant level)."""
    if isinstance(values, str):
        if values in ("D65", "A"):
            s = illuminant(values, wavelengths_nm).values
            return quantise(s * FULL_LEVEL / s.max(), wavelengths_nm).tolist()
        if values == "E":
            return [float(FULL_LEVEL)] * len(wavelengths_nm)
        raise ColorimetryError(
            f"values: unknown generated preset {values!r}; expected 'D65', 'A', 'E' or a list of "
            "31 levels at 10 nm")
    coarse = Spectrum(grid(10.0), np.asarray(values, dtype=float))
    return coarse.resample(wavelengths_nm, "linear").values.tolist()


def _moves(moves, wavelengths_nm: np.ndarray) -> list:
    """The seed's suggested edits of a setting-3 pair as [bin index, new left level] on the grid
    (on finer grids the bin nearest the 10 nm bin's wavelength)."""
    coarse = grid(10.0)
    return [[int(np.abs(wavelengths_nm - coarse[k]).argmin()), float(level)]
            for k, level in moves]


def presets(step_nm: float) -> dict:
    """All five settings' defaults on the grid of ``step_nm`` (see :mod:`.presets`)."""
    wl = grid(step_nm)

    def one(key, name, values):
        if values == "sunset":
            return {"key": key, "name": name, "cycle": [
                {"d": d, "levels": quantise(P.sunset(d, wl), wl).tolist()}
                for d in P.SUNSET_D]}
        if values == "level":
            return {"key": key, "name": name, "cycle": [
                {"level": v, "levels": [float(v)] * len(wl)} for v in range(FULL_LEVEL + 1)]}
        return {"key": key, "name": name, "levels": resolve(values, wl)}

    return {
        "wavelengths_nm": wl.tolist(),
        "full_level": FULL_LEVEL,
        "setting1": [one(*p) for p in P.SETTING1],
        "setting2": {"left": [one(*p) for p in P.SETTING2_LEFT],
                     "right": [one(*p) for p in P.SETTING2_RIGHT]},
        "setting3": [{"key": k, "name": n, "left": resolve(a, wl), "right": resolve(b, wl),
                      "moves": _moves(P.SETTING3_MOVES.get(k, ()), wl)}
                     for k, n, a, b in P.SETTING3],
        "setting4": {"illuminants": [one(*p) for p in P.SETTING4_ILLUMINANTS],
                     "samples": [{"key": k, "name": n, "left": resolve(a, wl),
                                  "right": resolve(b, wl)} for k, n, a, b in P.SETTING4_SAMPLES]},
        "setting5": [{"key": k, "name": n, "left": resolve(a, wl), "right": resolve(b, wl)}
                     for k, n, a, b in P.SETTING5],
        "setting5_additive": [{"key": k, "name": n, "left": resolve(a, wl), "right": resolve(b, wl)}
                              for k, n, a, b in P.SETTING5_ADDITIVE],
    }


def import_spectra(path, step_nm: float, method: str, scale: str, max_spectra: int = 4) -> dict:
    """Read a user's spectra (CSV/JSON) and resample them explicitly onto the page's grid.

    ``scale``: ``"peak"`` (each spectrum scaled so its peak in 400-700 nm is the full level),
    ``"unit"`` (values are factors 0-1) or ``"levels"`` (values are already 0-30). At most
    ``max_spectra`` spectra (the page lets the user choose which to edit), as one spectrum (K,)
    or a list (N, K).
    """
    s = read_spectra(path)
    if s.values.ndim > 2:
        raise SpectrumError(
            f"values: expected one spectrum or a list of spectra (N, K), got an array of shape "
            f"{s.values.shape}")
    count = 1 if s.values.ndim == 1 else s.values.shape[0]
    if count > max_spectra:
        raise SpectrumError(
            f"the file holds {count} spectra; the explorer reads at most {max_spectra} from "
            "one file: import a file with fewer")
    wl = grid(step_nm)
    lo, hi = float(s.wavelengths_nm[0]), float(s.wavelengths_nm[-1])
    if lo > START_NM or hi < STOP_NM:
        raise SpectrumError(
            f"file covers {lo:g}-{hi:g} nm; the explorer needs {START_NM:g}-{STOP_NM:g} nm and "
            "never extrapolates")
    r = s.resample(wl, method)
    values = np.atleast_2d(r.values)
    if scale == "peak":
        peak = values.max(axis=-1, keepdims=True)
        if np.any(peak <= 0):
            raise SpectrumError("a spectrum is zero everywhere in 400-700 nm; cannot scale")
        values = values / peak * FULL_LEVEL
    elif scale == "unit":
        values = values * FULL_LEVEL
    if values.min() < 0 or values.max() > FULL_LEVEL * (1 + 1e-9):
        raise SpectrumError(
            f"after scaling '{scale}' the levels run from {values.min():.4g} to "
            f"{values.max():.4g}; "
            f"they must lie in 0-{FULL_LEVEL} (choose scale 'peak' or 'unit')")
    names = list(s.names) if s.names else [f"spectrum {i + 1}" for i in range(len(values))]
    step = s.interval_nm
    grid_text = (f"{lo:g}-{hi:g} nm, {len(s.wavelengths_nm)} samples"
                 + (f" at {step:g} nm" if step is not None else ""))
    return {
        "names": names,
        "levels": np.clip(values, 0, FULL_LEVEL).tolist(),
        "note": f"read {len(values)} spectra on {grid_text}; resampled to {len(wl)} bins "
                f"({START_NM:g}-{STOP_NM:g} nm at {step_nm:g} nm) by {method} interpolation, "
                f"scale '{scale}'",
        "metadata": {k: str(v)[:300] for k, v in s.metadata.items()  # encoding, declared_* conditions
                     if k.startswith(("declared_", "encoding")) or k in ("format", "value_scale")},
    }


#: The unit of the page's values, as exported files declare it (the page's Load recognises it and
#: reads such a file as levels, whatever its "values as" choice).
EXPORT_UNIT = (f"SPECTRA levels 0-{FULL_LEVEL:g} ({FULL_LEVEL:g} = the full equal-energy spectrum, "
               "or reflectance/transmittance 1)")


def export_spectra(step_nm: float, names, spectra, path) -> None:
    """Write the page's distributions to ``path`` (CSV or JSON by its suffix), with their units.

    The CSV starts with a ``#`` comment line naming the units (the library's CSV reader skips
    comment lines; the wavelength column is ``wavelength_nm``); the JSON object carries a
    ``"units"`` entry beside ``wavelengths_nm`` and ``spectra`` (which
    :meth:`spectrocolor.Spectrum.from_dict` ignores). Names are written as given, so a file
    loaded back gives the same names.

    Parameters
    ----------
    step_nm : float
        The page's bin width, nm (the grid is 400-700 nm).
    names : sequence of str
        One name per distribution.
    spectra : sequence of sequence of float
        The distributions, levels 0..``FULL_LEVEL`` (unit :data:`EXPORT_UNIT`).
    path : pathlib.Path
        Output file, ``.csv`` or ``.json``; written atomically.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from spectrocolor import read_spectra
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "s.csv"
    ...     export_spectra(10.0, ["left straw"], [[15.0] * 31], path)
    ...     first = path.read_text().splitlines()[0]
    ...     back = read_spectra(path)
    >>> first.startswith("# values: SPECTRA levels 0-30"), back.names, float(back.values[0])
    (True, ('left straw',), 15.0)
    """
    import json

    from ..io.writers import spectra_to_csv
    from ..safe_write import write_text

    wl = grid(step_nm)
    s = Spectrum(wl, np.asarray(spectra, dtype=float), names=list(names))
    if Path(path).suffix.lower() == ".csv":
        text = f"# values: {EXPORT_UNIT}; wavelength_nm: nanometres\n" + spectra_to_csv(s)
    elif Path(path).suffix.lower() == ".json":
        text = json.dumps({**s.to_dict(), "units": {"wavelengths_nm": "nm", "values": EXPORT_UNIT}}, indent=1)
    else:
        write_spectra(s, path)
        return
    write_text(Path(path), text)
