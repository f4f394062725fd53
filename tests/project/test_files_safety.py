"""No file is lost: full disks, killed writers, and the overwrite policy of every writing command.

Two real write failures are used, neither needing root: the file-size limit (``RLIMIT_FSIZE``,
the kernel answers EFBIG exactly where a full disk answers ENOSPC) for every writer, and a file
object that raises ENOSPC. ``kill -9`` of a process writing a large TIFF checks that the target
only ever changes by rename.
"""

from __future__ import annotations

import csv
import errno
import hashlib
import json
import os
import resource
import signal
import subprocess
import sys
import time
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
import spectrocolor.cli as cli
from spectrocolor import safe_write
from spectrocolor.report import measurement_report
from spectrocolor.safe_write import OutputError, atomic_path, write_bytes

PIL = pytest.importorskip("PIL")
tifffile = pytest.importorskip("tifffile")

SPECTRA_CSV = "wavelength_nm,grey,=HYPERLINK(\"http://x\"),@SUM(A1)\n" + "".join(
    f"{w},0.5,0.2,0.7\n" for w in range(380, 781, 10))


def digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


@contextmanager
def file_size_limit(limit_bytes: int):
    """Writes beyond ``limit_bytes`` fail with EFBIG (SIGXFSZ ignored), as on a full disk."""
    soft, hard = resource.getrlimit(resource.RLIMIT_FSIZE)
    previous = signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, hard))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_FSIZE, (soft, hard))
        signal.signal(signal.SIGXFSZ, previous)


def _report():
    spectra = sc.Spectrum(np.arange(380.0, 781.0, 10.0), np.full((5, 41), 0.4),
                          names=tuple(f"sample {i}" for i in range(5)))
    return measurement_report(spectra, illuminant="D65")


def _writers():
    from spectrocolor.pictures import save_image, write_image
    from spectrocolor.report import write_report

    big8 = np.random.default_rng(0).integers(0, 256, (300, 300, 3), dtype=np.uint8)
    big16 = np.random.default_rng(1).integers(0, 65536, (200, 200, 3), dtype=np.uint16)
    floats = np.random.default_rng(2).random((200, 200, 3)).astype(np.float32)
    report = _report()
    return {
        "save_image png": ("x.png", lambda p: save_image(big8, p)),
        "save_image ppm": ("x.ppm", lambda p: save_image(big8, p)),
        "write_image png8": ("y.png", lambda p: write_image(p, big8)),
        "write_image png16": ("z.png", lambda p: write_image(p, big16)),
        "write_image tiff": ("t.tif", lambda p: write_image(p, floats, metadata={"q": "XYZ"})),
        "write_report html": ("r.html", lambda p: write_report(report, p)),
        "write_report csv": ("r.csv", lambda p: write_report(report, p)),
        "write_report json": ("r.json", lambda p: write_report(report, p)),
        "write_bytes": ("b.bin", lambda p: write_bytes(p, b"\0" * 100_000)),
    }


WRITERS = list(_writers())


@pytest.mark.parametrize("name", WRITERS)
def test_full_disk_keeps_the_previous_file(tmp_path, name):
    filename, write = _writers()[name]
    target = tmp_path / filename
    target.write_bytes(b"a complete previous file\n")
    before = digest(target)
    with file_size_limit(300), pytest.raises(OutputError) as info:  # every output is larger
        write(target)
    assert "unchanged" in str(info.value) and str(target) in str(info.value)
    assert digest(target) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == [filename]  # no temporary file left


def test_enospc_from_the_file_object_keeps_the_previous_file(tmp_path, monkeypatch):
    target = tmp_path / "a.bin"
    target.write_bytes(b"old contents")
    real_open = open

    class FullDisk:
        def __init__(self, handle):
            self.handle = handle

        def write(self, data):
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            self.handle.close()

    def failing_open(path, mode="r", *args, **kwargs):
        handle = real_open(path, mode, *args, **kwargs)
        return FullDisk(handle) if "w" in mode else handle

    monkeypatch.setattr("builtins.open", failing_open)
    with pytest.raises(OutputError, match="No space left on device"):
        write_bytes(target, b"new contents that do not fit")
    monkeypatch.undo()
    assert target.read_bytes() == b"old contents"
    assert [p.name for p in tmp_path.iterdir()] == ["a.bin"]


def test_a_failed_check_keeps_the_previous_file(tmp_path):
    target = tmp_path / "c.txt"
    target.write_text("old")

    def disagree(path):
        raise OutputError(errno.EIO, f"{path}: read back wrong")

    with pytest.raises(OutputError, match="read back wrong"):
        write_bytes(target, b"new", verify=disagree)
    assert target.read_text() == "old" and len(list(tmp_path.iterdir())) == 1


def test_an_encoder_error_keeps_the_previous_file(tmp_path):
    target = tmp_path / "d.txt"
    target.write_text("old")
    with pytest.raises(RuntimeError, match="encoder"), atomic_path(target) as temporary:
        temporary.write_text("half")
        raise RuntimeError("encoder failed half way")
    assert target.read_text() == "old" and len(list(tmp_path.iterdir())) == 1


def test_a_missing_folder_is_one_clear_error(tmp_path):
    with pytest.raises(OutputError, match="does not exist"):
        write_bytes(tmp_path / "no" / "such" / "x.bin", b"")
    (tmp_path / "file").write_text("")
    with pytest.raises(OutputError, match="is not a folder"):
        write_bytes(tmp_path / "file" / "x.bin", b"")


KILL_SCRIPT = """
import sys, numpy as np
from spectrocolor.pictures import write_image
image = np.random.default_rng(0).random((2500, 2500, 3)).astype(np.float32)  # 75 MB
print("start", flush=True)
for _ in range(50):
    write_image(sys.argv[1], image)
"""


@pytest.mark.parametrize("run", range(3))
def test_kill_9_during_a_tiff_write_keeps_the_previous_file(tmp_path, run):
    from spectrocolor.pictures import write_image

    target = tmp_path / "cube.tif"
    previous = np.arange(12, dtype=np.float32).reshape(2, 2, 3)
    write_image(target, previous)
    before = digest(target)
    proc = subprocess.Popen([sys.executable, "-c", KILL_SCRIPT, str(target)],
                            stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "start"
    deadline = time.monotonic() + 60
    partial = []
    while time.monotonic() < deadline:  # kill once the temporary TIFF is being written
        partial = [p for p in tmp_path.iterdir() if ".partial" in p.name and p.stat().st_size]
        if partial:
            break
        time.sleep(0.002 * (run + 1))
    proc.send_signal(signal.SIGKILL)
    proc.wait(10)
    assert partial, "the writer never started a temporary file"
    # the target is either the complete previous file or a complete new one, never a torn one
    data = tifffile.imread(target)
    if digest(target) == before:
        np.testing.assert_array_equal(data, previous)  # exact: the file was not touched: the same bytes
    else:
        assert data.shape == (2500, 2500, 3)


# --- the overwrite policy on the command line ----------------------------------------------------


@pytest.fixture
def spectra_file(tmp_path):
    path = tmp_path / "mine.csv"
    path.write_text(SPECTRA_CSV)
    return path


def run_cli(argv, capsys) -> tuple[int, str]:
    code = cli.main([str(a) for a in argv])
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return code, err


def test_report_never_writes_over_its_input(spectra_file, capsys):
    before = digest(spectra_file)
    for force in ([], ["--force"]):
        code, err = run_cli(["report", spectra_file, "--illuminant", "D65", "--out", spectra_file,
                             *force], capsys)
        assert code == 2 and "is the command's input" in err and err.count("\n") == 1
    assert digest(spectra_file) == before


def test_symlinks_and_hard_links_to_the_input_are_the_input(spectra_file, tmp_path, capsys):
    before = digest(spectra_file)
    (tmp_path / "soft.csv").symlink_to(spectra_file)
    os.link(spectra_file, tmp_path / "hard.csv")
    for out in ("soft.csv", "hard.csv"):
        code, err = run_cli(["report", spectra_file, "--illuminant", "D65", "--out",
                             tmp_path / out, "--force"], capsys)
        assert code == 2 and "is the command's input" in err
    assert digest(spectra_file) == before


def test_a_symlinked_output_is_written_through_and_stays_a_link(tmp_path):
    real_folder = tmp_path / "real"
    real_folder.mkdir()
    target = real_folder / "data.txt"
    target.write_text("old")
    os.chmod(target, 0o640)
    chain = tmp_path / "hop.txt"  # link -> link -> file
    chain.symlink_to(target)
    link = tmp_path / "out.txt"
    link.symlink_to(chain)
    safe_write.write_text(link, "new")
    assert link.is_symlink() and chain.is_symlink() and os.readlink(link) == str(chain)
    assert target.read_text() == "new" and link.read_text() == "new"
    assert stat_mode(target) == 0o640  # the replaced file keeps its mode
    assert sorted(p.name for p in real_folder.iterdir()) == ["data.txt"]  # temporary file beside the target
    assert sorted(p.name for p in tmp_path.iterdir()) == ["hop.txt", "out.txt", "real"]


def test_a_dangling_symlinked_output_creates_its_target(tmp_path):
    link = tmp_path / "out.csv"
    link.symlink_to(tmp_path / "made.csv")
    safe_write.write_text(link, "x\n")
    assert link.is_symlink() and (tmp_path / "made.csv").read_text() == "x\n"


def test_a_failed_write_through_a_link_leaves_the_target(tmp_path):
    target = tmp_path / "keep.bin"
    target.write_bytes(b"previous")
    link = tmp_path / "link.bin"
    link.symlink_to(target)

    def refuse(path):
        raise OutputError(errno.EIO, f"{path}: check failed")

    with pytest.raises(OutputError, match="check failed"):
        write_bytes(link, b"next", verify=refuse)
    assert link.is_symlink() and target.read_bytes() == b"previous"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["keep.bin", "link.bin"]


def test_cli_writes_through_a_symlinked_output(spectra_file, tmp_path, capsys):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "report.html").write_text("old report")
    link = tmp_path / "report.html"
    link.symlink_to(elsewhere / "report.html")
    code, _ = run_cli(["report", spectra_file, "--illuminant", "D65", "--out", link, "--force"], capsys)
    assert code == 0 and link.is_symlink()
    assert (elsewhere / "report.html").read_text() != "old report"


def stat_mode(path: Path) -> int:
    return os.stat(path).st_mode & 0o777


def test_recover_never_writes_over_its_input(tmp_path, capsys):
    source = tmp_path / "x.csv"
    source.write_text("X,Y,Z\n40,40,40\n")
    code, err = run_cli(["recover", "--csv", source, "--out", source, "--force"], capsys)
    assert code == 2 and "is the command's input" in err
    assert source.read_text() == "X,Y,Z\n40,40,40\n"


def test_image_never_writes_over_its_input(tmp_path, capsys):
    cube = tmp_path / "cube.tif"
    tifffile.imwrite(cube, np.full((4, 5, 31), 0.5, np.float32), photometric="minisblack",
                     planarconfig="contig")
    before = digest(cube)
    code, err = run_cli(["image", cube, "--illuminant", "D65", "--wavelengths", "400:700:10",
                         "--quantity", "xyz", "--out", cube, "--force"], capsys)
    assert code == 2 and "is the command's input" in err
    assert digest(cube) == before


def test_existing_outputs_need_force(spectra_file, tmp_path, capsys):
    out = tmp_path / "report.csv"
    out.write_text("keep me")
    code, err = run_cli(["report", spectra_file, "--illuminant", "D65", "--out", out], capsys)
    assert code == 2 and "--force" in err and out.read_text() == "keep me"
    code, _ = run_cli(["report", spectra_file, "--illuminant", "D65", "--out", out, "--force"],
                      capsys)
    assert code == 0 and out.read_text().startswith("# illuminant")


def test_two_outputs_of_one_command_must_differ(tmp_path, capsys):
    code, err = run_cli(["thinfilm", "zawischa", "--out", tmp_path / "a.png", "--csv",
                         tmp_path / "a.png"], capsys)
    assert code == 2 and "the same file" in err
    assert list(tmp_path.iterdir()) == []


def test_report_csv_names_a_spreadsheet_would_run_are_text(spectra_file, tmp_path, capsys):
    out = tmp_path / "r.csv"
    assert run_cli(["report", spectra_file, "--illuminant", "D65", "--out", out], capsys)[0] == 0
    names = [row[0] for row in csv.reader(out.read_text().splitlines()[2:])]
    assert names[0] == "grey" and names[1].startswith("'=") and names[2].startswith("'@")
    out_json = tmp_path / "r.json"
    assert run_cli(["report", spectra_file, "--illuminant", "D65", "--out", out_json],
                   capsys)[0] == 0
    assert [s["name"] for s in json.loads(out_json.read_text())["samples"]][2] == "@SUM(A1)"


def test_a_full_disk_on_the_command_line_is_one_line_and_exit_2(tmp_path, capsys):
    cube = tmp_path / "cube.npy"
    np.save(cube, np.full((64, 64, 31), 0.5))
    out = tmp_path / "out.tif"
    out.write_bytes(b"previous")
    with file_size_limit(4096):
        code, err = run_cli(["image", cube, "--illuminant", "D65", "--wavelengths", "400:700:10",
                             "--quantity", "xyz", "--out", out, "--force"], capsys)
    assert code == 2 and err.count("\n") == 1 and "unchanged" in err
    assert "wrote" not in capsys.readouterr().out
    assert out.read_bytes() == b"previous"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cube.npy", "out.tif"]


def test_the_policy_is_documented_once():
    text = (Path(__file__).parents[2] / "docs" / "robustness.md").read_text()
    assert "--force" in text and "own input" in text
    assert safe_write.__doc__ and "--force" in safe_write.__doc__


def test_xyz_csv_names_a_spreadsheet_would_run_are_text(spectra_file, capsys):
    assert cli.main(["xyz", str(spectra_file), "--format", "csv"]) == 0
    names = [row[0] for row in csv.reader(capsys.readouterr().out.splitlines()[1:])]
    assert names == ["grey", "'=HYPERLINK(\"http://x\")", "'@SUM(A1)"]


def test_new_files_get_the_usual_permissions_and_replaced_files_keep_theirs(tmp_path):
    mask = os.umask(0o022)
    try:
        fresh = write_bytes(tmp_path / "new.bin", b"x")
        old = tmp_path / "old.bin"
        old.write_bytes(b"old")
        old.chmod(0o640)
        write_bytes(old, b"new")
    finally:
        os.umask(mask)
    assert fresh.stat().st_mode & 0o777 == 0o666 & ~safe_write._UMASK  # as open(path, "w")
    assert old.stat().st_mode & 0o777 == 0o640 and old.read_bytes() == b"new"


# --- two writers of one output without --force (issue 31) ----------------------------------------


def test_an_output_created_while_the_command_ran_is_not_replaced(tmp_path):
    """check_outputs found the file absent; another program wrote it before this one finished:
    the other file is kept and this writer says so (it used to replace it silently)."""
    target = tmp_path / "out.csv"
    safe_write.check_outputs({"--out": target})
    target.write_text("written by another program")
    with pytest.raises(OutputError, match="created by another program.*--force"):
        safe_write.write_text(target, "mine")
    assert target.read_text() == "written by another program"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.csv"]  # no temporary file left


def test_with_force_the_output_is_replaced_whoever_wrote_it(tmp_path):
    target = tmp_path / "out.csv"
    safe_write.check_outputs({"--out": target}, force=True)
    target.write_text("written by another program")
    safe_write.write_text(target, "mine")
    assert target.read_text() == "mine"


def test_an_output_still_absent_is_created_and_later_writes_replace(tmp_path):
    target = tmp_path / "out.csv"
    safe_write.check_outputs({"--out": target})
    safe_write.write_text(target, "first")
    safe_write.write_text(target, "second")  # the same command writing again: its own file
    assert target.read_text() == "second"


RACER = """
import sys, time
from pathlib import Path
from spectrocolor.safe_write import OutputError, check_outputs, write_text
target, go, me = Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3]
check_outputs({"--out": target})  # absent: both runs pass the check
print("checked", flush=True)
while not go.exists():
    time.sleep(0.01)
try:
    write_text(target, me)
except OutputError as exc:
    print(exc, file=sys.stderr)
    sys.exit(2)
"""


def test_two_runs_writing_one_output_cannot_both_succeed(tmp_path):
    """Two ``spectrocolor`` runs without --force, both past the existence check: exactly one
    writes the file, the other stops with one line and the winner's file stays whole."""
    script, target, go = tmp_path / "racer.py", tmp_path / "out.csv", tmp_path / "go"
    script.write_text(RACER)
    runs = [subprocess.Popen([sys.executable, str(script), str(target), str(go), name],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            for name in ("run A", "run B")]
    try:
        for run in runs:
            assert run.stdout.readline().strip() == "checked"
        go.touch()
        results = [(run.wait(60), run.stderr.read()) for run in runs]
    finally:
        for run in runs:
            run.kill()
    codes = sorted(code for code, _ in results)
    assert codes == [0, 2], results
    loser = next(err for code, err in results if code == 2)
    assert "created by another program" in loser and loser.count("\n") == 1
    assert target.read_text() in ("run A", "run B")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["go", "out.csv", "racer.py"]
