"""The mechanism protocol (issue 33; CONTRIBUTING.md, "How to add a mechanism"), checked by
behaviour on every mechanism, in the manner of scikit-learn's ``parametrize_with_checks``.

Each mechanism gives a :class:`Case`: the mechanism, the inputs of one ``forward`` call and two
states to draw. Every check runs on every case: ``forward`` returns a result of the contract;
``draw(ax, mech, state, *, artists=None)`` returns a dict of named artists and, given them,
moves the same artists to another state without adding any; the protocol's verbs take the
mechanism first and have one signature each (at most one positional argument after it, the
options keyword-only); no function of a mechanism spells a quantity another way (the
equilibrium coordinates are ``chart``, the initial guess ``seed``); a result has no alias
field; the study's data and its reproduction are the mechanism's ``study`` module.
"""

import importlib
import inspect
from dataclasses import dataclass, fields

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from mechnum.results import STATUSES, Result  # noqa: E402

MECHANISMS = ("hacksaw", "finger", "elastica", "prr3", "rfr2", "pfr3", "actuator")
VERBS = ("forward", "inverse", "workspace", "singular_points", "atlas")
# Spellings the protocol replaced: the equilibrium's coordinates are `chart`, the end effector
# or platform `pose`, an initial guess `seed` (several: `seeds`).
NOT_NAMES = {"z", "P", "guess", "guesses", "x0", "u0", "starts"}
# Fields of a result that would repeat another one under a second name.
ALIASES = {"chart": "x", "theta": "inputs", "P": "pose", "lambdas": "inputs", "roots_": "x",
           "solutions_x": "x"}


@dataclass(frozen=True)
class Case:
    """One mechanism: its module, the mechanism, ``forward``'s inputs and two states."""

    name: str
    mech: object
    inputs: tuple
    states: tuple
    options: dict


def _case(name):
    """The :class:`Case` of mechanism ``name``."""
    module = importlib.import_module(f"mechnum.mechanisms.{name}")
    study = module.study
    if name == "hacksaw":
        mech = study.STUDY
        states = tuple((t, module.closed_form(mech, t)) for t in (0.0, 0.5))
        return Case(name, mech, ((0.0, 1.0, 0.0),), states, {})
    if name == "finger":
        mech = study.TABLE3_LINKAGE
        theta = np.array([4.6, 5.0])              # where the linkage assembles
        states = tuple((t, module.forward(mech, [t]).x[0, 0]) for t in theta)
        return Case(name, mech, (theta,), states, {})
    if name == "prr3":
        mech = study.EXAMPLES["Table 5"][0]
        lambdas = study.EXAMPLES["Table 5"][1]
        poses = module.forward(mech, lambdas).x
        finite = poses[np.all(np.isfinite(poses), axis=-1)]
        return Case(name, mech, (lambdas,), ((lambdas, finite[0]), (lambdas, finite[-1])), {})
    if name == "actuator":
        mech = study.ANNEX
        states = tuple((a, module.forward(mech, a).x[0]) for a in (0.6, 0.62))
        return Case(name, mech, (0.6,), states, {})
    if name == "elastica":
        mech = module.Mechanism(1.0, 1.0)
        found = module.forward(mech, [0.8, 0.1], modes=(1, 2))
        return Case(name, mech, ([0.8, 0.1],), (found.state(0), found.state(1)),
                    {"modes": (1, 2)})
    if name == "rfr2":
        mech, theta = study.TABLE7, study.TABLE7_THETA
        eq = module.forward(mech, theta, n_starts=40, check=1, rng=0)
        return Case(name, mech, (theta,), (eq.state(0), eq.state(1)),
                    {"n_starts": 40, "check": 1, "rng": 0})
    mech, lambdas = study.TABLE8, study.TABLE8_LAMBDAS       # pfr3
    eq = module.forward(mech, lambdas, n_starts=200, check=1, rng=0)
    return Case(name, mech, (lambdas,), (eq.state(0), eq.state(1)),
                {"n_starts": 200, "check": 1, "rng": 0})


@pytest.fixture(scope="module", params=MECHANISMS)
def case(request):
    return _case(request.param)


def _module(case):
    return importlib.import_module(f"mechnum.mechanisms.{case.name}")


def test_forward_returns_a_result_of_the_contract(case):
    result = _module(case).forward(case.mech, *case.inputs, **case.options)
    assert isinstance(result, Result), type(result)
    assert set(np.ravel(result.status)) <= set(STATUSES)
    assert isinstance(result.message, str) and result.message
    assert isinstance(result.x, np.ndarray)
    assert np.shape(result.converged) == np.shape(result.status)


def test_draw_returns_named_artists_and_moves_them(case):
    draw = _module(case).draw
    fig, ax = plt.subplots()
    try:
        artists = draw(ax, case.mech, case.states[0])
        assert isinstance(artists, dict) and artists
        assert all(isinstance(k, str) and isinstance(v, matplotlib.artist.Artist)
                   for k, v in artists.items())
        before = len(ax.get_children())
        data = {k: _data(v) for k, v in artists.items()}
        again = draw(ax, case.mech, case.states[1], artists=artists)
        assert again is artists and len(ax.get_children()) == before   # moved, none added
        moved = [k for k, v in artists.items() if not _same(_data(v), data[k])]
        assert moved, "no artist moved to the second state"
    finally:
        plt.close(fig)


def _data(artist):
    """What an artist draws: its points (a line, a polygon, an arrow)."""
    for getter in ("get_xydata", "get_xy"):
        if hasattr(artist, getter):
            return np.array(getattr(artist, getter)(), dtype=float)
    if hasattr(artist, "xyann"):
        return np.array([artist.xy, artist.xyann], dtype=float)
    return None


def _same(a, b):
    return (a is None and b is None) or (a is not None and b is not None and a.shape == b.shape
                                         and np.allclose(a, b, equal_nan=True))


@pytest.mark.parametrize("name", MECHANISMS)
def test_draw_has_the_protocols_signature(name):
    params = inspect.signature(importlib.import_module(f"mechnum.mechanisms.{name}").draw)
    params = list(params.parameters.values())
    assert [p.name for p in params[:3]] == ["ax", "mech", "state"]
    artists = {p.name: p for p in params}["artists"]
    assert artists.kind is inspect.Parameter.KEYWORD_ONLY and artists.default is None
    assert all(p.kind is inspect.Parameter.KEYWORD_ONLY for p in params[3:]), name


@pytest.mark.parametrize("name", MECHANISMS)
def test_the_verbs_take_the_mechanism_first_and_options_by_keyword(name):
    module = importlib.import_module(f"mechnum.mechanisms.{name}")
    for verb in (v for v in VERBS if v in module.__all__):
        params = list(inspect.signature(getattr(module, verb)).parameters.values())
        assert params[0].name == "mech", f"{name}.{verb}"
        positional = [p for p in params[1:] if p.kind is p.POSITIONAL_OR_KEYWORD]
        limit = 2 if verb == "atlas" else 1          # atlas(mech, a, b, *, ...)
        if verb in ("workspace", "singular_points", "atlas"):
            assert len(positional) <= limit, f"{name}.{verb}{[p.name for p in params]}"


def test_workspace_singular_points_and_atlas_have_one_signature_each():
    for verb in ("workspace", "singular_points", "atlas"):
        shapes = set()
        for name in MECHANISMS:
            module = importlib.import_module(f"mechnum.mechanisms.{name}")
            if verb in module.__all__:
                params = inspect.signature(getattr(module, verb)).parameters.values()
                shapes.add(sum(p.kind is p.POSITIONAL_OR_KEYWORD for p in params))
        assert len(shapes) <= (2 if verb == "singular_points" else 1), (verb, shapes)


@pytest.mark.parametrize("name", MECHANISMS)
def test_the_same_names_for_the_same_quantities(name):
    module = importlib.import_module(f"mechnum.mechanisms.{name}")
    for fname in module.__all__:
        obj = getattr(module, fname)
        if inspect.isfunction(obj):
            bad = NOT_NAMES & set(inspect.signature(obj).parameters)
            assert not bad, f"{name}.{fname} spells {bad}"


def test_results_have_no_alias_fields(case):
    result = _module(case).forward(case.mech, *case.inputs, **case.options)
    names = {f.name for f in fields(result)}
    assert not names & set(ALIASES), names & set(ALIASES)


@pytest.mark.parametrize("name", MECHANISMS)
def test_the_study_and_its_reproduction_are_the_study_module(name):
    module = importlib.import_module(f"mechnum.mechanisms.{name}")
    study = importlib.import_module(f"mechnum.mechanisms.{name}.study")
    assert module.study is study and "study" not in module.__all__
    assert callable(study.reproduce) and "reproduce" in study.__all__
    assert not [p for p in inspect.signature(study.reproduce).parameters.values()
                if p.default is inspect.Parameter.empty]
    assert not hasattr(module, "reproduce")
