"""Every equilibrium of the 3PFR: for given slider inputs (direct), or for a given pose
(inverse).

:func:`~mechnum.mechanisms.pfr3.forward` solves the reduced closed-form system of
:func:`~mechnum.mechanisms.pfr3.forward_system` from many starts at once
(:func:`mechnum.mechanisms._assembly.search`). A uniform sample of the six chart coordinates rarely
lands near the equilibria in which the rods are in strong tension (nearly straight along their
chords, forces tens of times the buckling loads): their basins are narrow in ``psi``, since the
force must point along the chord. The starts therefore come from two physical families, each
built from a random platform pose (centre in the clamps' bounding box, any angle):

* **pulling** rods: each force along its chord, from the clamp to the pin, with a large force
  (``q = t**2 / (1 - t**2)`` log-uniform in ``PULL_Q``);
* **pushing** rods: each force along the chord from the pin to the clamp, with a small to
  moderate force (``q`` log-uniform in ``PUSH_Q``), as in compressed and bent rods;

with random signs of ``t`` (the study's branches of ``k_rel``). On the study's examples every
equilibrium gets at least ~30 hits per 10,000 starts, against none to a few with uniform starts.
:func:`~mechnum.mechanisms.pfr3.inverse` solves the nine equations of
:func:`~mechnum.mechanisms.pfr3.full_system`
in the rods and the sliders at a given pose, from the same two families built from random
slider positions.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms import _assembly as assembly
from mechnum.mechanisms.pfr3 import _model as model
from mechnum.mechanisms.pfr3._analysis import crossings, stability, strain
from mechnum.rods import T_MAX, ClampedRods, in_chart

# q ranges of the starts (q ~ 2 sqrt(R L**2 / EI) for large forces R): pulling rods from about
# the buckling load to ~2e4 EI / L**2 (q = 300), pushing ones from a straight rod (q = 1e-8,
# t = 1e-4) to about twice the buckling load (q = 3).
PULL_Q = (1.0, 300.0)
PUSH_Q = (1e-8, 3.0)
# Newton's step tolerance in the (dimensionless) chart, and its most iterations from a start.
SEARCH_TOL = 1e-12
SEARCH_MAXITER = 40
# Roots closer than this (largest chart coordinate) are one.
SAME = 1e-8
# Default starts: the narrowest basin of the study's examples holds ~4e-3 of them, so 1000
# starts hit every equilibrium ~4 times (and the check of 10,000 ~40 times).
N_STARTS = 1000


def _starts(mech, rng, clamps, pins, q_range, pull):
    """Chart points (m, 6) of rods from ``clamps`` to ``pins`` (m, 3, 2), their forces along
    the chords (``pull``) or against them, ``q`` log-uniform in ``q_range``, random signs."""
    chord = pins - clamps if pull else clamps - pins
    psi = np.mod(np.arctan2(chord[..., 1], chord[..., 0]) - mech.clamp_angles, 2.0 * np.pi)
    q = np.exp(rng.uniform(*np.log(q_range), psi.shape))
    t = rng.choice([-1.0, 1.0], psi.shape) * np.sqrt(q / (1.0 + q))
    z = np.empty((len(psi), 6))
    z[:, 0::2] = np.clip(psi, 1e-6, 2.0 * np.pi - 1e-6)
    z[:, 1::2] = np.clip(t, -T_MAX, T_MAX)
    return z


def _halves(family, rng, m):
    """``m`` starts, half of pulling rods and half of pushing ones."""
    m = _validate.maxiter(m, "m", minimum=0, maximum=assembly.MAX_STARTS * assembly.MAX_CHECK)
    return np.concatenate((family(rng, m // 2, PULL_Q, True),
                           family(rng, m - m // 2, PUSH_Q, False)))


def sampler(mech: model.Mechanism, lambdas: ArrayLike) -> Callable:
    """The starts of :func:`forward`: ``sample(rng, m) -> (m, 6)`` chart points, half of
    pulling rods and half of pushing ones (see the module), at the sliders ``lambdas`` (3,).

    Examples
    --------
    >>> z = sampler(model.TABLE8, model.TABLE8_LAMBDAS)(np.random.default_rng(0), 4)
    >>> z.shape, bool(in_chart(z).all())
    ((4, 6), True)
    """
    assembly.check_type(mech, model.Mechanism)
    c = model.clamps(mech, _validate.array(lambdas, "lambdas", shape=(3,)))
    low, high = c.min(axis=0), c.max(axis=0)

    def family(rng, m, q_range, pull):
        pose = np.column_stack((rng.uniform(low, high, (m, 2)), rng.uniform(-np.pi, np.pi, m)))
        return _starts(mech, rng, c, model.pins_at(mech, pose), q_range, pull)

    return lambda rng, m: _halves(family, rng, m)


def inverse_sampler(mech: model.Mechanism, pose: np.ndarray) -> Callable:
    """The starts of :func:`inverse`: ``sample(rng, m) -> (m, 9)``, the chart and the sliders,
    each slider where its pin is within ``L`` of its clamp, the rods as in :func:`sampler`,
    for a checked pose (3,).

    Examples
    --------
    >>> u = inverse_sampler(model.TABLE8, np.array([0.0, 0.0, 1.2]))(np.random.default_rng(0), 4)
    >>> u.shape, bool(in_chart(u[:, :6]).all())
    ((4, 9), True)
    """
    B = model.pins_at(mech, pose)
    guide = np.stack((np.cos(mech.guide_angles), np.sin(mech.guide_angles)), -1)
    middle = np.sum((B - mech.origins) * guide, axis=-1)

    def family(rng, m, q_range, pull):
        lambdas = middle + mech.L * rng.uniform(-1.0, 1.0, (m, 3))
        z = _starts(mech, rng, model.clamps_at(mech, lambdas), B, q_range, pull)
        return np.concatenate((z, lambdas), axis=1)

    return lambda rng, m: _halves(family, rng, m)


def _classify(mech, modes, found, nfev, njev, lambdas, inputs, pose):
    """The :class:`~mechnum.mechanisms.Equilibria` of a search's roots, at sliders ``lambdas``
    (n, 3), showing
    ``inputs`` and ``pose`` (the given one unbatched)."""
    z = found.x[:, :6]
    n = len(z)
    _, force, moment, _ = model.rods(mech, lambdas, z, modes, jacobian=False)
    index = np.array([stability(mech, lambdas[i], z[i], modes) for i in range(n)],
                     dtype=int).reshape(n, 2)
    cross = [np.zeros((0, 3), int), np.zeros((0, 3), int), np.zeros(0, int)]
    if n:
        cross = [np.concatenate(c) for c in zip(*(crossings(mech, lambdas[i], z[i], modes)
                                                  for i in range(n)))]
    return assembly.Equilibria(
        x=z, status=np.full(n, "converged"), iterations=njev, nfev=nfev, njev=njev,
        message=assembly.equilibria_message(n, found), inputs=inputs, pose=pose,
        modes=tuple(int(m) for m in modes), solutions=model.thesis_from_chart(z), forces=force,
        clamp_moments=moment, index=index, rods_cross=cross[0], self_cross=cross[1],
        body_cross=cross[2], strain=strain(mech, lambdas, z, modes),
        strain_limit=mech.strain_limit, search=found)


def forward(mech: model.Mechanism, lambdas: ArrayLike, *, modes: ArrayLike = (1, 1, 1),
            n_starts: int = N_STARTS, check: int = 10,
            rng: np.random.Generator | int | None = None) -> assembly.Equilibria:
    """Every equilibrium of the mechanism at the slider inputs ``lambdas``, with given modes.

    Damped Newton on the reduced closed form (analytic Jacobian, only real assemblies of the
    platform) from ``n_starts`` starts of pulling and pushing rods (see the module), then
    ``check`` times as many new starts (:func:`mechnum.newton.solve_all`). Each equilibrium
    is classified: stability (:func:`stability`), crossings (:func:`crossings`) and bending
    strain (:func:`strain`). Rods under forces beyond the chart's range (``T_MAX`` of
    :mod:`mechnum.rods`, about ``(300 mode)**2 EI / L**2``) are not sought.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.pfr3.Mechanism
    lambdas : array_like, shape (3,)
        Slider inputs (m).
    modes : (int, int, int), optional
        Buckling modes of the rods (inflections on ``0 < s <= L``).
    n_starts : int, optional
        Starts of the search, at most ``MAX_STARTS = 100_000``.
    check : int, optional
        Size of the completeness check, in multiples of ``n_starts`` (0: none; at most
        ``MAX_CHECK = 100``).
    rng : numpy.random.Generator or int, optional
        Random generator or seed (a non-negative integer) of the starts.

    Returns
    -------
    mechnum.mechanisms.Equilibria
        ``n >= 0`` equilibria, sorted by ``psi1``, their chart ``x``; ``inputs`` the sliders
        (m), each ``pose`` the platform's centre ``(x, y)`` (m) and angle ``phi`` (rad, in
        ``(-pi, pi]``); ``solutions`` is the study's ``(psi_i, k_rel_i)`` (its Tabla 8),
        ``rods_cross`` (n, 3) counts the crossings of the rod pairs (1, 2), (2, 3) and (3, 1),
        ``self_cross`` (n, 3) those of each rod with itself (a loop), ``body_cross`` (n,)
        those of the rods with the platform's edges.

    Raises
    ------
    ValueError
        If ``mech`` is no Mechanism, ``lambdas`` not three finite numbers, ``modes`` not three
        integers ``>= 1``, or a size or ``rng`` invalid.
    GeometryError
        If no platform of side ``a`` can close between the clamps (:func:`check_closure`).

    Examples
    --------
    >>> eq = forward(model.TABLE8, model.TABLE8_LAMBDAS, rng=0)
    >>> len(eq.pose), eq.search.complete, np.round(eq.solutions[0], 4).tolist()
    (9, True, [5.1834, -0.7267, 5.006, -0.9287, 2.6908, -0.0953])
    """
    assembly.check_type(mech, model.Mechanism)
    lambdas = _validate.array(lambdas, "lambdas", shape=(3,))
    modes = assembly.check_modes(modes, 3)
    model.check_closure(mech, lambdas)
    system = model.forward_system(mech, lambdas, modes)
    found, nfev, njev = assembly.search(system, sampler(mech, lambdas), domain=in_chart,
                                        n_starts=n_starts, check=check, rng=rng,
                                        tol=SEARCH_TOL, maxiter=SEARCH_MAXITER, same=SAME)
    tip = model.rods_at(ClampedRods(mech.EI, mech.L, modes), mech, lambdas, found.x,
                        jacobian=False)[0]
    every = np.broadcast_to(lambdas, (len(tip), 3))
    return _classify(mech, modes, found, nfev, njev, every, lambdas,
                     model.pose_at(mech, tip))


def inverse(mech: model.Mechanism, pose: ArrayLike, *, modes: ArrayLike = (1, 1, 1),
            n_starts: int = N_STARTS, check: int = 10,
            rng: np.random.Generator | int | None = None) -> assembly.Equilibria:
    """Every equilibrium of the mechanism with its platform at ``pose``, with given modes.

    The inverse problem: the sliders and the rods that hold the platform at ``pose = (x, y,
    phi)`` against its load, found as :func:`forward` finds the direct problem's, on the nine
    equations of :func:`~mechnum.mechanisms.pfr3.full_system` in the rods and the sliders,
    from starts of pulling and pushing rods at random sliders.

    Parameters
    ----------
    mech, modes, n_starts, check, rng
        As in :func:`forward`.
    pose : array_like, shape (3,)
        The platform's centre (m) and angle (rad).

    Returns
    -------
    mechnum.mechanisms.Equilibria
        ``inputs`` of shape (n, 3), the sliders of each equilibrium; ``pose`` as given.

    Raises
    ------
    UnreachablePoseError
        If a pin of the pose is farther than ``L`` from its guide.

    Examples
    --------
    >>> eq = forward(model.TABLE8, model.TABLE8_LAMBDAS, rng=0)
    >>> back = inverse(model.TABLE8, eq.pose[0], n_starts=300, check=2, rng=0)
    >>> bool(np.abs(back.inputs).max(axis=1).min() < 1e-10)        # Tabla 8's sliders
    True
    """
    assembly.check_type(mech, model.Mechanism)
    pose = _validate.array(pose, "pose", shape=(3,))
    modes = assembly.check_modes(modes, 3)
    model.check_reach(mech, pose)
    fun = assembly.continuation_system(model.full_system(mech, modes), model.LAYOUT, "pose")
    found, nfev, njev = assembly.search(
        lambda u: fun(u, pose), inverse_sampler(mech, pose),
        domain=lambda u: in_chart(u[:, :6]), n_starts=n_starts, check=check, rng=rng,
        tol=SEARCH_TOL, maxiter=SEARCH_MAXITER, same=SAME)
    return _classify(mech, modes, found, nfev, njev, found.x[:, 6:], found.x[:, 6:],
                     pose)
