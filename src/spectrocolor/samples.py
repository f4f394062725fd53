"""The spectra bundled with the package, by name, from a clone or an installed wheel alike.

The tables are read from the package's own ``data`` folder through :mod:`importlib.resources`,
so ``sc.sample_data("colorchecker")`` works wherever spectrocolor is installed (a path such as
``src/spectrocolor/data/…`` exists only in the clone). ``data/PROVENANCE.md`` gives each table's
source. The standard tables have accessors of their own: :func:`spectrocolor.illuminant` for
the CIE illuminants and :func:`spectrocolor.observer` for the colour-matching functions.
"""

from __future__ import annotations

from importlib import resources

from .errors import SpectrumError
from .io import parse_spectra
from .spectrum import Spectrum

# This module is not named ``sample_data``: importing a submodule binds it on the package, so a
# module ``spectrocolor.sample_data`` would replace the function ``sc.sample_data`` after
# ``import spectrocolor.sample_data``.

__all__ = ["SAMPLE_DATA", "sample_data", "sample_data_names"]

#: Name -> (file in the package's ``data`` folder, what it holds). ``sample_data`` reads these.
SAMPLE_DATA: dict[str, tuple[str, str]] = {
    "colorchecker": (
        "reflectances_colorchecker_babel.csv",
        "ColorChecker Classic, 24 patches (dark_skin … black), spectral reflectance factors 0-1, "
        "380-730 nm, 10 nm (BabelColor average, D. Pascale 2012)",
    ),
    "cie_tcs": (
        "reflectances_cie_tcs.csv",
        "CIE 13.3-1995 test colour samples TCS01-TCS14, spectral radiance factors 0-1, 360-830 nm, 5 nm",
    ),
    "cie_ces": (
        "lighting/ces_cie224_1nm.csv",
        "CIE 224:2017 / ANSI/IES TM-30 colour evaluation samples CES01-CES99, spectral reflectance "
        "factors 0-1, 380-780 nm, 1 nm",
    ),
    "crt_primaries": (
        "display_crt_brainard1997.csv",
        "a typical CRT's red, green and blue phosphors (P22), relative spectral radiance at full drive, "
        "380-780 nm, 5 nm (Brainard 1997)",
    ),
    "alpha_opic_action_spectra": (
        "lighting/cie_s026_alpha_opic.csv",
        "CIE S 026 alpha-opic action spectra s_sc, s_mc, s_lc, s_rh, s_mel, 380-780 nm, 1 nm",
    ),
}


def sample_data_names() -> list[str]:
    """The names :func:`sample_data` accepts, in a stable order.

    Returns
    -------
    list of str
        ``["colorchecker", "cie_tcs", "cie_ces", "crt_primaries", "alpha_opic_action_spectra"]``.

    Examples
    --------
    >>> import spectrocolor as sc
    >>> sc.sample_data_names()[:2]
    ['colorchecker', 'cie_tcs']
    """
    return list(SAMPLE_DATA)


def sample_data(name: str) -> Spectrum:
    """A bundled set of spectra by name: the ColorChecker, the CIE test colours, and more.

    Parameters
    ----------
    name : str
        One of :func:`sample_data_names` (case and ``-``/``_``/spaces ignored):

        * ``"colorchecker"`` — ColorChecker Classic, 24 patches, reflectance 0-1, 380-730 nm, 10 nm;
        * ``"cie_tcs"`` — CIE 13.3 test colour samples TCS01-TCS14, 360-830 nm, 5 nm;
        * ``"cie_ces"`` — CIE 224 / TM-30 colour evaluation samples CES01-CES99, 380-780 nm, 1 nm;
        * ``"crt_primaries"`` — a typical CRT's R, G, B phosphor spectra, 380-780 nm, 5 nm;
        * ``"alpha_opic_action_spectra"`` — the five CIE S 026 action spectra, 380-780 nm, 1 nm.

    Returns
    -------
    Spectrum
        ``(N, K)`` spectra with their names; ``metadata["sample_data"]`` is ``name`` and
        ``metadata["description"]`` says what the table holds and where it comes from.

    Raises
    ------
    SpectrumError
        For a name that is not bundled (the message lists the accepted names).

    See Also
    --------
    spectrocolor.read_spectra : your own measurement files.
    spectrocolor.illuminant, spectrocolor.observer : the CIE illuminants and observers.

    Examples
    --------
    >>> import spectrocolor as sc
    >>> tiles = sc.sample_data("colorchecker")
    >>> tiles.values.shape, tiles.names[0], float(tiles.wavelengths_nm[0])
    ((24, 36), 'dark_skin', 380.0)
    >>> XYZ100 = sc.tristimulus(tiles, observer="1931", illuminant="D65")
    >>> round(float(XYZ100[18, 1]), 1)  # the white patch
    91.2
    >>> sc.sample_data("TCS")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.SpectrumError: no sample data named 'TCS'; the bundled spectra are: colorchecker, cie_tcs, ...
    """
    if not isinstance(name, str):
        raise SpectrumError(f"sample_data: name must be a str, got {type(name).__name__}")
    key = "_".join(name.strip().lower().replace("-", " ").replace("_", " ").split())
    if key not in SAMPLE_DATA:
        raise SpectrumError(
            f"no sample data named {name!r}; the bundled spectra are: {', '.join(SAMPLE_DATA)}"
        )
    file, description = SAMPLE_DATA[key]
    resource = resources.files(__package__).joinpath("data", *file.split("/"))
    spectra = parse_spectra(resource.read_text(encoding="utf-8"), file, percent=False)
    return Spectrum(
        spectra.wavelengths_nm,
        spectra.values,
        spectra.names,
        {**spectra.metadata, "sample_data": key, "description": description},
    )
