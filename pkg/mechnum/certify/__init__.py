"""Proofs, not samples: every root of a system in a box, certified by interval arithmetic.

Newton's method from many starts finds roots; it cannot show that there are no others. Interval
arithmetic can. With balls from Arb (``python-flint``; every operation rounded outward, so a
ball always holds the exact result), a function's value over a whole box is enclosed, and:

* a box over which the residual's enclosure excludes 0 holds **no** root;
* a box that Krawczyk's operator maps into its own interior holds **exactly one**
  (:mod:`mechnum.certify.krawczyk`);
* any other box is cut in two, and the search goes on
  (:func:`~mechnum.certify.search.roots`: branch and prune).

When no box is left undecided the count of roots is a theorem over the box: ``complete``. It
holds for the functions that the given ``residual`` and ``jacobian`` enclose; they are handed
balls that refuse to leave ball arithmetic (:mod:`mechnum.certify.guard`, which also says what
stays the caller's responsibility). The mechanisms' enclosures are in :mod:`mechnum.rods.balls`
and the applications :func:`~mechnum.rods.certified.certify_pinned`, ``rfr2.certify_forward``
and ``pfr3.certify_forward``. A search's **certificate** (its leaves and the test each passed,
and its ``scope``: ``"all"`` roots of a domain, or the ``"existence"`` of the roots found) is
stored as JSON and re-checked by :func:`~mechnum.certify.verify.verify`, in one evaluation per
leaf, against the caller's own functions and domain;
:func:`~mechnum.certify.definite.definite` proves a symmetric interval matrix positive definite
(or not), for certified stability.

Modules: :mod:`~mechnum.certify.balls` (intervals as balls, tight over wide boxes),
:mod:`~mechnum.certify.guard` (the balls a residual is handed, and the checks of what it
returns), :mod:`~mechnum.certify.krawczyk` (the tests of one box),
:mod:`~mechnum.certify.search` (:func:`~mechnum.certify.search.roots`,
:class:`~mechnum.certify.search.Roots`), :mod:`~mechnum.certify.certificate`
(:class:`~mechnum.certify.certificate.Certificate`), :mod:`~mechnum.certify.verify`
(:func:`~mechnum.certify.verify.verify`) and :mod:`~mechnum.certify.definite`; and
:func:`~mechnum.certify.clusters`, :func:`~mechnum.certify.hulls` and
:func:`~mechnum.certify.subtract`, the geometry of sets of boxes that a search over several
boxes needs (:mod:`mechnum.certify._clusters`).

Examples
--------
>>> from mechnum import certify
>>> f = lambda X: [X[0] ** 3 - X[0]]              # roots -1, 0 and 1
>>> J = lambda X: [[3 * X[0] ** 2 - 1]]
>>> r = certify.roots(f, J, [[-2.0, 2.0]])
>>> r.count, r.complete, certify.verify(r.certificate(), f, J, domain=[[-2.0, 2.0]]).count
(3, True, 3)
"""

from mechnum.certify._clusters import clusters, hulls, subtract
from mechnum.certify.balls import ball, bounds
from mechnum.certify.certificate import Certificate, CertificateError, Leaf
from mechnum.certify.definite import definite
from mechnum.certify.guard import Ball, BallArithmeticError, ResidualError
from mechnum.certify.search import MAX_BOXES, MAX_BOXES_LIMIT, MIN_WIDTH, Roots, roots
from mechnum.certify.verify import Verified, verify

__all__ = ["Ball", "BallArithmeticError", "Certificate", "CertificateError", "Leaf",
           "MAX_BOXES", "MAX_BOXES_LIMIT", "MIN_WIDTH", "ResidualError", "Roots", "Verified",
           "ball", "bounds", "clusters", "definite", "hulls", "roots", "subtract", "verify"]
