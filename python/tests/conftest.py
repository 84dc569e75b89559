# Shared fixtures of the spring_motion module's tests. CTest sets
# SPRING_MOTION_CLI (the spring-motion executable of the same build) and
# SPRING_MOTION_SOURCE_DIR; run by hand, the repository is found from this
# file and the tests that compare with the executable are skipped without it.
import os
import pathlib

import pytest


@pytest.fixture(scope="session")
def source_dir():
    env = os.environ.get("SPRING_MOTION_SOURCE_DIR")
    return pathlib.Path(env) if env else pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def data(source_dir):
    return lambda name: source_dir / name


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("SPRING_MOTION_CLI")
    if not path:
        pytest.skip("SPRING_MOTION_CLI is not set: the path of the spring-motion executable")
    assert os.access(path, os.X_OK), path
    return path
