"""Mechanism files: `Mechanism.from_file(path)` beside `from_toml(text)`, and
errors that name the file they came from."""

import os
import re
from pathlib import Path

import pytest

import flexure

ROOT = Path(__file__).resolve().parents[2]
CHAIN = ROOT / "examples" / "mixed_chain.toml"


@pytest.mark.parametrize("path", [CHAIN, str(CHAIN)])
def test_from_file_reads_and_solves(path):
    result = flexure.Mechanism.from_file(path).solve()
    # Closed form: the shoulder's spring turns M/k = 0.01/2 under the end moment.
    assert abs(result["coordinates"]["shoulder"][0] - 0.005) < 1e-10
    assert result["stable"] is True


def test_from_toml_still_parses_text_and_paths():
    for source in (CHAIN.read_text(), CHAIN, str(CHAIN)):
        assert flexure.Mechanism.from_toml(source).dof == flexure.Mechanism.from_file(CHAIN).dof


def test_missing_file_raises_file_not_found_naming_it(tmp_path):
    missing = tmp_path / "no" / "such.toml"
    with pytest.raises(FileNotFoundError) as info:
        flexure.Mechanism.from_file(missing)
    assert info.value.filename == str(missing) and str(missing) in str(info.value)


def test_from_toml_of_a_missing_path_is_not_parsed_as_toml(tmp_path, monkeypatch):
    # The newcomer's case: a relative path, run from the wrong folder.
    monkeypatch.chdir(tmp_path)
    with pytest.raises(FileNotFoundError, match="examples/finger.toml") as info:
        flexure.Mechanism.from_toml("examples/finger.toml")
    assert str(tmp_path) in str(info.value), "says where relative paths start"


def test_errors_in_a_file_name_it(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[[joint]]\nname = "a"\nkind = "flexure"\nparent = "palm"\nchild = "b"\nlength = 0.01\nei = 1.0\n')
    with pytest.raises(ValueError, match=rf"^{re.escape(str(bad))}: line 4, column 10: unknown body \"palm\""):
        flexure.Mechanism.from_file(bad)
    with pytest.raises(ValueError, match=rf"^{re.escape(str(bad))}: line 4"):
        flexure.Mechanism.from_toml(bad)
    # Text has no file to name.
    with pytest.raises(ValueError, match=r"^line 4, column 10"):
        flexure.Mechanism.from_toml(bad.read_text())


def test_solve_errors_name_the_file(tmp_path):
    # A free pin driven by a moment has no equilibrium to follow.
    free = tmp_path / "free.toml"
    free.write_text(
        '[[joint]]\nname = "pin"\nkind = "revolute"\nparent = "ground"\nchild = "arm"\n'
        '[[force]]\nbody = "arm"\nat = [0.0, 0.0]\nmoment = 1.0\n'
    )
    with pytest.raises((ValueError, flexure.ConvergenceError), match=rf"^{re.escape(str(free))}: "):
        flexure.Mechanism.from_file(free).solve()
    # An error about the Python argument is not the file's.
    with pytest.raises(ValueError, match=r"^accuracy"):
        flexure.Mechanism.from_file(free).solve(accuracy=(0.0, 1.0))


def test_a_file_that_is_not_text(tmp_path):
    binary = tmp_path / "binary.toml"
    binary.write_bytes(b"\xff\xfe\x00")
    with pytest.raises(ValueError, match=rf"^{re.escape(str(binary))}: not UTF-8 text"):
        flexure.Mechanism.from_file(binary)


@pytest.mark.parametrize("path", [3, None, b"examples/finger.toml"])
def test_path_of_the_wrong_type(path):
    with pytest.raises(ValueError, match=r"^path must"):
        flexure.Mechanism.from_file(path)


def test_relative_paths_start_at_the_working_directory(monkeypatch):
    monkeypatch.chdir(ROOT)
    assert flexure.Mechanism.from_file(os.path.join("examples", "finger.toml")).dof > 0


def test_a_file_is_read_to_a_bound():
    # /dev/zero has no end: refused at 64 MiB, as the CLI refuses it, not read forever.
    with pytest.raises(ValueError, match=r"/dev/zero: larger than 64 MiB"):
        flexure.Mechanism.from_file("/dev/zero")
