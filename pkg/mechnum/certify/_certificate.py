"""Certificates: the leaves of a search with the test each passed, to store and to re-check.

A certificate holds the searched boxes and, for each, its **leaves** in depth-first order:
disjoint boxes whose union is the searched box, each with the test that decided it
(:mod:`mechnum.certify`) and, for Krawczyk's test, the box it was proven on (the leaf
itself, or the leaf enlarged, inside the searched box, when its root sits near a face) and an
enclosure of its root. It says what it proves in one field, ``scope``:

* ``"all"``: the boxes are the whole domain of the question, and ``complete`` (no leaf
  undecided) makes ``count`` the number of roots in it;
* ``"existence"``: the roots counted exist, each alone in its enclosure; nothing is said of
  any other root (the boxes are, for example, small boxes around sampled roots). Such a
  certificate has no ``complete``.

``search`` names the search that made it (``SEARCH``), so that
other searches can store their own certificates in this format. Nothing stored is trusted:
:func:`~mechnum.certify.verify` re-derives the roots, the count, ``complete`` and the
cover from the leaves and the caller's functions and domain, and compares.

JSON (:meth:`~mechnum.certify.Certificate.to_json`): floats are written with
Python's shortest round-trip ``repr``, so every leaf comes back bit for bit;
:meth:`~mechnum.certify.Certificate.from_json` checks every key, type and shape and
raises :class:`CertificateError` naming what is wrong.

Examples
--------
>>> import numpy as np
>>> leaf = Leaf(np.array([[0.0, 1.0]]), "residual")
>>> cert = Certificate(boxes=[[[0.0, 1.0]]], leaves=[[leaf]], roots=[], count=0,
...                    scope="all", complete=True, search="by hand")
>>> Certificate.from_json(cert.to_json()).count
0
>>> Certificate.from_json('{"format": "' + FORMAT + '", "count": "seven"}')
Traceback (most recent call last):
...
mechnum.certify.CertificateError: a malformed certificate: missing keys \
['boxes', 'complete', 'inputs', 'leaves', 'roots', 'scope', 'search', 'work']
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from os import PathLike

import numpy as np

from mechnum.errors import MechnumError

__all__ = ["EXCLUSIONS", "FORMAT", "KEYS", "SCOPES", "TESTS", "Certificate", "CertificateError",
           "Leaf"]

EXCLUSIONS = ("residual", "exclude", "mean-value", "krawczyk-exclusion")
TESTS = EXCLUSIONS + ("krawczyk", "undecided")
SCOPES = ("all", "existence")
FORMAT = "mechnum-certificate-2"
KEYS = ("format", "scope", "search", "count", "complete", "roots", "boxes", "leaves", "inputs",
        "work")


class CertificateError(MechnumError):
    """A certificate that does not prove what it says (a leaf's test fails, the leaves do not
    cover the box, the domain, count, scope or roots are not the ones derived), or that is not
    a certificate at all (malformed JSON, a wrong type, a missing key)."""


def _malformed(what):
    return CertificateError(f"a malformed certificate: {what}")


def _floats(value, shape, name):
    """``value`` (nested lists of numbers) as a finite float array of ``shape`` (None: any
    length), every interval ``lo <= hi``."""
    depth = len(shape)

    def walk(v, level):
        if level == depth:
            if type(v) not in (int, float):
                raise _malformed(f"{name} holds {type(v).__name__} {v!r}, not a number")
            return
        if not isinstance(v, (list, tuple, np.ndarray)):
            raise _malformed(f"{name} must be nested lists {depth} deep, got "
                             f"{type(v).__name__} at depth {level}")
        for item in v:
            walk(item, level + 1)

    if isinstance(value, np.ndarray):
        array = value.astype(float) if value.dtype.kind in "iuf" else None
        if array is None:
            raise _malformed(f"{name} must be numbers, got an array of {value.dtype}")
    else:
        walk(value, 0)
        try:
            array = np.array(value, dtype=float)
        except ValueError:
            raise _malformed(f"{name} is ragged (rows of different lengths)") from None
        except OverflowError:
            raise _malformed(f"{name} holds an integer beyond the float range") from None
    if len(shape) == 3 and array.size == 0 and array.ndim < 3:
        array = array.reshape(0, *(s or 0 for s in shape[1:]))
    if array.ndim != depth or any(s is not None and s != a for s, a in zip(shape, array.shape)):
        raise _malformed(f"{name} must have shape {shape}, got {array.shape}")
    if not np.all(np.isfinite(array)) or np.any(array[..., 0] > array[..., 1]):
        raise _malformed(f"{name} must be finite intervals [lo, hi] with lo <= hi")
    return array


@dataclass(frozen=True)
class Leaf:
    """One leaf of a search.

    Attributes
    ----------
    box : ndarray, shape (n, 2)
        The leaf (float intervals).
    test : str
        ``"residual"``, ``"exclude"``, ``"mean-value"``, ``"krawczyk-exclusion"`` (no root),
        ``"krawczyk"`` (exactly one root in ``test_box``) or ``"undecided"``.
    test_box : ndarray, shape (n, 2) or None
        For ``"krawczyk"``: the box on which Krawczyk's test passed (it contains ``box`` and
        lies in the searched box).
    enclosure : ndarray, shape (n, 2) or None
        For ``"krawczyk"``: a box in ``test_box`` that holds its root: ``K(test_box)`` or a
        tighter box that Krawczyk's operator maps into its own interior.
    reason : str or None
        For ``"undecided"``: why.
    """

    box: np.ndarray
    test: str
    test_box: np.ndarray = None
    enclosure: np.ndarray = None
    reason: str = None

    def __post_init__(self):
        if self.test not in TESTS:
            raise _malformed(f"a leaf's test must be one of {list(TESTS)}, got {self.test!r}")
        box = _floats(self.box, (None, 2), "a leaf's box")
        object.__setattr__(self, "box", box)
        n = len(box)
        proven = self.test == "krawczyk"
        for name in ("test_box", "enclosure"):
            value = getattr(self, name)
            if proven != (value is not None):
                raise _malformed(f"a {self.test!r} leaf {'needs' if proven else 'has no'} "
                                 f"{name}")
            if value is not None:
                object.__setattr__(self, name, _floats(value, (n, 2), f"a leaf's {name}"))
        if self.reason is not None and (self.test != "undecided" or not isinstance(
                self.reason, str)):
            raise _malformed(f"only an undecided leaf has a reason (text), got "
                             f"{self.reason!r} on a {self.test!r} leaf")

    def to_dict(self) -> dict:
        """The leaf as JSON-ready data (the fields that are set)."""
        data = {"box": self.box.tolist(), "test": self.test}
        for name in ("test_box", "enclosure"):
            if getattr(self, name) is not None:
                data[name] = getattr(self, name).tolist()
        if self.reason is not None:
            data["reason"] = self.reason
        return data

    @classmethod
    def from_dict(cls, data: dict) -> "Leaf":
        """A leaf from :meth:`to_dict`'s data (checked)."""
        if not isinstance(data, dict):
            raise _malformed(f"a leaf must be an object, got {type(data).__name__}")
        unknown = set(data) - {"box", "test", "test_box", "enclosure", "reason"}
        if unknown or "box" not in data or "test" not in data:
            raise _malformed(f"a leaf has the keys box, test and optionally test_box, "
                             f"enclosure, reason; got {sorted(data)}")
        if not isinstance(data["test"], str):
            raise _malformed(f"a leaf's test must be text, got {data['test']!r}")
        return cls(data["box"], data["test"], data.get("test_box"), data.get("enclosure"),
                   data.get("reason"))


@dataclass(frozen=True, kw_only=True)
class Certificate:
    """The leaves of a search, storable as JSON and re-checkable by
    :func:`~mechnum.certify.verify`. Every field is checked on construction
    (:class:`CertificateError`).

    Attributes
    ----------
    boxes : ndarray, shape (m, n, 2)
        The searched boxes.
    leaves : tuple of tuple of Leaf
        For each searched box, its leaves in depth-first order.
    roots : ndarray, shape (c, n, 2)
        The enclosures of the distinct roots.
    count : int
        The number of roots the certificate claims (``verify`` derives it again).
    scope : str
        ``"all"`` or ``"existence"`` (see the module).
    complete : bool or None
        For ``"all"``: no leaf is undecided, ``count`` is every root in the boxes. None for
        ``"existence"``.
    search : str
        The search that made it.
    inputs : dict
        What was searched (the application's inputs), JSON-serialisable.
    work : dict
        ``boxes``, ``nfev``, ``njev``, ``seconds`` of the search.
    """

    boxes: np.ndarray
    leaves: tuple
    roots: np.ndarray
    count: int
    scope: str
    search: str
    complete: bool = None
    inputs: dict = field(default_factory=dict)
    work: dict = field(default_factory=dict)

    def __post_init__(self):
        boxes = _floats(self.boxes, (None, None, 2), "boxes")
        n = boxes.shape[1]
        if type(self.count) is not int or self.count < 0:
            raise _malformed(f"count must be an integer >= 0, got {self.count!r}")
        if self.scope not in SCOPES:
            raise _malformed(f"scope must be one of {list(SCOPES)}, got {self.scope!r}")
        if (self.scope == "all") != (type(self.complete) is bool):
            raise _malformed(f"complete is a bool for scope 'all' and absent for "
                             f"'existence', got complete={self.complete!r} with scope "
                             f"{self.scope!r}")
        for name, kind in (("search", str), ("inputs", dict), ("work", dict)):
            if not isinstance(getattr(self, name), kind):
                raise _malformed(f"{name} must be a {kind.__name__}, got "
                                 f"{type(getattr(self, name)).__name__}")
        if not isinstance(self.leaves, (list, tuple)) or not all(
                isinstance(part, (list, tuple)) and all(isinstance(leaf, Leaf) for leaf in part)
                for part in self.leaves):
            raise _malformed("leaves must be a sequence (one per searched box) of sequences "
                             "of Leaf")
        if any(len(leaf.box) != n for part in self.leaves for leaf in part):
            raise _malformed(f"every leaf must have the boxes' {n} coordinates")
        object.__setattr__(self, "boxes", boxes)
        object.__setattr__(self, "leaves", tuple(tuple(part) for part in self.leaves))
        object.__setattr__(self, "roots", _floats(self.roots, (None, n, 2), "roots"))

    def to_json(self) -> str:
        """The certificate as JSON text (floats exact)."""
        data = {"format": FORMAT, "scope": self.scope, "search": self.search,
                "count": self.count, "complete": self.complete,
                "roots": self.roots.tolist(), "boxes": self.boxes.tolist(),
                "leaves": [[leaf.to_dict() for leaf in part] for part in self.leaves],
                "inputs": self.inputs, "work": self.work}
        if self.scope != "all":
            del data["complete"]
        return json.dumps(data)

    @classmethod
    def from_json(cls, text: str) -> "Certificate":
        """A certificate from :meth:`to_json`'s text, every key and value checked.

        Raises
        ------
        CertificateError
            If the text is not JSON, not of this format, or any key is missing, unknown, of
            the wrong type or shape.
        """
        if not isinstance(text, (str, bytes, bytearray)):
            raise _malformed(f"the text must be str or bytes, got {type(text).__name__}")
        try:
            data = json.loads(text)
        except (ValueError, RecursionError) as error:
            raise _malformed(f"not JSON ({type(error).__name__}: {str(error)[:80]})") from None
        if not isinstance(data, dict):
            raise _malformed(f"the JSON must be an object, got {type(data).__name__}")
        if data.get("format") != FORMAT:
            raise CertificateError(f"not a {FORMAT} certificate: format "
                                   f"{str(data.get('format'))[:80]!r} (make certify re-makes "
                                   f"the book's)")
        expected = set(KEYS) - ({"complete"} if data.get("scope") == "existence" else set())
        missing, unknown = sorted(expected - set(data)), sorted(set(data) - expected)
        if missing or unknown:
            raise _malformed(f"missing keys {missing}" if missing else f"unknown keys {unknown}")
        if not isinstance(data["leaves"], list) or not all(
                isinstance(part, list) for part in data["leaves"]):
            raise _malformed("leaves must be a list (one per searched box) of lists")
        leaves = tuple(tuple(Leaf.from_dict(leaf) for leaf in part) for part in data["leaves"])
        return cls(boxes=data["boxes"], leaves=leaves, roots=data["roots"],
                   count=data["count"], scope=data["scope"], complete=data.get("complete"),
                   search=data["search"], inputs=data["inputs"], work=data["work"])

    def save(self, path: str | PathLike) -> None:
        """Write :meth:`to_json` to ``path``."""
        with open(path, "w", encoding="utf-8") as out:
            out.write(self.to_json())

    @classmethod
    def load(cls, path) -> "Certificate":
        """Read a certificate that :meth:`save` wrote (checked as :meth:`from_json`)."""
        with open(path, encoding="utf-8") as text:
            return cls.from_json(text.read())
