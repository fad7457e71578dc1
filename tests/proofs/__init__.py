"""Tests of proofs/coq: the extracted Coq checker against the Python kernel."""
