"""Options every command shares: one wording, one default and one vocabulary per concept.

``--illuminant`` takes the library's illuminant vocabulary (:func:`spectrocolor.canonical_illuminant`)
and, where a command reads lights, ``none``: the one way to say "these spectra are lights". The
defaults are the library's (:data:`spectrocolor.DEFAULT_ILLUMINANT`,
:data:`spectrocolor.DEFAULT_OBSERVER`, :data:`DEFAULT_GAMUT`), and the choices and help texts of
``--observer``, ``--gamut``, ``--method``, ``--normalise`` and ``--adapt`` come from the registries,
read when the parser is built (each run), so a new entry there is a new choice here.
"""

from __future__ import annotations

import argparse

from ..display.adaptation import ADAPTATION_METHODS
from ..display.gamut import DEFAULT_GAMUT, GAMUT_STRATEGIES
from ..display.normalise import NORMALISATIONS
from ..errors import ColorimetryError
from ..illuminants import DEFAULT_ILLUMINANT, LIGHT_KINDS, canonical_illuminant
from ..observers import OBSERVERS, canonical_observer_name


def illuminant_forms(cie_names: str = "D65, A, C, D50, FL11, LED-B1, …") -> str:
    """How a light is written on the command line, for ``--illuminant`` and ``--to`` help.

    The ``kind:T`` forms are read from :data:`~spectrocolor.illuminants.LIGHT_KINDS` when the
    parser is built, so a registered kind is listed.

    Parameters
    ----------
    cie_names : str
        The CIE names given as examples.

    Returns
    -------
    str

    Examples
    --------
    >>> illuminant_forms()
    'a CIE name (D65, A, C, D50, FL11, LED-B1, …), blackbody:T or D:T (T in kelvin)'
    """
    forms = [f"{LIGHT_KINDS.get(name).prefix}:T" for name in LIGHT_KINDS]
    listed = forms[0] if len(forms) == 1 else f"{', '.join(forms[:-1])} or {forms[-1]}"
    return f"a CIE name ({cie_names}), {listed} (T in kelvin)"


#: ``--illuminant``/``--observer`` value (and default, for commands that read a measurement file)
#: meaning "what the file declares" (:data:`spectrocolor.io.conditions.DECLARED`).
DECLARED = "declared"
#: How the ``declared`` default reads in the help.
_DECLARED_HELP = "{}, or what the file declares (e.g. ColorPort's MEASUREMENT_SOURCE)"


def _illuminant_type(lights: bool, declared: bool = False):
    def parse(text: str):
        if declared and text.strip().lower() == DECLARED:
            return DECLARED
        if text.strip().lower() == "none":
            if lights:
                return None
            raise argparse.ArgumentTypeError("this command needs a light on the samples; 'none' is for lights")
        try:
            return canonical_illuminant(text)
        except ColorimetryError as exc:
            raise argparse.ArgumentTypeError(str(exc).removeprefix("illuminant: ")) from None

    parse.__name__ = "illuminant"
    return parse


def add_illuminant(parser: argparse.ArgumentParser, *, lights: bool = False, default: str = DEFAULT_ILLUMINANT,
                   what: str = "the samples", declared: bool = False) -> None:
    """``--illuminant``: the light on ``what``; with ``lights``, ``none`` means the spectra are lights.

    With ``declared`` (commands that read a measurement file) the default is ``declared``: the
    illuminant the file declares, else ``default``; the value ``declared`` may also be given.
    """
    help_text = f"the light on {what}: {illuminant_forms()}"
    if lights:
        help_text += "; 'none' when the file holds lights (sources) rather than reflectances"
    if declared:
        help_text += f"; '{DECLARED}': what the file declares, else {default}"
    shown = _DECLARED_HELP.format(default) if declared else default
    parser.add_argument("--illuminant", type=_illuminant_type(lights, declared),
                        default=DECLARED if declared else default, help=f"{help_text} (default {shown})")


def _observer_type(text: str) -> str:
    try:
        return canonical_observer_name(text)
    except ColorimetryError as exc:
        raise argparse.ArgumentTypeError(str(exc).removeprefix("observer: ")) from None


_observer_type.__name__ = "observer"


def _declared_or_observer(text: str) -> str:
    return DECLARED if text.strip().lower() == DECLARED else _observer_type(text)


_declared_or_observer.__name__ = "observer"


def add_observer(parser: argparse.ArgumentParser, *, declared: bool = False) -> None:
    """``--observer``: a shipped observer or alias (default CIE 1931 2°; with ``declared``, what
    the measurement file declares, else CIE 1931 2°)."""
    default = _DECLARED_HELP.format("1931") if declared else "1931"
    parser.add_argument("--observer", type=_declared_or_observer if declared else _observer_type,
                        default=DECLARED if declared else "1931",
                        help="standard observer: " + "; ".join(f"{n} ({OBSERVERS.description(n)})"
                                                               for n in ("CIE 1931 2°", "CIE 1964 10°"))
                        + "; also 2015-2, 2015-10; aliases 1931, 1964, 2deg, 10deg"
                        + (f"; '{DECLARED}'" if declared else "") + f" (default {default})")


def add_gamut(parser: argparse.ArgumentParser, default: str = DEFAULT_GAMUT) -> None:
    """``--gamut``: the strategy for colours a display cannot show, from :data:`GAMUT_STRATEGIES`."""
    parser.add_argument("--gamut", choices=GAMUT_STRATEGIES.names(), default=default,
                        help=f"colours the display cannot show: {GAMUT_STRATEGIES.help()} (default {default})")


def adapt_choices() -> tuple[str, ...]:
    """``--adapt``'s choices: ``none`` and every transform of :data:`ADAPTATION_METHODS`."""
    return ("none", *ADAPTATION_METHODS.names())


def normalise_choices() -> tuple[str, ...]:
    """``--normalise``'s choices: the names of :data:`NORMALISATIONS`."""
    return NORMALISATIONS.names()


def _encoding_type(text: str) -> str:
    from ..errors import SpectrumError
    from ..io.text import codec_name

    try:
        return codec_name(text)
    except SpectrumError as exc:
        raise argparse.ArgumentTypeError(str(exc).removeprefix("encoding: ")) from None


_encoding_type.__name__ = "encoding"


def add_encoding(parser: argparse.ArgumentParser) -> None:
    """``--encoding``: the spectral file's text encoding, overriding detection (every command that reads one)."""
    parser.add_argument(
        "--encoding", type=_encoding_type, default=None,
        help="the file's text encoding, e.g. cp1252, latin-1, utf-16 (default: detected: a byte-order mark, "
             "else UTF-8, else cp1252 when every byte is a printable cp1252 character; the encoding used is "
             "in the result's metadata)")
