"""Re-execute notebooks in place, as the book's authors commit them (``make execute``).

Each notebook runs top to bottom in a fresh kernel started in its own folder; its outputs are
replaced, and nothing volatile is written: no execution timings (nbclient's ``record_timing``,
which ``jupyter execute --inplace`` keeps), so re-running an unchanged chapter leaves a clean
diff except for the cells whose output is volatile by nature (timings, animations), which are
tagged ``nbval-ignore-output``. A cell's consecutive prints are written as one stream output
(the kernel sends them in chunks that depend on timing), so the chunking leaves no diff either.

Usage: ``python .ci/execute_notebooks.py book/01_newton_hacksaw.ipynb [...]``
"""

import sys
from pathlib import Path

import nbformat
from nbclient import NotebookClient


def coalesce_streams(cell):
    """Join the cell's consecutive outputs of one stream (stdout or stderr) into one."""
    joined = []
    for output in cell.get("outputs", []):
        if (output.output_type == "stream" and joined and joined[-1].output_type == "stream"
                and joined[-1].name == output.name):
            joined[-1].text += output.text
        else:
            joined.append(output)
    cell["outputs"] = joined


for name in sys.argv[1:]:
    path = Path(name)
    notebook = nbformat.read(path, as_version=4)
    for cell in notebook.cells:
        cell.metadata.pop("execution", None)  # timings left by other tools
    NotebookClient(notebook, timeout=600, record_timing=False,
                   resources={"metadata": {"path": str(path.parent)}}).execute()
    for cell in notebook.cells:
        if cell.cell_type == "code":
            coalesce_streams(cell)
    nbformat.write(notebook, path)
    print(f"executed {path}")
