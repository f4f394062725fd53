"""Small upsampling tables shared by the upsampling tests (built once per session)."""

from functools import cache

from spectrocolor.upsampling import upsampling_table


@cache
def srgb_table():
    """sRGB under D65, 9 nodes per axis (every node exact)."""
    return upsampling_table("sRGB", "D65", resolution=9)


@cache
def rec2020_table():
    """Rec. 2020 under D65, 5 nodes per axis (its blue corner lies outside the solid)."""
    return upsampling_table("Rec. 2020", "D65", resolution=5)
