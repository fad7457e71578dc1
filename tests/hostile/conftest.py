"""Fixtures of the hostile suite: a scratch folder per probe with a valid instance, its
profile, the bundled map and a set of misbehaving solver programs."""

from __future__ import annotations

import shutil
from collections import Counter
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.hostile._harness import write_template

CAMPAIGNS = {("test_trust_inputs.py", "test_probe"), ("test_probes.py", "test_probe"),
             ("test_outputs.py", "test_output_probe"), ("test_batch_files.py", "test_batch_probe")}
"""The long probe lists of earlier rounds (hundreds of real processes): the default run takes
every :data:`SAMPLE`-th probe of each, by its place in the list; the others are ``slow``
(``python3 dev.py test -m hostile`` runs every probe, ``-m slow`` the rest). This round's
probes (``test_kernel_pass.py``) and every other hostile test always run."""

SAMPLE = 4


@pytest.hookimpl(tryfirst=True)  # before ``-m`` deselects by marker
def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Mark all but every :data:`SAMPLE`-th probe of the :data:`CAMPAIGNS` ``slow``."""
    seen: Counter[tuple[str, str]] = Counter()
    for item in items:
        key = (item.path.name, getattr(item, "originalname", ""))
        if key in CAMPAIGNS and item.path.parent.name == "hostile" and hasattr(item, "callspec"):
            if seen[key] % SAMPLE:
                item.add_marker(pytest.mark.slow)
            seen[key] += 1

SCRIPTS = {
    # a command-line solver that makes a FIFO at its profile path and exits 0
    "fifo_exit.sh": '#!/bin/sh\nmkfifo "$2"\nexit 0\n',
    # ... and then blocks writing into it
    "fifo_block.sh": '#!/bin/sh\nmkfifo "$2"\necho $$ > "$PIDS/fifo_block"\necho x > "$2"\n',
    # sleeps until killed, after recording its pid
    "slow.sh": '#!/bin/sh\necho $$ > "$PIDS/slow"\nexec sleep 300\n',
    # starts a child in a new session (an escapee), then exits 0 without a profile
    "escape_exit.sh": '#!/bin/sh\nsetsid sh -c \'echo $$ > "$PIDS/escapee"; exec sleep 300\' &\n'
                      'while [ ! -s "$PIDS/escapee" ]; do sleep 0.05; done\nexit 0\n',
    # the same, then hangs
    "escape_hang.sh": '#!/bin/sh\nsetsid sh -c \'echo $$ > "$PIDS/escapee"; exec sleep 300\' &\n'
                      'exec sleep 300\n',
    # a double fork: the grandchild is orphaned at once
    "orphan.sh": '#!/bin/sh\n( sh -c \'echo $$ > "$PIDS/orphan"; exec sleep 300\' & )\n'
                 'while [ ! -s "$PIDS/orphan" ]; do sleep 0.05; done\nexit 0\n',
    # floods its output, then fails
    "flood.sh": '#!/bin/sh\nhead -c 200000000 /dev/zero | tr "\\0" "x"\necho "last line"\n'
                'exit 1\n',
    # ignores SIGTERM
    "stubborn.sh": '#!/bin/sh\ntrap "" TERM\necho $$ > "$PIDS/stubborn"\n'
                   'while true; do sleep 1; done\n',
    # makes the profile path a symlink to /dev/zero
    "zero_link.sh": '#!/bin/sh\nln -s /dev/zero "$2"\nexit 0\n',
    # a folder at the profile path
    "dir_profile.sh": '#!/bin/sh\nmkdir "$2"\nexit 0\n',
    # exits 0 with an empty profile
    "empty.sh": '#!/bin/sh\n: > "$2"\nexit 0\n',
    # writes a profile of 100 MB
    "huge.sh": '#!/bin/sh\nhead -c 100000000 /dev/zero > "$2"\nexit 0\n',
    # kills its own process group
    "killgroup.sh": '#!/bin/sh\nkill -9 0\n',
    # writes binary garbage as the profile
    "binary.sh": '#!/bin/sh\nprintf "\\377\\376\\000" > "$2"\nexit 0\n',
}


@pytest.fixture(scope="session")
def template(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A folder with tri.json, its solver profile prof.json, paper10.map and the scripts."""
    return write_template(tmp_path_factory.mktemp("hostile-template"))


@pytest.fixture
def scratch(template: Path, tmp_path: Path) -> Iterator[Path]:
    """The probe's working folder (a copy of the template), with ``../bin`` (the scripts),
    ``../pids`` (pids the scripts record) and ``../tmp`` (the probe's TMPDIR) beside it."""
    d = tmp_path / "cwd"
    shutil.copytree(template, d)
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    for name, text in SCRIPTS.items():
        (bin_dir / name).write_text(text)
        (bin_dir / name).chmod(0o755)
    (tmp_path / "pids").mkdir()
    (tmp_path / "tmp").mkdir()
    yield d
