"""A behaviour profile of the exported ``.efg`` game as a ``dpp`` profile of the truncated game.

A peer (Gambit, OpenSpiel) that solved the game :func:`~dppverify.tree_route.efg.to_efg` wrote
returns a behaviour strategy per information set: the Attacker's next node per (type, walk
prefix[, the Defender's past allocations]), the Defender's allocation per (walk prefix, its own
past allocations). :func:`profile_from_behaviour` turns an exact one into the document
``dpp certify --horizon H`` reads (``docs/formats.md`` §2c):

- **the Attacker**, per type: the distribution over walks that the profile realises, each walk
  with the product of the probabilities along it (Kuhn's theorem: the realization-equivalent
  mixed strategy). With ``attacker_observes`` the type's moves may depend on the Defender's past
  allocations, which a walk mixture cannot express: the walk distribution is then the one
  realised against the profile's own Defender, and the count of such information sets is
  reported (:attr:`ImportedProfile.history_dependent`), since the imported profile is then
  another strategy than the peer's;
- **the Defender**: a table with one entry per walk prefix of the truncated game, the
  allocation averaged over its own past allocations with the probabilities its strategy gives
  them, ``σ̄(g | p) = Σ_h P_σ(h | p) σ(g | p, h)``. The payoff is a sum over steps, and against
  an Attacker that sees only the walk the step's expected allocation is all that counts, so
  every payoff against such an Attacker, best responses included, is unchanged: the
  exploitability of the imported profile is the peer's NashConv of the game exported with
  ``--attacker-blind`` (and of the other export whenever no Attacker move depends on the
  allocations).

The labels and action names are those of the writer itself (the game is rebuilt from the
instance, never read from the peer's file), so a profile of another game is refused by name.

Examples
--------
>>> from dppverify.game.examples import triangle
>>> from dppverify.tree_route.tree import build_tree
>>> tree = build_tree(triangle(), 1)
>>> sets = exported_infosets(tree)
>>> [(s.label, s.actions) for s in sets]  # doctest: +NORMALIZE_WHITESPACE
[('T1 p0 h-', ('go g1', 'go g2')), ('T2 p0 h-', ('go g1', 'go g2')),
 ('D p1 h-', ('alloc g1', 'alloc g2')), ('D p2 h-', ('alloc g1', 'alloc g2'))]
>>> from fractions import Fraction as F
>>> beh = {"T1 p0 h-": {"go g1": F(4, 7), "go g2": F(3, 7)},
...        "T2 p0 h-": {"go g1": F(0), "go g2": F(1)},
...        "D p1 h-": {"alloc g1": F(1), "alloc g2": F(0)},
...        "D p2 h-": {"alloc g1": F(1, 2), "alloc g2": F(1, 2)}}
>>> doc = profile_from_behaviour(tree, beh).document
>>> doc["attacker"]["primary"]
[{'path': ['s', 'g1'], 'probability': '4/7'}, {'path': ['s', 'g2'], 'probability': '3/7'}]
>>> doc["defender"]["entries"][1]
{'walk': ['s', 'g2'], 'probability': '1/2'}
"""

from __future__ import annotations

import re
from collections import defaultdict
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from dppverify.errors import ProfileError
from dppverify.formats.json_reading import node_to_json
from dppverify.formats.peer_profiles import Infoset
from dppverify.game.instance import Instance
from dppverify.tree_route.efg import DEFAULT_MAX_EFG_NODES, _node_names, tree_to_efg
from dppverify.tree_route.tree import WalkTree

ExactBehaviour = Mapping[str, Mapping[str, Fraction]]

_LINE = re.compile(r'^p "" (\d) (\d+) "([^"]*)" \{ (.*?) \} 0$', re.M)
_QUOTED = re.compile(r'"([^"]*)"')


def _decisions(tree: WalkTree, attacker_observes: bool, forced_moves: bool,
               max_nodes: int) -> Iterator[Infoset]:
    """Every decision node line of the export, in file order."""
    text = tree_to_efg(tree, attacker_observes=attacker_observes, forced_moves=forced_moves,
                       max_nodes=max_nodes)
    for m in _LINE.finditer(text):
        yield Infoset(int(m[1]), int(m[2]), m[3], tuple(_QUOTED.findall(m[4])))


def exported_infosets(tree: WalkTree, *, attacker_observes: bool = True,
                      forced_moves: bool = False,
                      max_nodes: int = DEFAULT_MAX_EFG_NODES) -> tuple[Infoset, ...]:
    """The information sets of the exported game in Gambit's order: the Attacker's, then the
    Defender's, each by number (the order of a Gambit profile line).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> [s.label for s in exported_infosets(build_tree(triangle(), 1), attacker_observes=False)]
    ['T1 p0', 'T2 p0', 'D p1 h-', 'D p2 h-']
    """
    seen: dict[tuple[int, int], Infoset] = {}
    for s in _decisions(tree, attacker_observes, forced_moves, max_nodes):
        seen.setdefault((s.player, s.number), s)
    return tuple(seen[k] for k in sorted(seen))


def exported_action_names(tree: WalkTree, *, attacker_observes: bool = True,
                          forced_moves: bool = False,
                          max_nodes: int = DEFAULT_MAX_EFG_NODES) -> tuple[str, ...]:
    """The players' action names by first appearance in the file: OpenSpiel's action ids.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> exported_action_names(build_tree(triangle(), 2))
    ('go g1', 'go g2', 'alloc g1', 'alloc g2')
    """
    names: dict[str, None] = {}
    for s in _decisions(tree, attacker_observes, forced_moves, max_nodes):
        names.update(dict.fromkeys(s.actions))
    return tuple(names)


@dataclass(frozen=True)
class ImportedProfile:
    """The ``dpp-profile/1`` (two goals) or ``dpp-ngoal-profile/1`` document, and how many of
    the Attacker's (type, prefix) decisions depended on the Defender's past allocations."""

    document: dict[str, Any]
    history_dependent: int


class _Game:
    """The exported game's labels and moves on a walk tree (the writer's own names)."""

    def __init__(self, tree: WalkTree, behaviour: ExactBehaviour, observes: bool,
                 forced: bool) -> None:
        self.tree, self.beh, self.observes, self.forced = tree, behaviour, observes, forced
        inst: Instance = tree.instance
        self.n = len(inst.goals)
        self.names = _node_names(inst)
        self.goal_names = [self.names[g] for g in inst.goals]
        self.sep = "" if self.n <= 9 else "."

    def after(self, hist: str, k: int) -> str:
        """The Defender history ``hist`` followed by an allocation to goal ``k``."""
        return f"{hist}{self.sep}{k + 1}" if hist else str(k + 1)

    def allocation(self, p: int, hist: str) -> list[Fraction]:
        """The Defender's distribution over the goals after prefix ``p`` and history ``hist``."""
        row = self.beh[f"D p{p} h{hist or '-'}"]
        return [row[f"alloc {g}"] for g in self.goal_names]

    def moves(self, theta: int, p: int, hist: str) -> list[tuple[int, Fraction]]:
        """The Attacker's next prefixes from ``p`` with their probabilities."""
        kids = list(self.tree.children(p))
        if len(kids) == 1 and not self.forced:
            return [(kids[0], Fraction(1))]
        label = (f"T{theta + 1} p{p} h{hist or '-'}" if self.observes else f"T{theta + 1} p{p}")
        row = self.beh[label]
        return [(c, row[f"go {self.names[int(self.tree.node[c])]}"]) for c in kids]

    def walks(self, theta: int) -> dict[int, Fraction]:
        """Leaf prefix -> the probability type ``theta`` ends its walk there."""
        out: dict[int, Fraction] = defaultdict(Fraction)
        stack: list[tuple[int, str, Fraction]] = [(0, "", Fraction(1))]
        while stack:
            p, hist, q = stack.pop()
            if self.tree.child_start[p] == self.tree.child_stop[p]:
                out[p] += q
                continue
            for c, pc in self.moves(theta, p, hist):
                if pc == 0:
                    continue
                if not self.observes:  # the moves do not see the allocations
                    stack.append((c, "", q * pc))
                    continue
                for k, pk in enumerate(self.allocation(c, hist)):
                    if pk:
                        stack.append((c, self.after(hist, k), q * pc * pk))
        return out

    def defender(self) -> dict[int, list[Fraction]]:
        """Prefix -> the allocation averaged over the Defender's own histories."""
        sigma: dict[int, list[Fraction]] = {}
        stack = [(int(c), "", Fraction(1)) for c in self.tree.children(0)]
        while stack:
            p, hist, q = stack.pop()
            probs = self.allocation(p, hist)
            acc = sigma.setdefault(p, [Fraction(0)] * self.n)
            for k, pk in enumerate(probs):
                acc[k] += q * pk
                if pk:
                    stack.extend((int(c), self.after(hist, k), q * pk)
                                 for c in self.tree.children(p))
        return sigma

    def history_dependent(self) -> int:
        """(type, prefix) decisions whose rows differ between Defender histories."""
        rows: dict[tuple[str, str], set[tuple[Fraction, ...]]] = defaultdict(set)
        for label, row in self.beh.items():
            m = re.fullmatch(r"(T\d+ p\d+) h\S+", label)
            if m is not None:
                rows[(m[1], "")].add(tuple(row[a] for a in sorted(row)))
        return sum(len(v) > 1 for v in rows.values())


def profile_from_behaviour(tree: WalkTree, behaviour: ExactBehaviour, *,
                           attacker_observes: bool = True, forced_moves: bool = False,
                           solver: Mapping[str, Any] | None = None) -> ImportedProfile:
    """The ``dpp`` profile of an exact behaviour profile of the exported game (module
    docstring); ``solver`` becomes the document's free-form ``solver`` record.

    ``behaviour`` maps every information set label of the export (:func:`exported_infosets`)
    to its actions' probabilities, each distribution summing to exactly 1.

    Raises
    ------
    ProfileError
        An information set or action of the game without a probability.

    Examples
    --------
    The module docstring converts the triangle's equilibrium; an incomplete profile:

    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> profile_from_behaviour(build_tree(triangle(), 1), {})
    Traceback (most recent call last):
    dppverify.errors.ProfileError: the behaviour profile has no probability for 'T1 p0 h-'
    """
    game = _Game(tree, behaviour, attacker_observes, forced_moves)
    inst = tree.instance
    ids = [node_to_json(v) for v in inst.nodes]

    def walk(p: int) -> list[Any]:
        return [ids[v] for v in tree.walk(p)]

    try:
        walks = [game.walks(theta) for theta in range(game.n)]
        sigma = game.defender()
    except KeyError as exc:
        raise ProfileError(f"the behaviour profile has no probability for {exc.args[0]!r}") \
            from None
    attacker = [[{"path": walk(p), "probability": str(q)} for p, q in sorted(w.items()) if q]
                for w in walks]
    doc: dict[str, Any]
    if game.n == 2:
        roles = inst.roles()
        first = inst.goals.index(roles.g1)
        doc = {"format": "dpp-profile/1",
               "goals": {"primary": ids[roles.g1], "secondary": ids[roles.g2]},
               "defender": {"rule": "table", "goal": ids[roles.g1], "entries": [
                   {"walk": walk(p), "probability": str(s[first])}
                   for p, s in sorted(sigma.items())]},
               "attacker": {"primary": attacker[first], "secondary": attacker[1 - first]},
               "exact": True, "tolerance": None}
    else:
        doc = {"format": "dpp-ngoal-profile/1", "goals": [ids[g] for g in inst.goals],
               "attacker": attacker,
               "defender": {"rule": "table", "entries": [
                   {"walk": walk(p), "probabilities": [str(x) for x in s]}
                   for p, s in sorted(sigma.items())]}}
    if solver is not None:
        doc["solver"] = dict(solver)
    dependent = game.history_dependent() if attacker_observes else 0
    return ImportedProfile(doc, dependent)
