"""Which lines of a ``.scen`` file a ``dpp batch`` runs: ``--lines A-B`` and ``--shard i/n``.

- ``--lines A-B`` keeps the scenario lines whose **file line number** (the CSV's ``line``
  column; line 1 is the ``version`` header) lies in ``A … B``; ``A`` alone is one line, ``A-``
  runs to the end of the file.
- ``--shard i/n`` (``1 ≤ i ≤ n``) then keeps every ``n``-th of those lines, starting with the
  ``i``-th: the ``k``-th selected line (``k = 0, 1, …`` in file order) belongs to shard
  ``k mod n + 1``. The shards are disjoint, together they are the selection, and each depends
  only on the file and the two options — never on the machine, the order lines run in or
  earlier runs — so ``n`` jobs of a job array each run one shard and ``dpp batch merge`` joins
  their CSVs (:mod:`solver.experiments.batch_merge`). Dealing the lines round-robin spreads
  the long lines of the last buckets (MovingAI sorts a file by bucket) over all shards.

Examples
--------
>>> sel = parse_selection("2-9", "2/3")
>>> sorted(sel.choose(range(1, 12)))
[3, 6, 9]
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass

from dppio.text import escaped
from solver.errors import InvalidInstanceError

_MAX = 10**9


@dataclass(frozen=True)
class LineSelection:
    """Lines ``first … last`` (``last`` None: to the end), then shard ``shard`` of ``shards``."""

    first: int = 1
    last: int | None = None
    shard: int = 1
    shards: int = 1

    @property
    def everything(self) -> bool:
        """True when nothing is left out.

        Examples
        --------
        >>> LineSelection().everything, parse_selection(None, "1/2").everything
        (True, False)
        """
        return self.first == 1 and self.last is None and self.shards == 1

    def choose(self, lines: Sequence[int]) -> set[int]:
        """The scenario line numbers (of ``lines``, in file order) this selection runs.

        Raises
        ------
        InvalidInstanceError
            ``--lines`` starts after the file's last line, ends after it, or holds no
            scenario line.

        Examples
        --------
        >>> sorted(LineSelection(3, 4).choose([2, 3, 4, 5]))
        [3, 4]
        >>> LineSelection(7, 9).choose([2, 3, 4, 5])
        Traceback (most recent call last):
        solver.errors.InvalidInstanceError: --lines 7-9: the file's scenario lines are 2-5
        """
        numbers = list(lines)
        span = f"{numbers[0]}-{numbers[-1]}" if numbers else "none"
        asked = f"{self.first}-{'' if self.last is None else self.last}"
        if numbers and (self.first > numbers[-1] or (self.last is not None
                                                     and self.last > numbers[-1])):
            raise InvalidInstanceError(f"--lines {asked}: the file's scenario lines are {span}")
        picked = [n for n in numbers
                  if n >= self.first and (self.last is None or n <= self.last)]
        if not picked:
            raise InvalidInstanceError(f"--lines {asked} holds no scenario line (the file's "
                                       f"scenario lines are {span})")
        return {n for k, n in enumerate(picked) if k % self.shards == self.shard - 1}


def parse_selection(lines: str | None, shard: str | None) -> LineSelection:
    """``--lines`` and ``--shard`` as a :class:`LineSelection` (None: not given).

    Raises
    ------
    InvalidInstanceError
        A malformed value (one line naming the option and the expected form).

    Examples
    --------
    >>> parse_selection("5", None), parse_selection("5-", "3/4")
    (LineSelection(first=5, last=5, shard=1, shards=1), LineSelection(first=5, last=None, \
shard=3, shards=4))
    >>> parse_selection("9-3", None)
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: --lines 9-3: the first line is after the last
    >>> parse_selection(None, "5/4")
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: --shard 5/4: i must lie in 1 … n (shard i of n)
    >>> parse_selection(None, "1/\u0662")  # ASCII digits only: an Arabic-Indic two is not 2
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: --shard takes i/n (shard i of n, e.g. 1/4; ASCII \
digits), got '1/\u0662'
    """
    first, last = 1, None
    if lines is not None:
        m = re.fullmatch(r" *([0-9]{1,10}) *(?:(-) *([0-9]{1,10})?)? *", lines, re.ASCII)
        if m is None:
            raise InvalidInstanceError(f"--lines takes A-B, A or A- (file line numbers, as the "
                                       f"CSV's line column; ASCII digits), got "
                                       f"{escaped(repr(lines))}")
        first = int(m.group(1))
        last = first if m.group(2) is None else (None if m.group(3) is None
                                                 else int(m.group(3)))
        if first < 1 or first > _MAX or (last is not None and last > _MAX):
            raise InvalidInstanceError(f"--lines {lines}: line numbers start at 1")
        if last is not None and last < first:
            raise InvalidInstanceError(f"--lines {lines}: the first line is after the last")
    i, n = 1, 1
    if shard is not None:
        m = re.fullmatch(r" *([0-9]{1,7}) */ *([0-9]{1,7}) *", shard, re.ASCII)
        if m is None:
            raise InvalidInstanceError(f"--shard takes i/n (shard i of n, e.g. 1/4; ASCII "
                                       f"digits), got {escaped(repr(shard))}")
        i, n = int(m.group(1)), int(m.group(2))
        if n < 1 or not 1 <= i <= n:
            raise InvalidInstanceError(f"--shard {shard}: i must lie in 1 … n (shard i of n)")
    return LineSelection(first, last, i, n)
