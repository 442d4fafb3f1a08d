"""Every test runs in a directory of its own under pytest's `tmp_path`, so
what a library writes beside the caller (MuJoCo's MUJOCO_LOG.TXT, written
to the working directory at its first warning) never lands in the source
tree. The tests reach the repository's files through `__file__`."""

import pytest


@pytest.fixture(autouse=True)
def run_in_a_temporary_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
