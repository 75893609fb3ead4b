"""Proofs, not samples: every root of a system in a box, certified by interval arithmetic.

Newton's method from many starts finds roots; it cannot show that there are no others. Interval
arithmetic can. With balls from Arb (``python-flint``; every operation rounded outward, so a
ball always holds the exact result), a function's value over a whole box is enclosed, and:

* a box over which the residual's enclosure excludes 0 holds **no** root;
* a box that Krawczyk's operator maps into its own interior holds **exactly one**;
* any other box is cut in two, and the search goes on
  (:func:`~mechnum.certify.roots`: branch and prune).

When no box is left undecided the count of roots is a theorem over the box: ``complete``. It
holds for the functions that the given ``residual`` and ``jacobian`` enclose; they are handed
balls that refuse to leave ball arithmetic (:class:`~mechnum.certify.Ball`; what stays the
caller's responsibility is that the residual computes on them as on numbers). The rods'
enclosures are in :mod:`mechnum.rods.certified`, and the applications
:func:`~mechnum.rods.certify_pinned`, ``rfr2.certify_forward`` and ``pfr3.certify_forward``.
A search's **certificate** (its leaves and the test each passed, and its ``scope``: ``"all"``
roots of a domain, or the ``"existence"`` of the roots found) is stored as JSON and re-checked
by :func:`~mechnum.certify.verify`, in one evaluation per leaf, against the caller's own
functions and domain; :func:`~mechnum.certify.definite` proves a symmetric interval matrix
positive definite (or not), for certified stability.

The search (:func:`roots`, :class:`Roots`), its certificate (:class:`Certificate`), its
re-check (:func:`verify`, :class:`Verified`), the guard of what a residual is handed
(:class:`Ball`) and Krawczyk's tests of one box are this package's private modules; the interval
arithmetic the rods' and the mechanisms' enclosures share is :mod:`mechnum.certify.balls`.

Examples
--------
>>> from mechnum import certify
>>> f = lambda X: [X[0] ** 3 - X[0]]              # roots -1, 0 and 1
>>> J = lambda X: [[3 * X[0] ** 2 - 1]]
>>> r = certify.roots(f, J, [[-2.0, 2.0]])
>>> r.count, r.complete, certify.verify(r.certificate(), f, J, domain=[[-2.0, 2.0]]).count
(3, True, 3)
"""

from mechnum.certify import balls
from mechnum.certify._certificate import Certificate, CertificateError

# An import ``X as X``: a result that a function here returns, documented with it (book/api.md)
# but not in __all__ (returned, never called: mechnum.results.Result is its interface).
from mechnum.certify._certificate import Leaf as Leaf
from mechnum.certify._definite import definite
from mechnum.certify._guard import Ball as Ball
from mechnum.certify._guard import BallArithmeticError, ResidualError
from mechnum.certify._search import MAX_BOXES, MAX_BOXES_LIMIT, roots
from mechnum.certify._search import Roots as Roots
from mechnum.certify._verify import Verified as Verified
from mechnum.certify._verify import verify

# The errors a caller catches show their public home in tracebacks.
for _error in (BallArithmeticError, CertificateError, ResidualError):
    _error.__module__ = __name__
del _error

__all__ = ["MAX_BOXES", "MAX_BOXES_LIMIT", "BallArithmeticError", "Certificate",
           "CertificateError", "ResidualError", "balls", "definite", "roots", "verify"]
