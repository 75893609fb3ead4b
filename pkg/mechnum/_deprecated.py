"""Deprecated call forms: the old ones keep working for one release, and say what replaces them.

When a public function is renamed or its arguments reordered (the mechanism protocol puts the
mechanism first, ``f(mech, inputs, ...)``), its old form stays callable until 0.3: it emits a
:class:`DeprecationWarning` naming the new form, then calls it. CHANGELOG.md lists every one.

Examples
--------
>>> import warnings
>>> def _old(x, scale=2):             # the old argument order, translated into the new one
...     return (scale, x), {}
>>> @old_form(_old, old="times(x, scale)", new="times(scale, x)",
...           is_new=lambda args, kwargs: isinstance(args[0], int))
... def times(scale, x):
...     return scale * x
>>> with warnings.catch_warnings(record=True) as caught:
...     warnings.simplefilter("always")
...     times(3, "a"), times("a", 3)
('aaa', 'aaa')
>>> [w.category.__name__ for w in caught]
['DeprecationWarning']
"""

import dataclasses
import functools
import inspect
import warnings
from collections.abc import Callable

REMOVED_IN = "0.3"


def warn(old: str, new: str) -> None:
    """Emit the :class:`DeprecationWarning` of the old form ``old``, pointing at ``new``.

    The warning is attributed to the caller of the deprecated function.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn("f(x)", "g(x)")
    >>> str(caught[0].message)
    'f(x) is deprecated and will be removed in 0.3: call g(x)'
    """
    warnings.warn(f"{old} is deprecated and will be removed in {REMOVED_IN}: call {new}",
                  DeprecationWarning, stacklevel=3)


def mech_at(position: int, mech_type: type) -> Callable[[tuple, dict], bool]:
    """The test of a new-form call: a ``mech_type`` (or another mechanism, or None) at
    ``position``, or, with fewer positional arguments, ``mech`` by keyword.

    Anything else there (a number, an array, a tuple of them) is the first argument of the old
    form, which had the mechanism later. A dataclass of another type, None or a string counts as
    the new form, so that its check names the wrong mechanism instead of misreading it.

    Examples
    --------
    >>> from fractions import Fraction
    >>> test = mech_at(0, Fraction)
    >>> test((Fraction(1), 2.0), {}), test((2.0,), {}), test((), {"mech": None}), test((None,), {})
    (True, False, True, True)
    """
    def is_new(args, kwargs):
        if len(args) <= position:
            return "mech" in kwargs
        first = args[position]
        return first is None or isinstance(first, (mech_type, str)) or \
            dataclasses.is_dataclass(first)
    return is_new


def old_form(translate: Callable, *, old: str, new: str, is_new: Callable[[tuple, dict], bool],
             target: Callable | None = None) -> Callable[[Callable], Callable]:
    """Decorate a function so that it also accepts its deprecated call form.

    Parameters
    ----------
    translate : callable
        Takes the arguments of the old form (its signature is the old one, defaults included)
        and returns ``(args, kwargs)`` of the new form.
    old, new : str
        The two forms, as the warning names them.
    is_new : callable
        ``is_new(args, kwargs)``: whether a call is of the new form (:func:`mech_at`).
    target : callable, optional
        What an old-form call calls with the translated arguments: the new function itself by
        default, or the old form's own implementation where the two differ in kind.

    Returns
    -------
    callable
        The decorator. The decorated function keeps the new function's name, docstring and
        signature (``__wrapped__``).
    """
    def decorate(function):
        @functools.wraps(function)
        def either(*args, **kwargs):
            if is_new(args, kwargs):
                return function(*args, **kwargs)
            warn(old, new)
            new_args, new_kwargs = translate(*args, **kwargs)
            return (target or function)(*new_args, **new_kwargs)
        return either
    return decorate


REQUIRED = inspect.Parameter.empty
"""The ``default`` of :func:`mech_moved` for an old mechanism argument that had none."""


def _shown(name, parameters):
    return f"{name}({', '.join(p.name for p in parameters if p.kind == p.POSITIONAL_OR_KEYWORD)})"


def _translator(function, to, name, default, position, renames):
    """The old signature of :func:`mech_moved` and :func:`renamed`, and its translation."""
    params = list(inspect.signature(function).parameters.values())
    lead, rest = params[:position], params[position + 1:]
    old_names = {new: old for new, old in (renames or {}).items()}
    rest_old = [p.replace(name=old_names.get(p.name, p.name)) for p in rest]
    moved = inspect.Parameter(name, inspect.Parameter.POSITIONAL_OR_KEYWORD, default=default)
    old = inspect.Signature(lead + rest_old[:to] + [moved] + rest_old[to:])
    back = {old: new for new, old in old_names.items()}

    def translate(*args, **kwargs):
        bound = old.bind(*args, **kwargs)
        bound.apply_defaults()
        values = dict(bound.arguments)
        mech_value = values.pop(name)
        new_args = [values.pop(p.name) for p in lead] + [mech_value]
        for p in rest_old:  # a **options of the old form goes on as keywords
            if p.kind == p.VAR_KEYWORD:
                values.update(values.pop(p.name))
        return new_args, {back.get(key, key): value for key, value in values.items()}

    return translate, old.parameters.values(), params


def mech_moved(mech_type: type, *, to: int, name: str = "geometry", default=REQUIRED,
               position: int = 0) -> Callable[[Callable], Callable]:
    """Decorate a function ``f(..., mech, *rest)`` whose old form took the mechanism later.

    The old form had the same arguments in the same order, except the mechanism: it came
    after ``to`` of the others, named ``name``, with the default ``default`` (if any). The new
    form has it at ``position`` (0, or 1 after a drawing's axes).

    Examples
    --------
    >>> import warnings
    >>> from fractions import Fraction
    >>> @mech_moved(Fraction, to=1, default=Fraction(2))
    ... def scaled(mech, x, offset=0):
    ...     return mech * x + offset
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     scaled(Fraction(3), 1), scaled(1), scaled(1, Fraction(3), offset=1)
    (Fraction(3, 1), Fraction(2, 1), Fraction(4, 1))
    """
    def decorate(function):
        translate, old, new = _translator(function, to, name, default, position, None)
        return old_form(translate, old=_shown(function.__name__, old),
                        new=_shown(function.__name__, new),
                        is_new=mech_at(position, mech_type))(function)
    return decorate


def renamed(function: Callable, old_name: str, *, mech_type: type, to: int,
            name: str = "geometry", default=REQUIRED, renames: dict | None = None) -> Callable:
    """A deprecated alias ``old_name`` of ``function``, whose old form took the mechanism later.

    It accepts the old form (as :func:`mech_moved` describes, with the arguments ``renames``
    ``{new name: old name}`` under their old names) and the new one, and always warns.

    Examples
    --------
    >>> import warnings
    >>> from fractions import Fraction
    >>> def scaled(mech, x):
    ...     return mech * x
    >>> times = renamed(scaled, "times", mech_type=Fraction, to=1, renames={"x": "value"})
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     times(value=2, geometry=Fraction(3)), times(Fraction(3), 2)
    (Fraction(6, 1), Fraction(6, 1))
    >>> str(caught[0].message)
    'times(value, geometry) is deprecated and will be removed in 0.3: call scaled(mech, x)'
    """
    translate, old, new = _translator(function, to, name, default, 0, renames)
    is_new = mech_at(0, mech_type)

    @functools.wraps(function)
    def alias(*args, **kwargs):
        warn(_shown(old_name, old), _shown(function.__name__, new))
        if is_new(args, kwargs):
            return function(*args, **kwargs)
        new_args, new_kwargs = translate(*args, **kwargs)
        return function(*new_args, **new_kwargs)

    alias.__name__ = alias.__qualname__ = old_name
    alias.__doc__ = (f"Deprecated alias of :func:`{function.__name__}` (removed in "
                     f"{REMOVED_IN}); it also takes the old argument order.")
    del alias.__wrapped__  # its own signature is the old one, not the new function's
    return alias
