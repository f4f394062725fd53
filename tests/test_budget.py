"""The memory budget (issue 25): one stated limit, set per call, per process and per CLI run.

Every size from outside is checked before anything is allocated: against the budget, against the
file's length, against what the file stores on disk (sparse files) and against the compressed
bytes times the largest expansion deflate reaches. These tests check the module itself and that
each way of setting the budget reaches a reader; ``tests/fuzz/test_fuzz_resources.py`` feeds the
readers and options hostile sizes under an address-space limit.
"""

from __future__ import annotations

import os

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import budget
from spectrocolor.cli import main
from spectrocolor.errors import BudgetError


@pytest.mark.parametrize(("text", "nbytes"), [
    ("2GiB", 2 * 2**30), ("2 GiB", 2 * 2**30), ("1.5G", 3 * 2**29), ("512MB", 512 * 10**6),
    ("512mib", 512 * 2**20), ("1048576", 2**20), (2**30, 2**30), ("1T", 2**40), ("4e9", 4 * 10**9),
])
def test_sizes_are_parsed_in_both_unit_systems(text, nbytes):
    assert budget.parse_size(text) == nbytes


@pytest.mark.parametrize("text", ["", "lots", "2XB", "-1GiB", "1KiB", "nan", "inf", True, 1.5e9, None,
                                  "1e400", [1]])
def test_bad_sizes_are_one_clear_error(text):
    with pytest.raises(BudgetError, match="memory_budget: expected a size in bytes of at least 1 MiB"):
        budget.parse_size(text)


def test_budget_resolution_keyword_then_environment_then_default(monkeypatch):
    monkeypatch.delenv(budget.ENVIRONMENT_VARIABLE, raising=False)
    assert budget.memory_budget() == budget.DEFAULT_MEMORY_BUDGET == 2**30
    monkeypatch.setenv(budget.ENVIRONMENT_VARIABLE, "3GiB")
    assert budget.memory_budget() == 3 * 2**30
    assert budget.memory_budget("64MiB") == 64 * 2**20
    monkeypatch.setenv(budget.ENVIRONMENT_VARIABLE, "plenty")
    with pytest.raises(BudgetError, match="SPECTROCOLOR_MEMORY_BUDGET: expected a size"):
        budget.memory_budget()


def test_check_bytes_names_input_claim_budget_and_how_to_raise_it():
    assert budget.check_bytes(2**20, "small", budget="1GiB") == 2**20
    with pytest.raises(BudgetError) as error:
        budget.check_bytes(9 * 2**30, "cube.npz: member 'values'", budget="2GiB")
    message = str(error.value)
    assert message.startswith("cube.npz: member 'values': needs 9 GiB of memory")
    assert "memory budget of 2 GiB" in message and "--memory-budget" in message
    assert "SPECTROCOLOR_MEMORY_BUDGET" in message and "\n" not in message
    assert isinstance(error.value, sc.SpectrumError) and isinstance(error.value, sc.ColorimetryError)


@pytest.mark.parametrize("shape", [(10, -3, 31), (2.5, 3), ("a", 1), (True, 2), None])
def test_claimed_shapes_must_be_whole_numbers(shape):
    with pytest.raises(BudgetError, match="every size must be a whole number >= 0"):
        budget.claimed_bytes(shape, 8, "x.npy: shape")


def test_claimed_bytes_are_exact_beyond_int64():
    assert budget.claimed_bytes((2**40, 2**40), 8, "x") == 2**83


def test_file_claims_against_length_sparse_holes_and_compression(tmp_path):
    dense = tmp_path / "dense.raw"
    dense.write_bytes(np.random.default_rng(0).bytes(3 * 2**20))
    assert budget.check_file_claim(dense, 3 * 2**20, "the header claims 3 MiB") == 3 * 2**20
    with pytest.raises(BudgetError, match="but the file holds"):
        budget.check_file_claim(dense, 3 * 2**20, "the header claims 3 MiB", offset=1)
    sparse = tmp_path / "sparse.raw"
    with open(sparse, "wb") as handle:
        handle.truncate(2**36)  # 64 GiB long, nothing stored
    if (budget.stored_bytes(sparse) or 0) < 2**20:  # the file system keeps holes (not all do)
        with pytest.raises(BudgetError, match="stores only .* on disk \\(a sparse file"):
            budget.check_file_claim(sparse, 2**36, "the header claims 64 GiB")
    assert budget.check_file_claim(dense, 1032 * 1000, "x", compressed_bytes=1000) == 1032 * 1000
    with pytest.raises(BudgetError, match="expansion over 1032:1"):
        budget.check_file_claim(dense, 1032 * 1000 + 1, "x", compressed_bytes=1000)


class _StatWithout:
    """An ``os.stat`` result as Windows gives it: no ``st_blocks``; ``st_file_attributes`` set."""

    def __init__(self, real, attributes: int) -> None:
        self.st_size = real.st_size
        self.st_file_attributes = attributes


@pytest.mark.parametrize("attributes", [0, 0x200])
def test_without_st_blocks_the_sparse_check_degrades_to_the_length_and_the_sparse_mark(
        tmp_path, monkeypatch, attributes):
    sparse = tmp_path / "sparse.raw"
    with open(sparse, "wb") as handle:
        handle.truncate(2**36)  # 64 GiB long, nothing stored
    real_stat = os.stat
    monkeypatch.setattr(budget.os, "stat", lambda path: _StatWithout(real_stat(path), attributes))
    assert budget.stored_bytes(sparse) is None  # the system does not say: no error, no guess
    with pytest.raises(BudgetError, match="but the file holds"):  # the length check stays
        budget.check_file_claim(sparse, 2**36 + 1, "the header claims 64 GiB + 1 B")
    if attributes:  # marked sparse: how much is stored is unknown, so a large claim is refused
        with pytest.raises(BudgetError, match="the system marks sparse"):
            budget.check_file_claim(sparse, 2**36, "the header claims 64 GiB")
    else:  # a plain file: its length is believed
        assert budget.check_file_claim(sparse, 2**36, "the header claims 64 GiB") == 2**36
    # small claims are never refused as sparse
    assert budget.check_file_claim(sparse, 2**16, "the header claims 64 KiB") == 2**16


def test_blocks_are_a_sixteenth_of_the_budget_and_one_row_must_fit():
    assert budget.block_bytes("1GiB") == 64 * 2**20
    assert budget.block_rows(2**20, "image", budget="1GiB") == 64
    assert budget.block_rows(2**29, "image", budget="1GiB") == 1  # wider than a block: one row
    with pytest.raises(BudgetError, match="image: one row: needs 2 GiB"):
        budget.block_rows(2**31, "image", budget="1GiB")


def test_npy_claim_checks_before_reading(tmp_path):
    path = tmp_path / "map.npy"
    np.save(path, np.zeros((512, 512), np.float64))  # 2 MiB
    assert budget.npy_claim(path)[:2] == ((512, 512), np.dtype(np.float64))
    assert budget.npy_claim(path, held=None, budget=2**20)[0] == (512, 512)  # read lazily: no budget
    with pytest.raises(BudgetError, match="map.npy: shape \\(512, 512\\) of float64: needs 2 MiB"):
        budget.npy_claim(path, budget=2**20)
    path.write_bytes(b"not a npy file")
    with pytest.raises(sc.SpectrumError, match="not a NumPy .npy file"):
        budget.npy_claim(path)


def test_the_keyword_reaches_the_readers(tmp_path):
    cube = np.zeros((64, 64, 31), np.float32)  # 508 KiB
    np.savez(tmp_path / "cube.npz", values=cube, wavelengths_nm=np.arange(400, 701, 10.0))
    assert sc.read_cube(tmp_path / "cube.npz").shape == (64, 64, 31)
    big = np.asfortranarray(np.zeros((256, 256, 31), np.float32))  # 7.75 MiB
    # deflated in Fortran order: the one kind of member still read whole (others beyond the budget stream)
    np.savez_compressed(tmp_path / "big.npz", values=big, wavelengths_nm=np.arange(400, 701, 10.0))
    with pytest.raises(BudgetError, match="member 'values': the header claims shape \\(256, 256, 31\\) of "
                                          "float32 .*: needs 7.75 MiB of memory, more than the memory budget of 1 MiB"):
        sc.read_cube(tmp_path / "big.npz", memory_budget="1MiB")


def test_the_cli_option_and_the_environment_reach_the_readers(tmp_path, capsys, monkeypatch):
    monkeypatch.delenv(budget.ENVIRONMENT_VARIABLE, raising=False)
    np.savez_compressed(tmp_path / "big.npz", values=np.asfortranarray(np.zeros((256, 256, 31), np.float32)),
                        wavelengths_nm=np.arange(400, 701, 10.0))  # read whole: see the test above
    argv = ["image", str(tmp_path / "big.npz"), "--out", str(tmp_path / "big.png")]
    assert main(["--memory-budget", "1MiB", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("spectrocolor image: error:") and "memory budget of 1 MiB" in err
    assert len(err.splitlines()) == 1
    assert budget.ENVIRONMENT_VARIABLE not in __import__("os").environ  # the run's setting is undone
    monkeypatch.setenv(budget.ENVIRONMENT_VARIABLE, "1MiB")
    assert main(argv) == 2
    assert "memory budget of 1 MiB" in capsys.readouterr().err
    assert main(["--memory-budget", "64MiB", *argv]) == 0  # the option wins over the environment
    capsys.readouterr()
    with pytest.raises(SystemExit):
        main(["--memory-budget", "lots", *argv])
    assert "argument --memory-budget: expected a size" in capsys.readouterr().err
