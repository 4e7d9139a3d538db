"""Shared fixtures of the client's tests: one daemon for the whole session (started by dashpot.Client() from
DASHPOT_DAEMON, which tests/test_python.sh sets to $BUILD/dashpotd, or from the source tree's build/), and
the helpers' directory on sys.path (references.py: the closed forms; specs.py: shared specs).

Figures are drawn with Agg: the tests never need a display.
"""

import os
import sys

os.environ.setdefault("MPLBACKEND", "Agg")
sys.path.insert(0, os.path.dirname(__file__))  # references.py, specs.py

import pytest  # noqa: E402

import dashpot  # noqa: E402


@pytest.fixture(scope="session")
def client():
    with dashpot.Client(timeout=(5, 60)) as c:
        yield c
