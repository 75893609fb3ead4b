"""Hypothesis profiles: the same examples for ``make test``, new ones for ``make explore``; the
book's module ``published`` on the path.

``make test`` (and CI) must give the same verdict on every run and every machine, so it sets
``HYPOTHESIS_PROFILE=repeatable``: each test draws the same examples every time (seeded from the
test's source) and no example database is kept. Searching for new counterexamples is a separate
act, ``make explore`` (or plain ``pytest tests``): the profile ``explore`` draws new random
examples on each run and remembers a failure in ``.hypothesis`` so that the next run replays it.
A counterexample it finds becomes an ``@example`` on its test, which every run then checks.
"""
import os
import sys
from pathlib import Path

from hypothesis import HealthCheck, settings

# The book's own module, book/published.py (the registry's rules, served with the chapters),
# importable as ``published`` as the chapters import it.
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "book"))

settings.register_profile("repeatable", derandomize=True, database=None, deadline=None,
                          print_blob=True,
                          # the one health check whose verdict depends on the machine's speed
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("explore", deadline=None, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "explore"))
