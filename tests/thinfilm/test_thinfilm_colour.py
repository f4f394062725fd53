"""Thin-film colours: seed 000's strip, film colours, thickness maps and the CLI."""

from __future__ import annotations

import csv

import numpy as np
import pytest

import spectrocolor.cli as cli
from spectrocolor.errors import ColorimetryError, SpectrumError
from spectrocolor.thinfilm import maps
from spectrocolor.thinfilm.colour import film_colours
from spectrocolor.thinfilm.films import soap_film
from spectrocolor.thinfilm.zawischa import zawischa_strip


def seed000_reference():
    """Seed 000's algorithm written out from its text (eqs. 7-24), independent of the package.

    CMFs: colour-science's CIE 1931 table at 5 nm (the seed's own source is the same CIE table).
    The Fortran's ordering bug (correcting channels already gamma-encoded) is not reproduced:
    eqs. (20)-(21) are applied in linear light to every negative channel, as the text says.
    """
    import colour

    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    wl_um = np.arange(360, 831, 5) / 1000.0
    xbar = np.array([cmfs[w * 1000] for w in wl_um])  # (95, 3)
    alf, T, lam0, beta = 14.388e3, 6504.0, 0.560, 0.95
    S = (lam0 / wl_um) ** 5 * (np.exp(alf / (T * lam0)) - 1) / (np.exp(alf / (T * wl_um)) - 1)
    s = 0.005 * np.arange(1, 1001)  # µm, the Fortran's ds
    refl = 1 + beta**2 - 2 * beta * np.cos(s[:, None] * 2 * np.pi / wl_um)
    XYZ = (refl * S) @ xbar  # eq. (9)

    prim = np.array([[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]])
    xyz_p = np.column_stack([prim[:, 0], prim[:, 1], 1 - prim.sum(1)]).T  # columns R, G, B
    xw, yw = 0.3127, 0.3290
    u = np.linalg.solve(xyz_p, [xw / yw, 1.0, (1 - xw - yw) / yw])  # eqs. (13)-(15)
    primaries = xyz_p * u  # eq. (13)
    to_rgb = np.linalg.inv(primaries)  # eqs. (16)-(19)
    rgb = XYZ @ to_rgb.T
    rgb /= rgb.max()  # global maximum of R, G, B
    Yc = primaries[1]
    Y = rgb @ Yc
    neg = rgb < 0
    factor = Y / (Y - np.where(neg, rgb, 0) @ Yc)  # eq. (21) for all negative channels
    rgb = np.where(neg, 0.0, rgb * factor[:, None])
    assert rgb.max() <= 1.0  # the series needs no clipping above 1
    enc = np.where(rgb <= 0.00304, 12.92 * rgb, 1.055 * rgb ** (1 / 2.4) - 0.055)  # (22)-(23)
    return 5.0 * np.arange(1, 1001), XYZ, np.rint(255 * enc).astype(int)  # eq. (24), rounded


def test_colour_science_cmfs_are_the_seed_tables():
    # spot values from the seed's Fortran data statements (CIE 1931, 5 nm)
    import colour

    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    np.testing.assert_allclose(cmfs[360], [0.1299e-3, 0.3917e-5, 0.6061e-3], rtol=1e-4)
    np.testing.assert_allclose(cmfs[555], [0.512050, 1.0, 0.575e-2], rtol=1e-4)
    np.testing.assert_allclose(cmfs[830], [0.125114e-5, 0.451810e-6, 0.0], atol=1e-10)


def test_zawischa_strip_matches_independent_reimplementation():
    opd, XYZ_ref, codes_ref = seed000_reference()
    strip = zawischa_strip()
    # exact: optical path differences are whole nanometres (5 · i): exact
    np.testing.assert_array_equal(strip.opd_nm, opd)
    # XYZ agree up to the arbitrary constant C of eq. (8)
    ratio = strip.colours.XYZ100 / XYZ_ref
    np.testing.assert_allclose(ratio, ratio[0, 0], rtol=1e-9)
    x_ref = XYZ_ref[:, :2] / XYZ_ref.sum(1, keepdims=True)
    np.testing.assert_allclose(strip.colours.xy, x_ref, atol=1e-12)
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach
    np.testing.assert_array_equal(strip.colours.rgb8, codes_ref)
    np.testing.assert_array_equal(strip.tick_columns, np.arange(99, 1000, 100))


def test_zawischa_cli_writes_strip_and_csv(tmp_path, monkeypatch):
    from PIL import Image

    monkeypatch.setattr(cli, "COMMAND_MODULES", ("thinfilm",))
    out, table = tmp_path / "strip.png", tmp_path / "strip.csv"
    assert cli.main(["thinfilm", "zawischa", "--out", str(out), "--csv", str(table)]) == 0
    opd, _, codes = seed000_reference()
    img = np.asarray(Image.open(out).convert("RGB"))
    assert img.shape == (80, 1000, 3)
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach
    np.testing.assert_array_equal(img[:70], np.broadcast_to(codes, (70, 1000, 3)))
    # tick band: white at 500 nm (column 99 and neighbours), black elsewhere
    assert np.all(img[70:, 98:101] == 255) and np.all(img[70:, 50] == 0)
    assert np.all(img[70:, 998:] == 255)
    with table.open() as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["opd_nm", "X", "Y", "Z", "x", "y", "r8", "g8", "b8"]
    assert len(rows) == 1001
    data = np.array(rows[1:], dtype=float)
    # exact: optical path differences are whole nanometres (5 · i): exact
    np.testing.assert_array_equal(data[:, 0], opd)
    np.testing.assert_array_equal(data[:, 6:].astype(int), codes)
    np.testing.assert_allclose(data[:, 4:6], data[:, 1:3] / data[:, 1:4].sum(1, keepdims=True),
                               atol=1e-9)


def test_perfect_reflector_exposure_matches_colour_science_tristimulus():
    import colour

    wl = np.arange(380.0, 781.0, 5.0)
    optics = soap_film(np.array([0.0, 120.0, 300.0, 550.0]), wl)
    ours = film_colours(optics, illuminant="D65", observer="1964", exposure="perfect-reflector")
    shape = colour.SpectralShape(380, 780, 5)
    cmfs = colour.MSDS_CMFS["CIE 1964 10 Degree Standard Observer"].copy().align(shape)
    d65 = colour.SDS_ILLUMINANTS["D65"].copy().align(shape)
    for i in range(4):
        sd = colour.SpectralDistribution(dict(zip(wl, optics.reflectance[i], strict=True)))
        ref = colour.sd_to_XYZ(sd, cmfs, d65, method="Integration")
        np.testing.assert_allclose(ours.XYZ100[i], ref, rtol=1e-9, atol=1e-12)
    # a perfect reflector maps to Y = 100 = the display white at gain 1
    assert ours.rendering.normalise == "none"


def test_film_colours_rules_and_errors():
    wl = np.arange(380.0, 781.0, 5.0)
    optics = soap_film(np.linspace(0, 1000, 11), wl)
    out = film_colours(optics)  # defaults: blackbody 6504 K, 1931, global-max
    assert out.illuminant == "blackbody 6504 K" and out.exposure == "global-max"
    assert out.rendering.rgb_unmapped.max() == pytest.approx(1.0)
    with pytest.raises(ColorimetryError, match="gain"):
        film_colours(optics, gain=2.0)
    with pytest.raises(ColorimetryError, match="exposure"):
        film_colours(optics, exposure="auto")
    with pytest.raises(ColorimetryError, match="blackbody"):
        film_colours(optics, illuminant="blackbody:hot")


# --- thickness maps ---------------------------------------------------------------------------


@pytest.fixture(scope="module")
def table():
    return maps.colour_table(soap_film, 1200.0, thickness_step_nm=0.5)


def test_table_lookup_equals_direct_rendering(table):
    d = np.array([[0.0, 100.0, 250.5], [600.0, 1199.5, np.nan]])
    img = maps.render_thickness_map(d, table, background=(7, 8, 9))
    wl = np.arange(380.0, 781.0, 5.0)
    direct = film_colours(soap_film(np.arange(0, 1200.5, 0.5), wl)).rgb8
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach
    np.testing.assert_array_equal(img[0, 0], direct[0])
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach
    np.testing.assert_array_equal(img[0, 1], direct[200])
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach
    np.testing.assert_array_equal(img[0, 2], direct[501])
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach
    np.testing.assert_array_equal(img[1, 1], direct[2399])
    np.testing.assert_array_equal(img[1, 2], [7, 8, 9])  # exact: the background codes given, set
    with pytest.raises(SpectrumError, match="0-1200 nm"):
        maps.render_thickness_map(np.array([[1300.0]]), table)


def test_angle_table_and_bubble():
    tab = maps.colour_table(soap_film, 600.0, thickness_step_nm=2.0, max_angle_deg=89.9,
                            angle_step_deg=10.0, exposure="perfect-reflector", gain=2.0)
    assert tab.rgb8.shape == (10, 301, 3)
    wl = np.arange(380.0, 781.0, 5.0)
    direct = film_colours(soap_film(np.array([300.0]), wl, angle_deg=40.0),
                          exposure="perfect-reflector", gain=2.0).rgb8[0]
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach
    np.testing.assert_array_equal(tab.lookup(np.array([300.0]), np.array([40.0]))[0], direct)
    thickness, angle = maps.bubble(64, top_thickness_nm=50, bottom_thickness_nm=500)
    assert np.isnan(thickness[0, 0]) and np.isnan(angle[0, 0])
    assert angle[32, 32] < 3.0 and np.nanmax(angle) > 75
    img = maps.render_thickness_map(thickness, tab, angle)
    assert img.shape == (64, 64, 3) and np.all(img[0, 0] == 0)


def _srgb_codes(rgb_linear):
    """IEC 61966-2-1 encoding and rounding to 8-bit codes, written out here."""
    x = np.asarray(rgb_linear, dtype=float)
    encoded = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.maximum(x, 0) ** (1 / 2.4) - 0.055)
    return np.rint(encoded * 255).astype(np.uint8)


def test_angle_lookup_interpolates_in_linear_light_between_grid_angles():
    options = dict(exposure="perfect-reflector", gain=2.0)
    tab = maps.colour_table(soap_film, 600.0, thickness_step_nm=2.0, max_angle_deg=89.9,
                            angle_step_deg=10.0, **options)
    wl = np.arange(380.0, 781.0, 5.0)
    # (thickness, angle, lower grid angle, upper grid angle); the last grid angle is 89.9°
    cases = [(300.0, 45.0, 40.0, 50.0), (120.0, 72.5, 70.0, 80.0), (550.0, 85.0, 80.0, 89.9),
             (430.0, 89.9, 80.0, 89.9)]
    for d, a, a0, a1 in cases:
        lin0, lin1 = (film_colours(soap_film(np.array([d]), wl, angle_deg=g), **options)
                      .rendering.rgb_linear[0] for g in (a0, a1))
        w = (a - a0) / (a1 - a0)
        expected = _srgb_codes((1 - w) * lin0 + w * lin1)
        got = tab.lookup(np.array([d]), np.array([a]))[0]
        # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
        # reach
        np.testing.assert_array_equal(got, expected, err_msg=f"{d} nm at {a}°")
    # the mixture is not just one of the rows (the test can tell interpolation from nearest)
    row40, row50 = tab.rgb8[4, 150], tab.rgb8[5, 150]
    mid = tab.lookup(np.array([300.0]), np.array([45.0]))[0]
    # exact: integer codes; the test asserts that they differ
    assert not np.array_equal(mid, row40) and not np.array_equal(mid, row50)
    with pytest.raises(SpectrumError, match="0-89.9°"):
        tab.lookup(np.array([300.0]), np.array([89.95]))
    with pytest.raises(SpectrumError, match="angle_deg"):
        tab.lookup(np.array([300.0]), np.array([-1.0]))


def test_single_angle_lookup_is_the_nearest_entry_bit_for_bit(table):
    rng = np.random.default_rng(7)
    d = rng.uniform(0, 1200.0, (40, 30)).astype(np.float32)
    d[::7, ::5] = np.nan
    img = table.lookup(d, background=(1, 2, 3))
    film = ~np.isnan(d)
    nearest = np.rint(d[film].astype(np.float64) / 0.5).astype(int)
    # exact: codes picked from the table: no arithmetic
    np.testing.assert_array_equal(img[film], table.rgb8[0, nearest])
    assert np.all(img[~film] == [1, 2, 3])
    assert table.rgb_linear is None  # one-angle tables keep only their codes


def test_draining_film_profile():
    d = maps.draining_film(4, 100, time_s=100.0, film_height_m=0.01)
    x = (np.arange(100) + 0.5) / 100 * 0.01
    np.testing.assert_allclose(d[:, 0], 2 * np.sqrt(1e-3 * x / (1000 * 9.80665 * 100)) * 1e9,
                               rtol=1e-6)
    later = maps.draining_film(4, 100, time_s=400.0, film_height_m=0.01)
    np.testing.assert_allclose(later, d / 2, rtol=1e-6)  # h ∝ t^(-1/2)


def test_read_thickness_maps(tmp_path):
    from PIL import Image

    counts = (np.arange(12, dtype=np.uint16).reshape(3, 4) * 5000).astype(np.uint16)
    png = tmp_path / "t.png"
    Image.fromarray(counts).save(png)
    np.testing.assert_allclose(maps.read_thickness_map(png, nm_per_count=0.02), counts * 0.02,
                               rtol=1e-6)
    with pytest.raises(SpectrumError, match="nm_per_count"):
        maps.read_thickness_map(png)
    npy = tmp_path / "t.npy"
    np.save(npy, np.ones((2, 2)) * 123.0)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    assert maps.read_thickness_map(npy)[0, 0] == 123.0


def test_draining_film_gif(tmp_path, table):
    from PIL import Image

    path = maps.draining_film_gif(tmp_path / "drain.gif", table, 32, 24,
                                  times_s=[3000.0, 6000.0, 12000.0], film_height_m=0.01)
    with Image.open(path) as gif:
        assert gif.n_frames == 3


def test_cli_strip_map_and_errors(tmp_path, monkeypatch, capsys):
    from PIL import Image

    monkeypatch.setattr(cli, "COMMAND_MODULES", ("thinfilm",))
    strip = tmp_path / "oil.png"
    assert cli.main(["thinfilm", "strip", "--film", "oil", "--substrate", "water",
                     "--illuminant", "D65", "--columns", "200", "--out", str(strip)]) == 0
    assert np.asarray(Image.open(strip)).shape == (80, 200, 3)
    image = tmp_path / "wedge.png"
    assert cli.main(["thinfilm", "map", "--kind", "wedge", "--width", "64", "--height", "8",
                     "--max-thickness", "800", "--out", str(image)]) == 0
    assert np.asarray(Image.open(image)).shape == (8, 64, 3)
    assert cli.main(["thinfilm", "strip", "--film", "unobtainium", "--out", str(strip),
                     "--force"]) == 2
    assert "unknown medium" in capsys.readouterr().err


def test_cli_rejects_bad_sizes_layers_and_plot_files(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(cli, "COMMAND_MODULES", ("thinfilm",))
    out = tmp_path / "x.png"
    cases = [
        (["zawischa", "--out", str(out), "--locus", str(tmp_path / "l.txt")], "--locus must end in"),
        (["locus", "--out", str(tmp_path / "l.txt")], "--out must end in"),
        (["strip", "--under", "water:-5", "--out", str(out)], "must be a finite number of nm >= 0"),
        (["strip", "--columns", "10000000", "--out", str(out)], "at most 100000 columns"),
        (["map", "--width", "100000", "--height", "100000", "--out", str(out)], "1-16384 pixels"),
    ]
    for argv, message in cases:
        assert cli.main(["thinfilm", *argv]) == 2, argv
        err = capsys.readouterr().err
        assert message in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists()


def test_zawischa_strip_needs_columns():
    for columns in (0, -3, 2.5):
        with pytest.raises(SpectrumError, match="columns"):
            zawischa_strip(columns=columns)


# --- tables computed in blocks (issue 25) ---------------------------------------------------------


def test_a_table_computed_in_blocks_is_the_table_computed_at_once():
    options = dict(max_angle_deg=60.0, angle_step_deg=20.0, thickness_step_nm=2.0)
    whole = maps.colour_table(soap_film, 900.0, memory_budget="64GiB", **options)
    blocks = maps.colour_table(soap_film, 900.0, memory_budget="1MiB", **options)  # 64 KiB blocks: 6 thicknesses
    # exact: 8-bit codes rounded from floats that agree to ~1e-14 move only at a half-code tie
    np.testing.assert_array_equal(blocks.rgb8, whole.rgb8)
    # each entry's XYZ is a sum of K = 81 products; a matrix product split into other batches may
    # add them in another order: at most K rounding errors of the largest value (eps each)
    K = 81
    bound = K * np.finfo(float).eps * np.abs(whole.rgb_linear).max()
    np.testing.assert_allclose(blocks.rgb_linear, whole.rgb_linear, rtol=0, atol=bound)


def test_tables_beyond_the_budget_are_one_error_before_any_work():
    with pytest.raises(SpectrumError, match="max_thickness_nm / thickness_step_nm: a table of 1500000001 thicknesses"):
        maps.colour_table(soap_film, 1500.0, thickness_step_nm=1e-6)
    with pytest.raises(SpectrumError, match="max_angle_deg / angle_step_deg"):
        maps.colour_table(soap_film, 100.0, max_angle_deg=80.0, angle_step_deg=1e-300)
    with pytest.raises(SpectrumError, match="columns: 10000000 columns"):
        zawischa_strip(columns=10**7)
