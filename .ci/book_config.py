"""Write a copy of ``_config.yml`` with some values changed, for a build of the book that differs
from ``make book`` in those values only (``make book-committed``, ``make pdf``, the students'
edition).

Usage: ``python .ci/book_config.py [--from CONFIG] OUT KEY=VALUE KEY+=TEXT ...``, each KEY a
dotted path into the configuration (``execute.execute_notebooks``), each VALUE read as YAML,
each TEXT appended to the string already there. ``--from`` reads another configuration than
the repository's ``_config.yml``. The folders of the local extensions are made absolute, since
Jupyter Book reads them relative to the configuration file.
"""

import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]

arguments = sys.argv[1:]
source = ROOT / "_config.yml"
if arguments[0] == "--from":
    source, arguments = Path(arguments[1]), arguments[2:]
out, *changes = arguments
config = yaml.safe_load(source.read_text(encoding="utf-8"))
for change in changes:
    keys, value = change.split("=", 1)
    append = keys.endswith("+")
    *path, last = keys.rstrip("+").split(".")
    node = config
    for key in path:
        node = node[key]
    node[last] = node[last] + value if append else yaml.safe_load(value)
sphinx = config["sphinx"]
sphinx["local_extensions"] = {name: str((ROOT / folder).resolve())
                              for name, folder in sphinx["local_extensions"].items()}
Path(out).parent.mkdir(parents=True, exist_ok=True)
Path(out).write_text(yaml.safe_dump(config), encoding="utf-8")
