"""dppio: the edges both packages share (bounded reading, all-or-nothing writing, output
safety, the shared numeric and size limits).

The solver (``solver``) and the checker (``dppverify``) stay independent in everything
mathematical: each has its own parsers and validators of instances, maps and numbers, so that
a reader bug is never shared (``tests/maps/test_readers_agree.py`` cross-checks them). What
they share lives here and only here: how a file is read without hanging or exhausting memory
(:mod:`dppio.files`), how outputs are written all or nothing (where an output path writes:
:mod:`dppio.targets`; the lock discipline of batch CSVs: :mod:`dppio.locks`), how standard
input is read (:mod:`dppio.inputs`), how a document's strings are shown without forging a
line (:mod:`dppio.text`), the limit values with the
checks that refuse a numeral before it is parsed or a JSON document nested too deep
(:mod:`dppio.limits`), how much memory a command may use (:mod:`dppio.memory`), and how the
processes
a command started are found to end them (:mod:`dppio.procs`). Each package raises its own
error classes (the checks and writers take ``error=``). ``dppio`` imports neither package
(import-linter enforces it).

>>> from dppio.limits import MAX_INPUT_BYTES
>>> MAX_INPUT_BYTES
67108864
"""

