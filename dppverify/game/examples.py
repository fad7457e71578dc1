"""Small bundled games for examples, doctests and quick experiments, two goals or more.

The triangle is proofs/ERRATA.md E1's smallest instance with all the structure of the game: the
secondary walk ``s -> g2`` is all phase II, the primary mixes ``s -> g1`` (4/7) with
``s -> g2`` (3/7), and ``U* = 12/5``. The kite is the two-goal game of the README.

``star3`` is a hub graph with three goals: from ``s`` one step to the hub ``m``, from which
each goal is one step away, plus a direct edge ``s–a`` of weight 2. Walking through ``m``
keeps every goal possible for one more step. ``hub4`` is the four-goal hub where the
coalition DP is not the value (``proofs/NGOAL.md``); :func:`hub_document` draws random hubs of
its family (the proof checks' and the property tests' N-goal games).
"""

from __future__ import annotations

import random
from fractions import Fraction
from typing import Any

from dppverify.game.instance import Instance, instance_from_json

__all__ = ["fork", "hub4", "hub4_document", "hub_document", "kite", "kite_document",
           "kite_naive_profile", "star3", "star3_document", "star3_profile", "triangle",
           "triangle_attacker", "triangle_document", "triangle_profile"]


def triangle_document(prior: tuple[str, str] = ("7/10", "3/10")) -> dict[str, Any]:
    """The triangle ``s–g2`` (2), ``g2–g1`` (2), ``s–g1`` (3) as an instance document.

    Parameters
    ----------
    prior : (str, str)
        The prior of ``goals[0]`` and ``goals[1]``, as exact strings.

    Returns
    -------
    dict
        The instance document (``docs/formats.md`` §1).

    Examples
    --------
    >>> doc = triangle_document()
    >>> doc["start"], doc["goals"], doc["prior"]
    ('s', ['g1', 'g2'], ['7/10', '3/10'])
    """
    return {"graph": {"nodes": [{"id": "s"}, {"id": "g1"}, {"id": "g2"}],
                      "edges": [{"source": "s", "target": "g2", "weight": 2},
                                {"source": "g2", "target": "g1", "weight": 2},
                                {"source": "s", "target": "g1", "weight": 3}]},
            "start": "s", "goals": ["g1", "g2"], "prior": list(prior)}


def triangle(prior: tuple[str, str] = ("7/10", "3/10")) -> Instance:
    """The triangle as a parsed :class:`~dppverify.game.instance.Instance`.

    Parameters
    ----------
    prior : (str, str)
        The prior of ``goals[0]`` and ``goals[1]``, as exact strings.

    Returns
    -------
    Instance

    Examples
    --------
    >>> inst = triangle()
    >>> inst.nodes[inst.roles().g1], inst.prior
    ('g1', (Fraction(7, 10), Fraction(3, 10)))
    """
    return instance_from_json(triangle_document(prior))


def fork() -> Instance:
    """The undirected path ``2 - 0 - 1 - 3``, start ``0``, goals ``2`` and ``3``, prior 1/2 -
    1/2 (walk trees of every depth stay small).

    Returns
    -------
    Instance

    Examples
    --------
    >>> inst = fork()
    >>> inst.start, inst.goals, inst.n_nodes
    (0, (2, 3), 4)
    """
    return instance_from_json({
        "graph": {"nodes": [{"id": 0}, {"id": 1}, {"id": 2}, {"id": 3}],
                  "edges": [{"source": 0, "target": 1}, {"source": 0, "target": 2},
                            {"source": 1, "target": 3}]},
        "start": 0, "goals": [2, 3], "prior": ["1/2", "1/2"]})


def triangle_attacker(p_g1: str = "4/7", p_g2: str = "3/7") -> dict[str, Any]:
    """The ``attacker`` part of a triangle profile: the equilibrium mixture by default.

    The primary goes ``s -> g1`` with ``p_g1`` and ``s -> g2`` with ``p_g2`` (eq. (15): 4/7
    and 3/7 at the prior 7/10); the secondary goes ``s -> g2``.

    Parameters
    ----------
    p_g1, p_g2 : str
        The primary's probabilities of ``s -> g1`` and ``s -> g2``.

    Returns
    -------
    dict
        The profile's ``attacker`` object.

    Examples
    --------
    >>> [w["probability"] for w in triangle_attacker("3/7", "4/7")["primary"]]
    ['3/7', '4/7']
    """
    return {"primary": [{"path": ["s", "g1"], "probability": p_g1},
                        {"path": ["s", "g2"], "probability": p_g2}],
            "secondary": [{"path": ["s", "g2"], "probability": 1}]}


def triangle_profile(attacker: dict[str, Any] | None = None, **claims: Any) -> dict[str, Any]:
    """A ``dpp-profile/1`` document for the triangle with the progress Defender.

    Parameters
    ----------
    attacker : dict, optional
        The ``attacker`` member (default: :func:`triangle_attacker`, the equilibrium).
    **claims
        Extra members, e.g. ``value={"U": "12/5"}`` or ``phases={...}``.

    Returns
    -------
    dict
        The ``dpp-profile/1`` document (``attacker`` given or the equilibrium's, ``claims``
        added).

    Examples
    --------
    >>> from dppverify import certify
    >>> certify(triangle_document(), triangle_profile()).verdict
    'pass'
    >>> certify(triangle_document(), triangle_profile(triangle_attacker("3/7", "4/7"))).verdict
    'fail'
    """
    return {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
            "defender": {"rule": "progress", "goal": "g1"},
            "attacker": triangle_attacker() if attacker is None else attacker, **claims}


def kite_document(prior: tuple[str, str] = ("3/5", "2/5")) -> dict[str, Any]:
    """The kite ``s–g1``, ``s–g2`` of weight 2, ``s–a`` 1, ``a–g1``, ``a–g2`` 1: the game
    where a PASS at ``H = 1`` is not one of the untruncated game.

    Walking straight to one's goal (one step of weight 2) is an equilibrium of the game
    truncated at ``H = 1`` but not of the untruncated game, where the secondary's detour
    ``s a g2`` (two steps) costs 1 against σ*; ``V = 8/5``.

    Parameters
    ----------
    prior : (str, str)
        The prior of ``goals[0]`` and ``goals[1]``, as exact strings.

    Returns
    -------
    dict
        The instance document (``docs/formats.md`` §1).

    Examples
    --------
    >>> from dppverify import certify
    >>> certify(kite_document(), kite_naive_profile()).verdict
    'fail'
    >>> certify(kite_document(), kite_naive_profile(), horizon=1).verdict
    'pass'
    """
    edges = [("s", "g1", 2), ("s", "g2", 2), ("s", "a", 1), ("a", "g1", 1), ("a", "g2", 1)]
    return {"graph": {"directed": False,
                      "nodes": [{"id": v} for v in ("s", "a", "g1", "g2")],
                      "edges": [{"source": u, "target": v, "weight": w} for u, v, w in edges]},
            "start": "s", "goals": ["g1", "g2"], "prior": list(prior)}


def kite(prior: tuple[str, str] = ("3/5", "2/5")) -> Instance:
    """The kite (:func:`kite_document`) as a parsed :class:`~dppverify.game.instance.Instance`.

    Parameters
    ----------
    prior : (str, str)
        The prior of ``goals[0]`` and ``goals[1]``, as exact strings.

    Returns
    -------
    Instance

    Examples
    --------
    >>> kite().nodes
    ('s', 'a', 'g1', 'g2')
    """
    return instance_from_json(kite_document(prior))


def kite_naive_profile() -> dict[str, Any]:
    """Each type walks straight to its goal; the Defender is σ* (the progress rule to g1).

    Returns
    -------
    dict
        The profile document.

    Examples
    --------
    >>> kite_naive_profile()["attacker"]["secondary"]
    [{'path': ['s', 'g2'], 'probability': 1}]
    """
    return {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
            "defender": {"rule": "progress", "goal": "g1"},
            "attacker": {"primary": [{"path": ["s", "g1"], "probability": 1}],
                         "secondary": [{"path": ["s", "g2"], "probability": 1}]}}


def star3_document(prior: tuple[str, ...] = ("1/2", "1/3", "1/6")) -> dict[str, Any]:
    """The hub instance ``s–m`` (1), ``m–a``, ``m–b``, ``m–c`` (1 each), ``s–a`` (2).

    Parameters
    ----------
    prior : tuple of str
        One exact prior per goal.

    Returns
    -------
    dict
        The instance document (``docs/formats.md`` §1).

    Examples
    --------
    >>> doc = star3_document()
    >>> doc["goals"], doc["prior"]
    (['a', 'b', 'c'], ['1/2', '1/3', '1/6'])
    """
    return {"graph": {"directed": False,
                      "nodes": [{"id": v} for v in ("s", "m", "a", "b", "c")],
                      "edges": [{"source": "s", "target": "m", "weight": 1},
                                {"source": "m", "target": "a", "weight": 1},
                                {"source": "m", "target": "b", "weight": 1},
                                {"source": "m", "target": "c", "weight": 1},
                                {"source": "s", "target": "a", "weight": 2}]},
            "start": "s", "goals": ["a", "b", "c"], "prior": list(prior)}


def star3(prior: tuple[str, ...] = ("1/2", "1/3", "1/6")) -> Instance:
    """The hub instance, parsed.

    Parameters
    ----------
    prior : tuple of str
        One exact prior per goal.

    Returns
    -------
    Instance

    Examples
    --------
    >>> inst = star3()
    >>> inst.n_goals, inst.labels(inst.goals)
    (3, ('a', 'b', 'c'))
    """
    return instance_from_json(star3_document(prior))


def star3_profile() -> dict[str, Any]:
    """An equilibrium profile of the hub instance at ``H = 2`` (``dpp-ngoal-profile/1``).

    Every type walks ``s m`` and then to its own goal; the Defender guards ``a`` (the
    largest prior) on ``s m`` and everywhere off the walks, and the true goal on ``s m b``
    and ``s m c``. ``U = 1/2 · 2 + 1/3 · 1 + 1/6 · 1 = 3/2 = V_2``.

    Returns
    -------
    dict
        The ``dpp-ngoal-profile/1`` document.

    Examples
    --------
    >>> [mix[0]["path"] for mix in star3_profile()["attacker"]]
    [['s', 'm', 'a'], ['s', 'm', 'b'], ['s', 'm', 'c']]
    """
    return {"format": "dpp-ngoal-profile/1", "goals": ["a", "b", "c"],
            "attacker": [[{"path": ["s", "m", g], "probability": 1}] for g in ("a", "b", "c")],
            "defender": {"rule": "table",
                         "entries": [{"walk": ["s", "m", "b"], "probabilities": [0, 1, 0]},
                                     {"walk": ["s", "m", "c"], "probabilities": [0, 0, 1]}],
                         "default": [1, 0, 0]},
            "value": {"U": "3/2"}}


def hub4_document(prior: tuple[str, ...] = ("2/7", "2/7", "2/7", "1/7"), *,
                  directed: bool = True) -> dict[str, Any]:
    """The four-goal hub where the coalition DP is not the value (``proofs/NGOAL.md``).

    Unit arcs ``u→u1``; ``u1→A, B, C``; ``A→g1, g2``; ``B→g1, g3``; ``C→g2, g3, g4``; return
    arcs ``g_i→u`` of weight 10 (they keep the goals' distances finite). Start ``u``. With
    the default prior the coalition DP is 25/14 and the value 12/7 at every ``H >= 3``.
    ``directed=False`` gives the undirected version (same gap).

    Parameters
    ----------
    prior : tuple of str
        One exact prior per goal.
    directed : bool
        Directed arcs (the hub's) or undirected edges.

    Returns
    -------
    dict
        The instance document (``docs/formats.md`` §1).

    Examples
    --------
    >>> doc = hub4_document()
    >>> len(doc["graph"]["edges"]), doc["prior"]
    (15, ['2/7', '2/7', '2/7', '1/7'])
    """
    arcs = [("u", "u1", 1), ("u1", "A", 1), ("u1", "B", 1), ("u1", "C", 1),
            ("A", "g1", 1), ("A", "g2", 1), ("B", "g1", 1), ("B", "g3", 1),
            ("C", "g2", 1), ("C", "g3", 1), ("C", "g4", 1)]
    arcs += [(g, "u", 10) for g in ("g1", "g2", "g3", "g4")]
    nodes = ("u", "u1", "A", "B", "C", "g1", "g2", "g3", "g4")
    return {"graph": {"directed": directed, "nodes": [{"id": v} for v in nodes],
                      "edges": [{"source": a, "target": b, "weight": w} for a, b, w in arcs]},
            "start": "u", "goals": ["g1", "g2", "g3", "g4"], "prior": list(prior)}


def hub4(prior: tuple[str, ...] = ("2/7", "2/7", "2/7", "1/7"), *,
         directed: bool = True) -> Instance:
    """The four-goal hub, parsed (:func:`hub4_document`).

    Parameters
    ----------
    prior : tuple of str
        One exact prior per goal.
    directed : bool
        Directed arcs (the hub's) or undirected edges.

    Returns
    -------
    Instance

    Examples
    --------
    >>> hub4().n_goals
    4
    """
    return instance_from_json(hub4_document(prior, directed=directed))


def hub_document(rng: random.Random, n_goals: int, *, directed: bool | None = None,
                 shortcuts: bool = True, returns: bool = True) -> dict[str, Any]:
    """A random hub of :func:`hub4_document`'s family: ``u → u1 → m_j → (two or three goals)``.

    Two to four middles ``m_j``, arc weights 1 or 2; every goal reachable; return arcs
    ``g → u`` of weight 10 unless ``returns=False`` (they keep the distances between goals
    finite); random priors (weights 1..6, normalised).

    Parameters
    ----------
    rng : random.Random
        The only source of randomness: the same seed draws the same document.
    n_goals : int
        ``N >= 2`` (four or five make gaps between the coalition DP and the value likely).
    directed : bool or None
        None draws it (directed with probability 0.6).
    shortcuts : bool
        Also draw ``u1 → g`` (probability 0.2 per goal, weight 2..4) and ``u → m`` (0.3).
    returns : bool
        The return arcs ``g → u``.

    Returns
    -------
    dict
        The instance document (``docs/formats.md`` §1).

    Examples
    --------
    >>> doc = hub_document(random.Random(3), 4, directed=True)
    >>> doc["start"], doc["goals"], doc["graph"]["directed"]
    ('u', ['g1', 'g2', 'g3', 'g4'], True)
    >>> doc == hub_document(random.Random(3), 4, directed=True)
    True
    """
    goals = [f"g{i + 1}" for i in range(n_goals)]
    mids = [f"m{j}" for j in range(rng.randint(2, 4))]
    arcs = {("u", "u1"): rng.randint(1, 2)}
    for m in mids:
        arcs[("u1", m)] = rng.randint(1, 2)
        for g in rng.sample(goals, rng.randint(2, min(3, n_goals))):
            arcs[(m, g)] = rng.randint(1, 2)
    for g in goals:
        if returns:
            arcs[(g, "u")] = 10
        if not any((m, g) in arcs for m in mids):  # every goal reachable from the start
            arcs[(rng.choice(mids), g)] = rng.randint(1, 2)
        if shortcuts and ("u1", g) not in arcs and rng.random() < 0.2:
            arcs[("u1", g)] = rng.randint(2, 4)
    if shortcuts and rng.random() < 0.3:
        arcs[("u", rng.choice(mids))] = rng.randint(2, 3)
    if directed is None:
        directed = rng.random() < 0.6
    ws = [rng.randint(1, 6) for _ in range(n_goals)]
    return {"graph": {"directed": directed,
                      "nodes": [{"id": v} for v in ["u", "u1", *mids, *goals]],
                      "edges": [{"source": a, "target": b, "weight": w}
                                for (a, b), w in arcs.items()]},
            "start": "u", "goals": goals, "prior": [str(Fraction(w, sum(ws))) for w in ws]}
