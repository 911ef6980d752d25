"""The server's player order per episode: sides interleaved, the first side alternating."""

from __future__ import annotations

import pytest

from pillagerbench.match import Match
from pillagerbench.scenarios import make_scenario


@pytest.mark.parametrize("key", ["mushroom_war", "dash_and_dine"])
def test_player_order_alternates_the_first_side_and_keeps_everyone(tmp_path, key):
    sc = make_scenario(key)
    match = Match(None, sc, {}, tmp_path)
    red, blue = (s.player_names for s in sc.sides)
    even, odd = match.player_order(0), match.player_order(1)
    assert sorted(even) == sorted(odd) == sorted(p.name for p in sc.all_players())
    assert even[:4] == [red[0], blue[0], red[1], blue[1]]
    assert odd[:4] == [blue[0], red[0], blue[1], red[1]]
    assert match.player_order(2) == even
