"""Run one student notebook in a confined kernel and read back the source of its functions.

Run by the grader in a session of its own, as ``python -m mechnum_course.grading._notebook
JOB.json``. The kernel is started through :mod:`._sandbox` (limits, Landlock), talks over Unix
sockets in the notebook's temporary folder (it needs no TCP), has that folder as its home and
temporary folder, and its standard output and error go nowhere. Every cell runs, each within a
time limit (a cell that overruns is interrupted; a kernel that ignores the interrupt is given
up on at the next cell); what the cells print is kept up to a bound, beyond which it is dropped.
The last cell (:func:`._extract.cell`) prints the functions' sources. The result, a JSON file
outside the sandbox, lists the cells that raised (with the number Jupyter shows, ``In [n]``)
and the sources; the grader judges nothing the notebook says about itself.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellTimeoutError, DeadKernelError

from mechnum_course.grading import _extract


class _Stuck(Exception):
    """The kernel ignored an interrupt: it is given up on."""


class _Client(NotebookClient):
    """nbclient with a bound on the output kept and on a kernel that ignores interrupts."""

    def __init__(self, *args, max_output, **kwargs):
        super().__init__(*args, **kwargs)
        self.max_output, self.kept, self.dropped, self.timeouts = max_output, 0, 0, []

    def output(self, outs, msg, display_id, cell_index):
        size = len(json.dumps(msg.get("content", {}), default=str))
        if self.kept + size > self.max_output:
            self.dropped += size
            return None
        self.kept += size
        return super().output(outs, msg, display_id, cell_index)

    async def _async_handle_timeout(self, timeout, cell=None):
        if self.timeouts and self.timeouts[-1] == self.code_cells_executed - 1:
            raise _Stuck
        self.timeouts.append(self.code_cells_executed)
        await super()._async_handle_timeout(timeout, cell)
        return {"content": {"status": "error", "ename": "Timeout",
                            "evalue": f"the cell ran longer than {timeout} s and was "
                                      "interrupted", "traceback": []}}


def _kernel_spec(folder, confinement):
    """A Jupyter kernel that starts confined; its folder for JUPYTER_PATH."""
    (folder / "sandbox.json").write_text(json.dumps(confinement), encoding="utf-8")
    spec = folder / ".jupyter" / "kernels" / "mechnum-sandbox"
    spec.mkdir(parents=True)
    argv = [sys.executable, "-m", "mechnum_course.grading._sandbox",
            str(folder / "sandbox.json"), "--", sys.executable, "-s", "-m",
            "ipykernel_launcher", "-f", "{connection_file}"]
    (spec / "kernel.json").write_text(json.dumps(
        {"argv": argv, "display_name": "sandbox", "language": "python"}), encoding="utf-8")
    startup = folder / ".ipython" / "profile_default" / "startup"
    startup.mkdir(parents=True)
    (startup / "00-grader.py").write_text(_extract.PRELUDE, encoding="utf-8")
    return folder / ".jupyter"


def _errors(notebook, count):
    """The cells that raised: their index, ``In [n]``, and the exception's name and text."""
    found, code = [], 0
    for index, cell in enumerate(notebook.cells[:count]):
        if cell.cell_type != "code":
            continue
        code += 1
        for out in cell.get("outputs", []):
            if out.get("output_type") == "error":
                found.append({"cell": index + 1, "code_cell": code,
                              "count": cell.get("execution_count"),
                              "ename": str(out.get("ename", ""))[:200],
                              "evalue": str(out.get("evalue", ""))[:1000]})
    return found


def run(job):
    """Execute the job's notebook; the result (a dictionary)."""
    folder = Path(job["folder"])
    notebook = nbformat.read(job["notebook"], as_version=4)
    count = len(notebook.cells)
    notebook.cells.append(nbformat.v4.new_code_cell(_extract.cell(job["names"], folder)))
    jupyter = _kernel_spec(folder, job["confinement"])
    runtime = folder / ".runtime"
    runtime.mkdir()
    env = {**job["env"], "JUPYTER_PATH": str(jupyter), "JUPYTER_RUNTIME_DIR": str(runtime),
           "IPYTHONDIR": str(folder / ".ipython")}
    os.environ.update(JUPYTER_PATH=str(jupyter), JUPYTER_RUNTIME_DIR=str(runtime))
    client = _Client(notebook, timeout=job["cell_limit"], allow_errors=True,
                     interrupt_on_timeout=True, kernel_name="mechnum-sandbox",
                     max_output=job["max_output"], startup_timeout=120,
                     resources={"metadata": {"path": str(Path(job["notebook"]).parent)}})
    client.km = client.create_kernel_manager()
    client.km.transport, client.km.ip = "ipc", str(runtime / "kernel")
    client.km.connection_file = str(runtime / "connection.json")
    problem = ""
    try:
        client.execute(env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       stdin=subprocess.DEVNULL)
    except _Stuck:
        problem = "a cell ignored the interrupt after its time limit: the kernel was stopped"
    except (CellTimeoutError, DeadKernelError) as error:
        problem = f"the kernel stopped ({type(error).__name__})"
    except Exception as error:  # the notebook could not be run at all
        problem = f"the notebook could not run ({type(error).__name__}: {str(error)[:300]})"
    text = "".join(out.get("text", "") for out in notebook.cells[-1].get("outputs", [])
                   if out.get("output_type") == "stream")
    line = next((ln for ln in reversed(text.splitlines()) if ln.startswith(_extract.MARK)), "")
    return {"errors": _errors(notebook, count), "problem": problem,
            "sources": line[len(_extract.MARK):], "dropped": client.dropped}


def main(path):
    job = json.loads(Path(path).read_text(encoding="utf-8"))
    result = run(job)
    Path(job["result"]).write_text(json.dumps(result), encoding="utf-8")


if __name__ == "__main__":
    main(sys.argv[1])
