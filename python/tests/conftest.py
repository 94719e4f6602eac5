"""Shared fixtures of the adjoin Python tests, and the exit status CTest reads.

A test file whose run skipped a test (pytest.importorskip: matplotlib missing) and failed none
exits with 77, which CTest shows as skipped (SKIP_RETURN_CODE in python/CMakeLists.txt), so a
missing optional dependency is visible instead of counted as a pass.
"""
import os
import pathlib

import pytest

SOURCE = pathlib.Path(__file__).resolve().parents[2]
SCENES = SOURCE / "records" / "scenes"
RECORDS = SOURCE / "records" / "real"

_skipped = []


def pytest_runtest_logreport(report):
    if report.skipped:
        _skipped.append(report.nodeid)


def pytest_sessionfinish(session, exitstatus):
    if exitstatus == 0 and _skipped:
        session.exitstatus = 77


@pytest.fixture(scope="session")
def adjoin_cli():
    """The `adjoin` program of the same build (CTest sets ADJOIN_CLI), or the one in build/."""
    path = os.environ.get("ADJOIN_CLI") or str(SOURCE / "build" / "adjoin")
    if not os.access(path, os.X_OK):
        pytest.fail(f"the adjoin program is not at {path}: build the target adjoin_cli (CTest sets ADJOIN_CLI)")
    return path
