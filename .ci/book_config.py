"""Write a copy of ``_config.yml`` with some values changed, for a build of the book that differs
from ``make book`` in those values only (``make book-committed``, ``make pdf``).

Usage: ``python .ci/book_config.py OUT KEY=VALUE ...``, each KEY a dotted path into the
configuration (``execute.execute_notebooks``), each VALUE read as YAML. The folders of the local
extensions are made absolute, since Jupyter Book reads them relative to the configuration file.
"""

import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]

out, *changes = sys.argv[1:]
config = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
for change in changes:
    keys, value = change.split("=", 1)
    *path, last = keys.split(".")
    node = config
    for key in path:
        node = node[key]
    node[last] = yaml.safe_load(value)
sphinx = config["sphinx"]
sphinx["local_extensions"] = {name: str((ROOT / folder).resolve())
                              for name, folder in sphinx["local_extensions"].items()}
Path(out).parent.mkdir(parents=True, exist_ok=True)
Path(out).write_text(yaml.safe_dump(config), encoding="utf-8")
