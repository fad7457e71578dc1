"""The solver's version (written into every profile it produces)."""

__all__ = ["__version__"]

__version__ = "0.1.0"
