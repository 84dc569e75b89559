# Shared fixtures of the spring_motion module's tests. CTest sets
# SPRING_MOTION_CLI (the spring-motion executable of the same build) and
# SPRING_MOTION_SOURCE_DIR; run by hand, the repository is found from this
# file and the tests that compare with the executable are skipped without it.
import os
import pathlib
import threading
import time

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


@pytest.fixture(scope="session")
def ticks_in_the_middle():
    """Runs work(repeats) on a thread while this one records time stamps, and
    says whether a stamp fell in the middle half of the work. A fast machine can
    finish a short run inside one switch interval (5 ms), where even a released
    GIL leaves no stamp in the middle, so the work is doubled until it lasts
    0.2 s (asserting it lasts at least 0.05 s)."""
    def run(work):
        repeats = 1
        while True:
            span = {}

            def timed():
                span["start"] = time.perf_counter()
                work(repeats)
                span["end"] = time.perf_counter()

            ticks = []
            worker = threading.Thread(target=timed)
            worker.start()
            while worker.is_alive():
                ticks.append(time.perf_counter())
            worker.join()
            length = span["end"] - span["start"]
            if length >= 0.2 or repeats >= 64:
                break
            repeats *= 2
        assert length > 0.05, "the run is too short to tell"
        lo = span["start"] + 0.25 * length
        hi = span["start"] + 0.75 * length
        return any(lo < t < hi for t in ticks)
    return run
