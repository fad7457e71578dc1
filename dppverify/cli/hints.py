"""Re-exports of :mod:`dppio.cli.hints` for the command modules that still import them from
here (removed once those modules import :mod:`dppio.cli` directly)."""

from dppio.cli.hints import what_is

__all__ = ["what_is"]
