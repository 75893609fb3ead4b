"""Re-execute notebooks in place, as the book's authors commit them (``make execute``).

Each notebook runs top to bottom in a fresh kernel started in its own folder; its outputs are
replaced, and nothing volatile is written: no execution timings (nbclient's ``record_timing``,
which ``jupyter execute --inplace`` keeps), so re-running an unchanged chapter leaves a clean
diff except for the cells whose output is volatile by nature (timings, animations), which are
tagged ``nbval-ignore-output``.

Usage: ``python .ci/execute_notebooks.py book/01_newton_hacksaw.ipynb [...]``
"""

import sys
from pathlib import Path

import nbformat
from nbclient import NotebookClient

for name in sys.argv[1:]:
    path = Path(name)
    notebook = nbformat.read(path, as_version=4)
    for cell in notebook.cells:
        cell.metadata.pop("execution", None)  # timings left by other tools
    NotebookClient(notebook, timeout=600, record_timing=False,
                   resources={"metadata": {"path": str(path.parent)}}).execute()
    nbformat.write(notebook, path)
    print(f"executed {path}")
