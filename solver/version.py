"""The solver's version (written into every profile it produces)."""


__version__ = "0.1.0"
