"""The version of dppverify (one place; the package and its certificates read it)."""

__version__ = "0.1.0"
