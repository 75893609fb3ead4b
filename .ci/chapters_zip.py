"""Write the chapters' zip that the page "Run the chapters yourself" serves (``make downloads``,
``make book-student``): every notebook of a book folder with every file a notebook reads or
cites, at the paths the notebooks use.

Usage: ``python .ci/chapters_zip.py BOOK_FOLDER ZIP``

What a notebook reads is listed once, here, in :data:`SERVED`: the book's module ``published``
(the registry's rules, which every chapter imports), the registry and its findings (the study
pages and the appendix), the stored certificates (Chapters 3, 5 and 6 and the study
page of Chapter 3 verify them) and the bibliography the chapters cite. The script that recomputes
the certificates (``make certify``) is the repository's, not the reader's. A pattern that
matches no file is an error, so that a renamed file cannot silently leave the zip;
``tests/test_downloads.py`` runs every served notebook from the unpacked zip.
"""

import sys
import zipfile
from pathlib import Path

SERVED = ("*.ipynb", "published.py", "published_values.csv", "findings.csv", "references.bib",
          "certificates/*.json")


def served_files(book):
    """The files of ``book`` that the zip serves, in a stable order."""
    files = []
    for pattern in SERVED:
        found = sorted(book.glob(pattern))
        if not found:
            raise SystemExit(f"{book}: no file matches {pattern!r}, which the chapters need")
        files += found
    return files


def main(book, out):
    book, out = Path(book), Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
        for path in served_files(book):
            archive.write(path, path.relative_to(book).as_posix())


if __name__ == "__main__":
    main(*sys.argv[1:])
