"""Ratings and scheduling on synthetic outcomes (no server)."""

from __future__ import annotations

from pillagerbench.league.ratings import Outcome, Rating, ranked, rate
from pillagerbench.league.schedule import next_round, open_pairs, settled
from pillagerbench.league.simulate import SCENARIO, order, scheduled

STRENGTHS = {"do_nothing": 0.05, "passive": 1.0, "balanced": 4.0, "aggressive": 16.0, "slimy": 64.0}
TRUE_ORDER = sorted(STRENGTHS, key=lambda n: -STRENGTHS[n])


def wins(a: str, b: str, n: int, start: int = 0) -> list[Outcome]:
    return [Outcome(SCENARIO, a, b, 1.0, 0.0, (start + i,)) for i in range(n)]


def test_a_clearly_stronger_team_ends_on_top_and_do_nothing_anchors_zero():
    outs = wins("strong", "weak", 10) + wins("weak", "do_nothing", 10, 10) + wins("strong", "do_nothing", 10, 20)
    r = rate(outs, ["weak", "do_nothing", "strong"])
    assert ranked(r) == ["strong", "weak", "do_nothing"]
    assert r["do_nothing"].mu == 0.0 and r["strong"].conservative > r["weak"].mu - 3 * r["weak"].sigma
    assert r["strong"].episodes == 20


def test_the_same_outcomes_give_the_same_ratings_in_any_file_order():
    outs = wins("a", "b", 5) + wins("b", "a", 2, 5) + [Outcome(SCENARIO, "a", "b", 1.0, 1.0, (7,))]
    assert rate(outs, ["a", "b"]) == rate(list(reversed(outs)), ["a", "b"])


def test_draws_keep_two_teams_level():
    outs = [Outcome(SCENARIO, "a", "b", 0.0, 0.0, (i,)) for i in range(6)]
    r = rate(outs, ["a", "b"])
    assert abs(r["a"].mu - r["b"].mu) < 1e-9 and r["a"].sigma < 25 / 3


def test_scheduler_ranks_the_teams_correctly_and_stops_by_itself():
    outs, done = scheduled(STRENGTHS, seed=1, budget=1500)
    assert done and order(outs, STRENGTHS) == TRUE_ORDER
    assert not open_pairs(rate(outs, STRENGTHS), 0.95)


def test_only_open_adjacent_pairs_are_scheduled():
    r = {"a": Rating(30, 1, 50), "b": Rating(20, 1, 50), "c": Rating(19.5, 1, 50)}
    got = next_round({SCENARIO: r}, [], 0.95, 3)
    assert [(p.red, p.blue) for p in got] == [("b", "c")]  # a vs b is separated, a vs c is not adjacent
    assert settled({SCENARIO: {"a": r["a"], "b": r["b"]}}, 0.95)


def test_an_entrant_added_later_plays_only_its_own_matches():
    outs, done = scheduled(STRENGTHS, seed=2, budget=1500)
    assert done
    late = {**STRENGTHS, "newcomer": 8.0}
    more, done = scheduled(late, seed=3, budget=1500, outcomes=outs)
    added = more[len(outs) :]
    own = [o for o in added if "newcomer" in (o.red, o.blue)]
    assert all("newcomer" in (o.red, o.blue) for o in added[:4])  # the first round: only the newcomer's pairs
    # an established pair reopens only when the newcomer's results moved one of its entrants
    assert len(own) >= 0.9 * len(added), [(o.red, o.blue) for o in added if o not in own]
    assert len(added) < len(outs)  # placing one entrant costs less than the league did
    assert done and order(more, late).index("newcomer") == 2  # between aggressive (16) and balanced (4)


def test_sides_alternate_within_a_pairing():
    r = {"a": Rating(20, 5, 2), "b": Rating(20, 5, 2)}
    first = next_round({SCENARIO: r}, [], 0.95, 1)[0]
    again = next_round({SCENARIO: r}, wins(first.red, first.blue, 1), 0.95, 1)[0]
    assert (again.red, again.blue) == (first.blue, first.red)


def test_the_budget_stops_an_unsettled_league():
    outs, done = scheduled({"a": 1.0, "b": 1.0}, seed=0, budget=20)
    assert not done and len(outs) == 20
