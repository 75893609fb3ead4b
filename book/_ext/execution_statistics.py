"""How long each notebook took to execute, measured where it was executed, with the machine and its
load: the records, the pytest plugin that takes them in strict nbval, and the Sphinx extension
that takes them in the book build and shows them (the directive ``{execution-statistics}``).

A notebook is executed in a fresh kernel, either by strict nbval (``make notebooks`` and ``make
notebooks-other-machine``, through ``book/conftest.py``, when ``MECHNUM_EXECUTION_RECORD``
names the run's file) or by the book build (``make book``, which executes what its cache
lacks). Both measure the same things and write them in the same form, one JSON file per run in
``_build/execution/``:

* the **wall time** from the kernel's start to its end (nbval: its first cell's setup to its last
  cell's teardown; the book build: the time the notebook executor reports);
* the **CPU time** of the kernel, user and system (what the finished kernel adds to the
  measuring process's ``RUSAGE_CHILDREN``): unlike the wall time, it does not grow when other
  processes share the cores. On a quiet machine the wall time is about the same: a little more
  for the moments the kernel waits for the next cell, less when BLAS computes on two cores;
* the **load average** of the last minute when the notebook started and when it ended (the
  number of processes running or waiting for a core: on a two-core machine, 2 means busy);
* the notebook's SHA-256, so that a record is shown only for the notebook it measured.

The directive renders a table per run: the book build's own records when it executes the
notebooks, the strict nbval runs' when it renders the committed outputs (``execute_notebooks:
off``, as ``make test`` builds the book after strict nbval has checked them).
"""

import datetime
import hashlib
import json
import os
import platform
import posixpath
import resource
import time
from pathlib import Path

import pytest
from docutils import nodes
from myst_nb.sphinx_ import NbMetadataCollector
from sphinx.addnodes import pending_xref
from sphinx.transforms.post_transforms import SphinxPostTransform
from sphinx.util.docutils import SphinxDirective

FOLDER = "_build/execution"
"""Where the runs' records are, relative to the project's root."""
BOOK_RUN = "book.json"
"""The record file of the book build, beside strict nbval's."""
ARITHMETIC = ("OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES", "OPENBLAS_NUM_THREADS")
"""The environment variables that change the arithmetic of a run (Makefile: OTHER_MACHINE)."""


def digest(path):
    """The SHA-256 of a file's bytes, in hex."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def machine():
    """The processor's model name and the number of its logical cores."""
    names = [line.split(":", 1)[1].strip() for line in _cpuinfo() if line.startswith("model name")]
    return f"{names[0] if names else platform.processor() or 'unknown processor'}, " \
           f"{os.cpu_count()} logical cores"


def _cpuinfo():
    try:
        return Path("/proc/cpuinfo").read_text().splitlines()
    except OSError:
        return []


class Stopwatch:
    """Times one notebook's execution from its creation to :meth:`stop` (see the module)."""

    def __init__(self, path):
        self.path, self.started = Path(path), time.time()
        self._wall, self._cpu, self._load = time.perf_counter(), _children_cpu(), os.getloadavg()[0]

    def stop(self, wall=None):
        """The record (``wall``: the executor's own wall time, when it reports one)."""
        return {"sha256": digest(self.path),
                "started": datetime.datetime.fromtimestamp(self.started).isoformat("T", "seconds"),
                "wall": round(time.perf_counter() - self._wall if wall is None else wall, 2),
                "cpu": round(_children_cpu() - self._cpu, 2),
                "load": [round(self._load, 2), round(os.getloadavg()[0], 2)]}


def _children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def save(file, records):
    """Add ``records`` (notebook path -> record) to the run's file, with this machine and this
    run's arithmetic; records of other notebooks in the file are kept."""
    file = Path(file)
    run = read(file) or {"notebooks": {}}
    run["notebooks"].update(records)
    run["machine"] = machine()
    run["arithmetic"] = {k: os.environ[k] for k in ARITHMETIC if k in os.environ}
    file.parent.mkdir(parents=True, exist_ok=True)
    file.write_text(json.dumps(run, indent=1, sort_keys=True), encoding="utf-8")


def read(file):
    """The run recorded in ``file``, or None."""
    try:
        return json.loads(Path(file).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def current(run, root, notebook):
    """The run's record of ``notebook`` (a path relative to ``root``) if it measured the notebook
    as it is now, else None."""
    record = run["notebooks"].get(str(notebook))
    return record if record and record["sha256"] == digest(Path(root) / notebook) else None


def measured(root, notebook, folder=FOLDER):
    """``(run file name, record)`` of every run in ``root/folder`` that measured ``notebook``
    (a path relative to ``root``) as it is now."""
    runs = ((file.name, read(file)) for file in sorted((Path(root) / folder).glob("*.json")))
    return [(name, current(run, root, notebook)) for name, run in runs
            if run and current(run, root, notebook)]


# --- the pytest plugin (book/conftest.py): strict nbval's runs --------------------------------

RECORD = "MECHNUM_EXECUTION_RECORD"
"""The environment variable naming the record file of a strict nbval run (relative to the
project's root); without it nbval records nothing."""
ROOT = Path(__file__).resolve().parents[2]
"""The project's root (book/_ext/ is two folders below it): record keys are relative to it."""
_running, _failed, _records = {}, set(), {}  # by notebook, as pytest's node ids begin


def _notebook(node_id):
    return node_id.split("::")[0]


@pytest.hookimpl(wrapper=True)
def pytest_runtest_setup(item):
    if os.environ.get(RECORD) and item.path.suffix == ".ipynb":
        _running.setdefault(_notebook(item.nodeid), Stopwatch(item.path))  # before its kernel
    return (yield)


@pytest.hookimpl(wrapper=True)
def pytest_runtest_teardown(item, nextitem):
    result = yield
    notebook = _notebook(item.nodeid)
    if notebook in _running and (nextitem is None or _notebook(nextitem.nodeid) != notebook):
        record = _running.pop(notebook).stop()                # its kernel has stopped
        if notebook not in _failed:                           # only what strict nbval passed
            _records[str(item.path.relative_to(ROOT))] = record
    return result


def pytest_runtest_logreport(report):
    if report.failed:
        _failed.add(_notebook(report.nodeid))


def pytest_sessionfinish(session):
    if os.environ.get(RECORD) and _records:
        save(ROOT / os.environ[RECORD], _records)


# --- the Sphinx extension: the book build's runs, and the directive ----------------------------

class Placeholder(nodes.General, nodes.Element):
    """Where the tables go, once every notebook has been read (and executed)."""


class Directive(SphinxDirective):
    """``{execution-statistics}``: the tables of the runs that measured this build's notebooks."""

    def run(self):
        self.env.execution_statistics_pages = \
            getattr(self.env, "execution_statistics_pages", set()) | {self.env.docname}
        return [Placeholder()]


class Render(SphinxPostTransform):
    default_priority = 8  # before the cross-references are resolved (10)

    def run(self, **kwargs):
        for node in list(self.document.findall(Placeholder)):
            node.replace_self(_tables(self.app, self.env.docname))


def setup(app):
    app.add_node(Placeholder)
    app.add_directive("execution-statistics", Directive)
    app.add_post_transform(Render)
    app.connect("source-read", _start)
    app.connect("doctree-read", _stop)
    app.connect("env-get-outdated", lambda app, env, *changes:
                sorted(getattr(env, "execution_statistics_pages", ())))
    return {"parallel_read_safe": False, "parallel_write_safe": True}


def _folder(app):
    return Path(app.srcdir) / FOLDER


def _executing(app):
    return app.config.nb_execution_mode not in ("off", False)


_reading = {}


def _start(app, docname, source):
    path = Path(app.env.doc2path(docname))
    if _executing(app) and path.suffix == ".ipynb":
        _reading[docname] = Stopwatch(path)


def _stop(app, doctree):
    docname = app.env.docname
    watch = _reading.pop(docname, None)
    executed = NbMetadataCollector.get_exec_data(app.env, docname)
    if watch is None or not executed or not executed["succeeded"]:
        return
    key, file = str(watch.path.relative_to(app.srcdir)), _folder(app) / BOOK_RUN
    if executed["mtime"] >= watch.started:        # executed now, not taken from the cache
        record = watch.stop(wall=executed["runtime"])
    else:  # from the cache: the record of the build that executed it, if it took one
        record = (read(file) or {}).get("notebooks", {}).get(key)
        if not record or record["wall"] != round(executed["runtime"], 2):
            return
        record["sha256"] = digest(watch.path)     # its code, which the cache matched, is unchanged
    save(file, {key: record})


def _tables(app, docname):
    """The paragraphs and tables that replace the directive."""
    files = sorted(_folder(app).glob("*.json"))
    files = [f for f in files if (f.name == BOOK_RUN) == _executing(app)]
    notebooks = {page: Path(app.env.doc2path(page)).relative_to(app.srcdir)
                 for page in sorted(app.env.found_docs)
                 if Path(app.env.doc2path(page)).suffix == ".ipynb"}
    out = []
    for file in files:
        run = read(file) or {"notebooks": {}}
        rows = [(page, current(run, app.srcdir, path)) for page, path in notebooks.items()]
        rows = [(page, record) for page, record in rows if record]
        if rows:
            out += [nodes.paragraph(text=_describe(file.name, run, rows)),
                    _table(docname, rows)]
    if not out:
        out.append(nodes.paragraph(text=(
            "No execution of these pages, as they are now, was measured: this build rendered "
            "the outputs committed with them without executing them, and no run of strict nbval "
            "recorded in _build/execution measured them since they last changed.")))
    return out


def _describe(name, run, rows):
    who = ("Executed by the book build" if name == BOOK_RUN else
           f"Executed by strict nbval (make {Path(name).stem})")
    arithmetic = ", ".join(f"{k}={v}" for k, v in sorted(run["arithmetic"].items()))
    first, last = (min(r["started"] for _, r in rows).split("T"),
                   max(r["started"] for _, r in rows).split("T"))
    when = (f"on {first[0]}, the notebooks starting between {first[1]} and {last[1]}"
            if first[0] == last[0] else f"from {' '.join(first)} to {' '.join(last)}")
    how = f"another machine's arithmetic ({arithmetic})" if arithmetic else "its own arithmetic"
    return f"{who}, with {how}, on {run['machine']}, {when}:"


def _table(docname, rows):
    header = ["page", "wall time (s)", "CPU time (s)", "load average, start → end"]
    table, group = nodes.table(classes=["colwidths-auto"]), nodes.tgroup(cols=len(header))
    table += group
    group += [nodes.colspec(colwidth=1) for _ in header]
    body = nodes.tbody()
    group += [nodes.thead("", _row([nodes.Text(h) for h in header])), body]
    for page, record in rows:
        link = pending_xref(refdoc=docname, reftype="doc", refdomain="std", refexplicit=True,
                            reftarget="/" + page, refwarn=True)
        link += nodes.inline(text=posixpath.basename(page))
        start, end = record["load"]
        body += _row([link, nodes.Text(f"{record['wall']:.1f}"),
                      nodes.Text(f"{record['cpu']:.1f}"), nodes.Text(f"{start:.1f} → {end:.1f}")])
    return table


def _row(cells):
    return nodes.row("", *[nodes.entry("", nodes.paragraph("", "", cell)) for cell in cells])
