"""Relighting: library identity and spectral agreement, and the ``relight`` command."""

import numpy as np
import pytest
from PIL import Image

import spectrocolor as sc
from spectrocolor.cli import main
from spectrocolor.upsampling import relight, rgb_linear_from_image, save_table, upsample
from upsampling_tables import srgb_table

EXACT = 1e-9


def test_same_light_gives_back_the_input_with_or_without_adaptation():
    table = srgb_table()
    t = np.random.default_rng(4).random((200, 3))
    for adaptation in (None, "bradford"):
        back = relight(table, t, "D65", adaptation=adaptation)
        assert back.exact.all()
        np.testing.assert_allclose(back.rgb_linear, t, rtol=0, atol=EXACT)


def test_relight_equals_the_spectral_route():
    table = srgb_table()
    t = np.random.default_rng(5).random((300, 3))
    W_A = sc.weights(table.wavelengths_nm, illuminant="A")
    XYZ_A = upsample(table, t).reflectance @ W_A
    for adaptation, white in ((None, table.weights.sum(0)), ("cat16", W_A.sum(0))):
        expected = sc.adapt(XYZ_A, white, sc.rgb_space("sRGB").white_XYZ, method=adaptation
                            or "bradford")
        got = relight(table, t, "A", adaptation=adaptation).XYZ100
        np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-12)


def test_white_turns_warm_unadapted_and_stays_white_adapted():
    table = srgb_table()
    warm = relight(table, [1.0, 1.0, 1.0], "A").rgb_linear
    assert warm[0] > 1.0 > warm[1] > warm[2]
    adapted = relight(table, [1.0, 1.0, 1.0], "A", adaptation="bradford").rgb_linear
    np.testing.assert_allclose(adapted, 1.0, atol=EXACT)


def test_codes_are_decoded_with_the_space_transfer():
    codes = np.array([[0, 128, 255]], dtype=np.uint8)
    np.testing.assert_allclose(rgb_linear_from_image(codes),
                               sc.transfer("srgb").decode(codes / 255.0))
    wide = np.array([[0, 32768, 65535]], dtype=np.uint16)
    np.testing.assert_allclose(rgb_linear_from_image(wide)[0, 2], 1.0)
    with pytest.raises(sc.ColorimetryError, match="uint8 or uint16"):
        rgb_linear_from_image(np.zeros((2, 3)))


def photo(path, size=(12, 9), seed=0):
    rng = np.random.default_rng(seed)
    codes = rng.integers(0, 256, (size[1], size[0], 3), dtype=np.uint8)
    Image.fromarray(codes).save(path)
    return codes


def test_cli_relight_to_the_same_light_returns_the_photo(tmp_path, capsys):
    codes = photo(tmp_path / "in.png")
    assert main(["relight", str(tmp_path / "in.png"), "--to", "D65", "--resolution", "5",
                 "--out", str(tmp_path / "out.png")]) == 0
    # exact: codes re-encoded from a round trip exact to 1e-9 relative lie within 1e-6 of a code, far from a half-code
    # tie
    np.testing.assert_array_equal(np.asarray(Image.open(tmp_path / "out.png")), codes)
    assert "0 of 108 pixels not reproduced exactly" in capsys.readouterr().out


def test_cli_relight_to_a_warms_the_photo_and_adaptation_undoes_the_cast(tmp_path):
    codes = photo(tmp_path / "in.png")
    for adapt, name in (("none", "a.png"), ("bradford", "b.png")):
        assert main(["relight", str(tmp_path / "in.png"), "--to", "A", "--adapt", adapt,
                     "--resolution", "5", "--out", str(tmp_path / name)]) == 0
    warm = np.asarray(Image.open(tmp_path / "a.png")).astype(float)
    adapted = np.asarray(Image.open(tmp_path / "b.png")).astype(float)
    cast = (warm[..., 0] - warm[..., 2]).mean() - (codes[..., 0] - codes[..., 2].astype(float)).mean()
    assert cast > 20  # red minus blue rises under the incandescent light
    assert abs((adapted - codes).mean(axis=(0, 1))).max() < abs((warm - codes).mean(axis=(0, 1))).max()


def test_cli_uses_a_saved_table_and_16_bit_output(tmp_path):
    save_table(srgb_table(), tmp_path / "t.scup")
    photo(tmp_path / "in.png")
    assert main(["relight", str(tmp_path / "in.png"), "--to", "F11", "--table",
                 str(tmp_path / "t.scup"), "--bit-depth", "16",
                 "--out", str(tmp_path / "out.png")]) == 0
    with open(tmp_path / "out.png", "rb") as handle:
        assert handle.read(25)[24] == 16
    assert main(["relight", str(tmp_path / "in.png"), "--to", "F11", "--table",
                 str(tmp_path / "t.scup"), "--from", "A", "--out", str(tmp_path / "x.png")]) == 2


def test_cli_folder_mode(tmp_path, capsys):
    (tmp_path / "photos").mkdir()
    (tmp_path / "relit").mkdir()
    photo(tmp_path / "photos" / "one.png")
    photo(tmp_path / "photos" / "two.png", seed=1)
    (tmp_path / "photos" / "notes.txt").write_text("not a photo")
    assert main(["relight", str(tmp_path / "photos"), "--to", "A", "--resolution", "3",
                 "--out", str(tmp_path / "relit")]) == 0
    assert sorted(p.name for p in (tmp_path / "relit").iterdir()) == ["one.png", "two.png"]
    assert capsys.readouterr().out.count("wrote") == 2
    # the same folder as output, or outputs that exist without --force: refused before work
    assert main(["relight", str(tmp_path / "photos"), "--to", "A",
                 "--out", str(tmp_path / "photos")]) == 2
    assert main(["relight", str(tmp_path / "photos"), "--to", "A",
                 "--out", str(tmp_path / "relit")]) == 2
    assert "--force" in capsys.readouterr().err


def test_cli_never_writes_over_its_input(tmp_path, capsys):
    codes = photo(tmp_path / "in.png")
    assert main(["relight", str(tmp_path / "in.png"), "--to", "A", "--force",
                 "--out", str(tmp_path / "in.png")]) == 2
    assert "input" in capsys.readouterr().err
    # exact: the refused command left the file as it was
    np.testing.assert_array_equal(np.asarray(Image.open(tmp_path / "in.png")), codes)


@pytest.mark.parametrize("argv, message", [
    (["--to", "Q99"], "--to"),
    (["--to", "A", "--resolution", "1"], "--resolution"),
    (["--to", "A", "--space", "nonsense"], "space"),
])
def test_cli_bad_options_get_one_line(tmp_path, capsys, argv, message):
    photo(tmp_path / "in.png")
    code = main(["relight", str(tmp_path / "in.png"), "--out", str(tmp_path / "o.png"), *argv])
    err = capsys.readouterr().err
    assert code == 2 and message in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def test_cli_reads_16_bit_png_whole_and_refuses_damaged_files(tmp_path, capsys):
    from spectrocolor.pictures import write_image
    from spectrocolor.upsampling import read_png

    codes = np.random.default_rng(3).integers(0, 65536, (5, 7, 3), dtype=np.uint16)
    codes[0, 0] = (1, 2, 3)  # codes that differ only in the low byte survive
    write_image(tmp_path / "deep.png", codes)
    assert main(["relight", str(tmp_path / "deep.png"), "--to", "D65", "--resolution", "5",
                 "--bit-depth", "16", "--out", str(tmp_path / "o.png")]) == 0
    # exact: codes re-encoded from a round trip exact to 1e-9 relative lie within 1e-4 of a code, far from a half-code
    # tie
    np.testing.assert_array_equal(read_png(tmp_path / "o.png"), codes)
    (tmp_path / "cut.png").write_bytes((tmp_path / "deep.png").read_bytes()[:60])
    assert main(["relight", str(tmp_path / "cut.png"), "--to", "A",
                 "--out", str(tmp_path / "o2.png")]) == 2
    err = capsys.readouterr().err
    assert "cannot be read" in err and "cut.png" in err and "Traceback" not in err
    (tmp_path / "junk.png").write_bytes(b"\x89PNG\r\n\x1a\n" + b"\0" * 40)
    assert main(["relight", str(tmp_path / "junk.png"), "--to", "A",
                 "--out", str(tmp_path / "o3.png")]) == 2
    assert "cannot be read" in capsys.readouterr().err
