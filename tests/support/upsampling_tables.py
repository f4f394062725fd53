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


@cache
def wide_table(space: str, resolution: int = 17):
    """A wide-gamut table at the default resolution (17 nodes per axis): Rec. 2020 (694 nodes
    moved; ~50 s to build on a loaded 2-core machine), Display P3 or Adobe RGB (84 moved)."""
    return upsampling_table(space, "D65", resolution=resolution, measure_excess=False)
