"""dppverify: an independent checker for deceptive-path-planning (DPP) game profiles.

It never imports ``solver``: it reads instances and strategy profiles as JSON
(``docs/formats.md``) and certifies them against the paper's game.
"""

from __future__ import annotations

__version__ = "0.1.0"
