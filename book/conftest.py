"""Strict nbval over the book's notebooks: when ``MECHNUM_EXECUTION_RECORD`` names a file, as
``make notebooks`` does, the run records how long each notebook took to execute
(``_ext/execution_statistics.py``), for the page *Execution statistics* and the lecture budget."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent / "_ext"))
from execution_statistics import (  # noqa: E402,F401
    pytest_runtest_logreport,
    pytest_runtest_setup,
    pytest_runtest_teardown,
    pytest_sessionfinish,
)
