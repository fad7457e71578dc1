"""The ``dpp`` group names its commands by module (``dppio.cli.lazy.LazyCommands``): each name
is its command's own, and a command's run imports that command's module, not the others'."""

from __future__ import annotations

import json
import sys

import pytest

from dpp import main
from dppverify import cli as checker_cli
from solver import cli as solver_cli
from tests import _guard

HOMES = {**solver_cli.HOMES, **checker_cli.HOMES}


@pytest.mark.parametrize("name", sorted(HOMES))
def test_each_name_is_its_command_s_own(name: str) -> None:
    assert main.commands[name].name == name
    assert name in main.commands and main.get_command(None, name) is main.commands[name]  # type: ignore[arg-type]


def test_the_group_lists_every_command_once() -> None:
    assert sorted(main.list_commands(None)) == sorted(HOMES)  # type: ignore[arg-type]
    assert main.get_command(None, "nope") is None  # type: ignore[arg-type]


def test_starting_one_command_imports_no_other_command() -> None:
    probe = ("import sys\nfrom dpp import main\n"
             "try:\n    main(['check', '--help'], prog_name='dpp')\nexcept SystemExit:\n    pass\n"
             "import json\nprint(json.dumps(sorted(m for m in sys.modules if m.endswith(('"
             + "', '".join(sorted(m for m, _ in HOMES.values())) + "')))))")
    out = _guard.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    loaded = json.loads(out.stdout.strip().splitlines()[-1])
    assert loaded == ["dppverify.cli.check"], loaded
