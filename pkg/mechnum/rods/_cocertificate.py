"""The certificate of a co-refinement, and its verifier, which repeats every test it needs.

A :class:`CoCertificate` (:meth:`~mechnum.rods._cosearch.CertifiedAll.certificate`) stores what a
co-refinement (:mod:`mechnum.rods._corefine`) **chose**: the first grid, the axis of every cut
of every round, the boxes in which each round's clusters were settled, and the certificate of
the final Krawczyk search of those boxes (:class:`mechnum.certify.Certificate`);
with, per round, the tuples tested, left live and dropped by each reason, and the count.

:func:`verify` trusts none of it: from the mechanism's rods (with their a-priori bounds,
derived again by the caller) and equations, it rebuilds the grid, re-encloses every box, cuts
it where the certificate says (any cut is a valid one: the two halves cover the box), tests
every tuple again and drops the live tuples that each round's settled boxes cover; it then
checks that no live tuple is left, and re-checks the Krawczyk certificate against the settled
boxes as its domain, scope ``"all"`` (:func:`mechnum.certify.verify`: exactly those boxes
searched, none overlapping another, every leaf's test re-run). The count and
``complete`` it derives must be the stored ones, and so must every round's summary: a
certificate whose numbers differ from what its choices imply is rejected
(:class:`mechnum.certify.CertificateError`, naming the difference).
"""

import json
import time
from dataclasses import dataclass, field

import numpy as np

from mechnum import certify
from mechnum.certify import CertificateError
from mechnum.rods._corefine import Refinement, checked

FORMAT = "mechnum-corefinement-1"
SCOPES = ("all",)


@dataclass(frozen=True)
class CoCertificate:
    """What a co-refinement chose and found, to re-check with :func:`verify`.

    Attributes
    ----------
    grid : (int, int)
    dims : tuple of tuple of str
        Per round and rod, the axis of each cut (``"0"``: psi, ``"1"``: t).
    resolved : tuple of ndarray
        Per round, the boxes in which clusters were settled (the last: those left at the end).
    rounds : tuple of dict
        Per round: ``tested``, ``live`` and ``dropped`` (tuples, by reason).
    search : mechnum.certify.Certificate
        The Krawczyk search of every settled box.
    count : int
        Equilibria proven.
    complete : bool
        ``count`` is every equilibrium of the searched domain.
    scope : str
        ``"all"``: what ``complete`` claims is every equilibrium in the domain.
    inputs, work : dict
        What was searched (the caller's, to rebuild the mechanism) and the work done.
    """

    grid: tuple
    dims: tuple
    resolved: tuple
    rounds: tuple
    search: object
    count: int
    complete: bool
    scope: str = "all"
    inputs: dict = field(default_factory=dict)
    work: dict = field(default_factory=dict)

    def to_json(self):
        """The certificate as JSON text (floats exact)."""
        return json.dumps({
            "format": FORMAT, "scope": self.scope, "inputs": self.inputs, "work": self.work,
            "count": int(self.count), "complete": bool(self.complete),
            "grid": list(self.grid), "dims": [list(d) for d in self.dims],
            "resolved": [np.asarray(r, dtype=float).tolist() for r in self.resolved],
            "rounds": [{k: h[k] for k in ("tested", "live", "dropped")} for h in self.rounds],
            "search": json.loads(self.search.to_json())})

    @classmethod
    def from_json(cls, text):
        """A certificate from :meth:`to_json`'s text.

        Raises
        ------
        CertificateError
            If the text is not a certificate of this format.
        """
        try:
            data = json.loads(text)
            if not isinstance(data, dict) or data.get("format") != FORMAT:
                raise CertificateError(f"not a {FORMAT} certificate")
            if data.get("scope") not in SCOPES:
                raise CertificateError(f"unknown scope {data.get('scope')!r}")
            search = certify.Certificate.from_json(json.dumps(data["search"]))
            n = np.shape(search.boxes)[1:]
            return cls(tuple(int(g) for g in data["grid"]),
                       tuple(tuple(str(x) for x in d) for d in data["dims"]),
                       tuple(np.array(r, dtype=float).reshape((-1,) + n)
                             for r in data["resolved"]),
                       tuple(dict(h) for h in data["rounds"]), search, int(data["count"]),
                       bool(data["complete"]), data["scope"], dict(data["inputs"]),
                       dict(data["work"]))
        except (KeyError, TypeError, ValueError, AttributeError, RecursionError) as error:
            raise CertificateError(f"a malformed co-refinement certificate: {error}") from error

    def save(self, path):
        """Write :meth:`to_json` to ``path``."""
        with open(path, "w", encoding="utf-8") as out:
            out.write(self.to_json())

    @classmethod
    def load(cls, path):
        """Read a certificate that :meth:`save` wrote."""
        with open(path, encoding="utf-8") as text:
            return cls.from_json(text.read())


def certificate(result, inputs=None):
    """The :class:`CoCertificate` of a :class:`~mechnum.rods._cosearch.CoRefined`."""
    return CoCertificate(result.grid, result.dims, result.resolved, result.rounds,
                         result.search.certificate(), result.count, result.complete, "all",
                         dict(inputs or {}),
                         {"rounds": result.iterations, "seconds": round(result.seconds, 1),
                          "evaluations": int(result.nfev),
                          "boxes": int(result.rounds[-1]["boxes"]),
                          "probes": int(result.probes)})


@dataclass(frozen=True)
class CoVerified:
    """What :func:`verify` re-proved.

    Attributes
    ----------
    count : int
    scope : str
        ``"all"``: ``complete`` speaks of every equilibrium of the domain.
    complete : bool
    roots : ndarray, shape (count, 2 r, 2)
    rounds : int
    evaluations : int
        Evaluations of the rods' enclosures.
    seconds : float
    """

    count: int
    scope: str
    complete: bool
    roots: np.ndarray
    rounds: int
    evaluations: int
    seconds: float


def _same(summary, stored, r):
    for key in ("tested", "live"):
        if summary[key] != stored.get(key):
            raise CertificateError(f"round {r}: {summary[key]} tuples {key}, the certificate "
                                   f"says {stored.get(key)}")
    mine = {k: v for k, v in summary["dropped"].items() if v}
    theirs = {k: v for k, v in dict(stored.get("dropped") or {}).items() if v}
    if mine != theirs:
        raise CertificateError(f"round {r}: dropped {mine}, the certificate says {theirs}")


def verify(cert, rods, assembly, residual, jacobian, exclude=None, split=None):
    """Re-check a co-refinement's certificate (see the module).

    Parameters
    ----------
    cert : CoCertificate
    rods : sequence of mechnum.rods._leaves.ChartRod
        The mechanism's rods, their domains derived by the caller (not read from ``cert``).
    assembly : mechnum.rods._tuples.Assembly
    residual, jacobian, exclude, split : callable
        The mechanism's equations over boxes, as given to the search.

    Returns
    -------
    CoVerified

    Raises
    ------
    CertificateError
        If a round's numbers, the settled boxes, the Krawczyk certificate or the count differ
        from what the certificate says.
    """
    if not isinstance(cert, CoCertificate):
        raise ValueError(f"cert must be a CoCertificate, got {type(cert).__name__}")
    rods, assembly, _ = checked(rods, assembly, (residual, jacobian, exclude, split))
    start = time.perf_counter()
    if len(cert.rounds) != len(cert.dims) + 1 or len(cert.resolved) not in (
            len(cert.dims) + 1, len(cert.dims) + 2):
        raise CertificateError(f"{len(cert.dims)} rounds of cuts, {len(cert.rounds)} summaries "
                               f"and {len(cert.resolved)} sets of settled boxes do not match")
    try:
        state = Refinement(rods, assembly, cert.grid)
        _same(state.history[0], cert.rounds[0], 0)
        state.resolve(cert.resolved[0])
        for r, axes in enumerate(cert.dims, start=1):
            if len(axes) != len(rods):
                raise CertificateError(f"round {r} cuts {len(axes)} rods, not {len(rods)}")
            state.step(axes)
            _same(state.history[-1], cert.rounds[r], r)
            state.resolve(cert.resolved[r])
        if len(cert.resolved) == len(cert.dims) + 2:
            state.resolve(cert.resolved[-1], final=True)
    except ValueError as error:
        raise CertificateError(f"the certificate's cuts cannot be made: {error}") from error
    settled = state.resolved_hulls()
    found = certify.verify(cert.search, residual, jacobian, exclude, domain=settled,
                           scope="all")
    complete = bool(found.complete) and not len(state.live)
    if found.count != cert.count or complete != cert.complete:
        raise CertificateError(f"the certificate proves {found.count} equilibria (complete: "
                               f"{complete}, {len(state.live)} tuples left), it says "
                               f"{cert.count} (complete: {cert.complete})")
    return CoVerified(found.count, "all", complete, found.roots, len(cert.dims),
                      sum(x.evaluations for x in state.leaves), time.perf_counter() - start)
