"""spectrocolor: spectra into colour, exactly.

The public names below are loaded lazily, so ``import spectrocolor`` costs only what
the names you use need (the core needs NumPy and SciPy; plotting, images, the app and
dask are optional extras that are imported only by the functions that use them).
"""

from __future__ import annotations

import importlib

from ._version import __version__ as __version__

# public name -> module (relative to this package) that defines it
_PUBLIC: dict[str, str] = {
    # spectra
    "Spectrum": "spectrum",
    "SpectrumError": "errors",
    "ColorimetryError": "errors",
    "BudgetError": "errors",
    # the memory budget every outside size is checked against
    "memory_budget": "budget",
    "DEFAULT_MEMORY_BUDGET": "budget",
    "parse_size": "budget",
    "claimed_bytes": "budget",
    "check_bytes": "budget",
    "check_file_claim": "budget",
    "block_bytes": "budget",
    "wavelength_grid": "spectrum",
    "read_spectra": "io",
    "write_spectra": "io",
    "parse_spectra": "io",
    "sample_data": "samples",
    "sample_data_names": "samples",
    # standard data
    "observer": "observers",
    "observer_names": "observers",
    "illuminant": "illuminants",
    "illuminant_names": "illuminants",
    "canonical_illuminant": "illuminants",
    "illuminant_label": "illuminants",
    "Illuminant": "illuminants",
    "resolve_illuminant": "illuminants",
    "Observer": "observers",
    "resolve_observer": "observers",
    "DEFAULT_ILLUMINANT": "illuminants",
    "DEFAULT_OBSERVER": "observers",
    "Registry": "registry",
    "SUMMATION_METHODS": "colorimetry",
    "ILLUMINANTS": "illuminants",
    "LIGHT_KINDS": "illuminants",
    "LightKind": "illuminants",
    "OBSERVERS": "observers",
    "GAMUT_STRATEGIES": "display.gamut",
    "NORMALISATIONS": "display.normalise",
    "ADAPTATION_METHODS": "display.adaptation",
    "RGB_SPACES": "display.spaces",
    "TRANSFERS": "display.transfer",
    "blackbody": "radiators",
    "daylight": "radiators",
    "daylight_xy": "radiators",
    # colorimetry
    "weights": "colorimetry",
    "tristimulus": "colorimetry",
    "white_point": "colorimetry",
    "cone_fundamentals": "cones",
    "cone_responses": "cones",
    "xy": "coordinates",
    "xyY": "coordinates",
    "XYZ_from_xyY": "coordinates",
    "uv_1960": "coordinates",
    "uv_1976": "coordinates",
    "xy_from_uv_1976": "coordinates",
    "xy_from_uv_1960": "coordinates",
    "lab": "coordinates",
    "XYZ_from_lab": "coordinates",
    "lch": "coordinates",
    "lab_from_lch": "coordinates",
    "delta_e_76": "differences",
    "delta_e_2000": "differences",
    # chromaticity
    "spectral_locus": "chromaticity",
    "SpectralLocus": "chromaticity",
    "dominant_wavelength": "chromaticity",
    "DominantWavelength": "chromaticity",
    "colorimetric_purity": "chromaticity",
    "cct": "temperature",
    "CCT": "temperature",
    "xy_from_cct": "temperature",
    # reflectance recovery (smoothest reflectance, optimal colours, metamers)
    "smoothest_reflectance": "recovery.smoothest",
    "SmoothestResult": "recovery.smoothest",
    "object_colour_membership": "recovery.optimal",
    "optimal_colours": "recovery.optimal",
    "macadam_limits": "recovery.optimal",
    "fundamental_metamer": "recovery.metamerism",
    "metameric_black": "recovery.metamerism",
    "cohen_projector": "recovery.metamerism",
    "metamerism_index": "recovery.metamerism",
    "colour_shift": "recovery.metamerism",
    "domain_of_validity": "recovery.validity",
    "DomainOfValidity": "recovery.validity",
    "metamer_mismatch_region": "recovery.metamers",
    "MismatchRegion": "recovery.metamers",
    "smoothest_metamer": "recovery.metamers",
    "most_different_metamer": "recovery.metamers",
    # display
    "RGBSpace": "display.spaces",
    "rgb_space": "display.spaces",
    "rgb_space_names": "display.spaces",
    "render": "display.render",
    "Rendering": "display.render",
    "adapt": "display.adaptation",
    "adaptation_matrix": "display.adaptation",
    "max_object_rgb": "display.normalise",
    "white_scale": "display.normalise",
    "transfer": "display.transfer",
    "transfer_names": "display.transfer",
    "spectra_excitation_table": "display.transfer",
    "to_codes": "display.transfer",
    "from_codes": "display.transfer",
    "primary_emission": "display_emission",
    "emitted_light": "display_emission",
    "excitation_function": "display_emission",
    # mixing (seed 002: superposition, filters in series, complementary distributions)
    "additive_mix": "mixing",
    "subtractive_mix": "mixing",
    "complement": "mixing",
    # pictures and plots (Pillow / matplotlib imported only when called)
    "wavelength_tint": "pictures",
    "write_swatches": "pictures",
    "write_strip": "pictures",
    "chromaticity_diagram": "plot",
    "spectrum_plot": "plot",
    # spectral images and reports (images: Pillow/tifffile/xarray/dask imported only when used)
    "read_cube": "images",
    "SpectralCube": "images",
    "cube_to_xyz": "images",
    "cube_to_lab": "images",
    "cube_to_rgb": "images",
    "write_image": "pictures",
    "measurement_report": "report",
    "MeasurementReport": "report",
    "write_report": "report",
    # thin films
    "Medium": "thinfilm.media",
    "medium": "thinfilm.media",
    "FilmOptics": "thinfilm.optics",
    "two_beam_reflectance": "thinfilm.optics",
    "optical_path_difference": "thinfilm.optics",
    "thin_film": "thinfilm.optics",
    "thin_film_reflectance": "thinfilm.optics",
    "stack_optics": "thinfilm.optics",
    "soap_film": "thinfilm.films",
    "oil_on_water": "thinfilm.films",
    "film_on_glass": "thinfilm.films",
    "film_colours": "thinfilm.colour",
    "FilmColours": "thinfilm.colour",
    "colour_table": "thinfilm.maps",
    "render_thickness_map": "thinfilm.maps",
    "zawischa_strip": "thinfilm.zawischa",
    # ASTM E308 / E2022 weights
    "astm_e308_weights": "astm_e308",
    "astm_e308_table6_weights": "astm_e308",
    "bandpass_correction": "bandpass",
    # spectral upsampling: RGB images to exact reflectances by table
    "upsampling_table": "upsampling",
    "UpsamplingTable": "upsampling",
    "upsample": "upsampling",
    # light sources: colour rendering, fidelity, photometry, α-opic (matplotlib only for graphics)
    "colour_rendering_index": "lighting.cri",
    "CRI": "lighting.cri",
    "colour_fidelity": "lighting.fidelity",
    "Fidelity": "lighting.fidelity",
    "luminous_quantity": "lighting.photometry",
    "luminous_efficacy_of_radiation": "lighting.photometry",
    "alpha_opic": "lighting.alpha_opic",
    "AlphaOpic": "lighting.alpha_opic",
    "light_report": "lighting.summary",
    "LightReport": "lighting.summary",
    "write_light_report": "lighting.report",
    # the SPECTRA explorer as a notebook widget (anywidget and FastAPI imported only when called)
    "explore": "app.notebook_widget",
    "explore_lab": "app.notebook_labs",  # a lab of the explorer, likewise
}


def __getattr__(name: str):
    module = _PUBLIC.get(name)
    if module is None:
        raise AttributeError(f"module 'spectrocolor' has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted([*globals(), *_PUBLIC])


__all__ = sorted(_PUBLIC)
