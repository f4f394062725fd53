"""The one "cannot be reproduced" line (seed 002, STEP 3 and question 4) for every interface."""

from __future__ import annotations

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.display.explain import GAMUT_ACTIONS, explain, out_of_gamut_channels
from spectrocolor.display.gamut import GAMUT_STRATEGIES


def test_every_registered_strategy_says_what_it_does():
    assert set(GAMUT_ACTIONS) == set(GAMUT_STRATEGIES)


@pytest.mark.parametrize("gamut", list(GAMUT_ACTIONS))
def test_the_line_names_the_channels_and_the_strategy(gamut):
    # sRGB: XYZ (1, 60, 5) drives R and B negative and G above 1; (20, 21, 22) is in gamut
    r = sc.render([[20.0, 21.0, 22.0], [1.0, 60.0, 5.0]], "sRGB", gamut=gamut)
    assert out_of_gamut_channels(r) == ([[], ["R", "B"]], [[], ["G"]])
    assert r.explain() == explain(r) == [
        "in gamut", f"cannot be reproduced (R, B negative; G above 1): {GAMUT_ACTIONS[gamut]}"]


def test_a_batch_keeps_one_line_per_colour():
    r = sc.render(np.full((2, 3, 3), 20.0), "sRGB")
    assert explain(r) == ["in gamut"] * 6


def test_a_colour_whose_display_luminance_is_not_positive_is_said_to_leave_black():
    """A violet far outside the gamut, adapted in display RGB, can have Y < 0 on the display:
    keeping its luminance leaves black, and the message says why (not a bare black patch)."""
    from spectrocolor.display.render import render

    space = sc.rgb_space("sRGB")
    rgb_unmapped = np.array([0.2, -0.9, 1.0])  # Y = 0.2126·0.2 − 0.7152·0.9 + 0.0722 < 0
    XYZ = np.asarray(space.matrix_to_XYZ) @ rgb_unmapped * 100 / space.white_XYZ[1]
    assert XYZ[1] < 0
    dark, = explain(render(XYZ[None], "sRGB", gamut="desaturate"))
    assert dark.endswith("its luminance on this display is not positive, so that leaves black")
    clipped, = explain(render(XYZ[None], "sRGB", gamut="clip"))
    assert "not positive" not in clipped
