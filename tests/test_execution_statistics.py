"""The records of how long each notebook took to execute (``book/_ext/execution_statistics.py``):
the CPU time of a finished child process is measured, and a record counts only for the notebook
as it was measured. The page that shows them is tested on the built book
(``tests/test_built_html.py``)."""

import subprocess
import sys

from lecture_pages import ROOT

sys.path.insert(0, str(ROOT / "book" / "_ext"))
import execution_statistics as stats  # noqa: E402

BUSY = "import time\nt = time.process_time()\nwhile time.process_time() - t < 0.3:\n    pass"


def test_a_stopwatch_measures_the_cpu_time_of_a_finished_kernel(tmp_path):
    notebook = tmp_path / "a.ipynb"
    notebook.write_text("{}")
    watch = stats.Stopwatch(notebook)
    subprocess.run([sys.executable, "-c", BUSY], check=True)  # a kernel: 0.3 s on a core
    record = watch.stop()
    assert 0.3 <= record["cpu"] < 3.0 and record["wall"] >= 0.3
    assert record["sha256"] == stats.digest(notebook) and len(record["load"]) == 2


def test_a_record_counts_only_for_the_notebook_it_measured(tmp_path):
    notebook = tmp_path / "book" / "a.ipynb"
    notebook.parent.mkdir()
    notebook.write_text("{}")
    record = stats.Stopwatch(notebook).stop()
    stats.save(tmp_path / stats.FOLDER / "notebooks.json", {"book/a.ipynb": record})
    assert stats.measured(tmp_path, "book/a.ipynb") == [("notebooks.json", record)]
    notebook.write_text('{"cells": []}')  # edited since: the record no longer says anything
    assert stats.measured(tmp_path, "book/a.ipynb") == []
