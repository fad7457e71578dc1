"""The trusted kernel: decides from an instance, a profile and a ``dpp-witness/1`` whether the
profile is a weak PBNE of the untruncated game, by exact inequalities alone (proofs/KERNEL.md).

Standard library only (an import-linter contract and ``tests/dppverify/kernel`` enforce it):
it shares no code with the rest of ``dppverify`` or with ``solver``. ``dpp check`` runs it in
its own process (``dppverify/kernel/__main__.py`` run as a file loads nothing else).

>>> from dppverify.kernel import check
>>> check(b"{}", b"{}", b"{}").status
'bad-input'
"""

from dppverify.kernel.check import check
from dppverify.kernel.verdict import EXIT_CODES, Verdict

__all__ = ["EXIT_CODES", "Verdict", "check"]
