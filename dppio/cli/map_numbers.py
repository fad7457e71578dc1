"""The numbers of the ``--map`` option group: ``--prior`` and ``--goal-values``, checked as
typed, before the map is read, so that a mistake in them is blamed on the option (the
group itself is :mod:`dppio.cli.map_options`)."""

from __future__ import annotations

from fractions import Fraction

from dppio.errors import DppioError, OptionError
from dppio.limits import check_numeral, check_rational
from dppio.text import show


def priors(prior: str, n: int) -> tuple[str, ...]:
    """``--prior``'s ``n`` numbers as typed (stripped), checked (:func:`check_prior`)."""
    parts = prior.split(",")
    if len(parts) != n or not all(p.strip() for p in parts):
        if n == 2:
            raise OptionError(f"--prior takes two numbers P,Q (e.g. 0.6,0.4 or 3/5,2/5), "
                              f"got {prior!r}")
        raise OptionError(f"--prior takes {n} numbers, one per goal (e.g. "
                          f"{','.join(['1/' + str(n)] * n)}), got {prior!r}")
    check_prior([p.strip() for p in parts])
    return tuple(p.strip() for p in parts)


def check_prior(parts: list[str]) -> None:
    """Check ``--prior``'s numbers (any count) before the map is read, so that a mistake in
    them is blamed on ``--prior``, not on the map file.

    Raises
    ------
    OptionError
        A number that is not a probability strictly between 0 and 1, or a sum other than 1.

    Examples
    --------
    >>> check_prior(["0.6", "2/5"])
    >>> check_prior(["0.6", "0.5"])
    Traceback (most recent call last):
    dppio.errors.OptionError: --prior must sum to exactly 1, got 3/5 + 1/2 = 11/10
    >>> check_prior(["0.6", "x"])
    Traceback (most recent call last):
    dppio.errors.OptionError: --prior: 'x' is not a number (write e.g. 0.6 or 3/5)
    """
    values = []
    for text in parts:
        try:
            check_numeral(text, where="--prior")  # the size limits first, as for any numeral
            p = Fraction(text.strip())
        except (ValueError, ZeroDivisionError) as exc:
            why = str(exc) if isinstance(exc, DppioError) else f"--prior: {text!r} is not a number"
            raise OptionError(f"{why} (write e.g. 0.6 or 3/5)") from None
        try:
            check_rational(p, where="--prior")
        except DppioError as exc:
            raise OptionError(f"{exc} (write e.g. 0.6 or 3/5)") from None
        if not 0 < p < 1:
            raise OptionError(f"--prior: each prior must lie strictly between 0 and 1, got "
                              f"{text}")
        values.append(p)
    total = sum(values, Fraction(0))
    if total != 1:
        raise OptionError(f"--prior must sum to exactly 1, got "
                          f"{' + '.join(show(v) for v in values)} = {show(total)}")


def goal_values(text: str, n: int) -> tuple[str, ...]:
    """``--goal-values``: ``n`` numbers (checked here, before the map is read).

    Examples
    --------
    >>> goal_values("0, 1/2", 2)
    ('0', '1/2')
    >>> goal_values("1", 2)
    Traceback (most recent call last):
    dppio.errors.OptionError: --goal-values takes 2 numbers, one per goal, got '1'
    """
    parts = tuple(p.strip() for p in text.split(","))
    if len(parts) != n or not all(parts):
        raise OptionError(f"--goal-values takes {n} numbers, one per goal, got {text!r}")
    for part in parts:
        try:
            check_numeral(part, where="--goal-values")
            check_rational(Fraction(part), where="--goal-values")
        except (ValueError, ZeroDivisionError) as exc:
            why = str(exc) if isinstance(exc, DppioError) else \
                f"--goal-values: {part!r} is not a number"
            raise OptionError(f"{why} (write e.g. 0, -1 or 1/2)") from None
    return parts
