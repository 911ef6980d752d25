from __future__ import annotations

import pytest

from pillagerbench.agents.prompts import PromptError, PromptTemplate, load_prompts


def test_render_checks_names_both_ways(tmp_path):
    (tmp_path / "a.txt").write_text("Team $team at ${x}y costs $$5; code: `$${v}`\n")
    tpl = load_prompts(tmp_path)["a"]
    assert tpl.placeholders == {"team", "x"}
    assert tpl.render(team="red", x=3) == "Team red at 3y costs $5; code: `${v}`\n"
    assert tpl.render({"team": "$x"}, x=1).startswith("Team $x at 1y")  # values are not expanded again
    with pytest.raises(PromptError, match="missing values for x"):
        tpl.render(team="red")
    with pytest.raises(PromptError, match="does not use: extra"):
        tpl.render(team="red", x=1, extra=2)


def test_a_lone_dollar_fails_at_load(tmp_path):
    (tmp_path / "b.txt").write_text("one\ncosts $ 5\n")
    with pytest.raises(PromptError, match="line 2"):
        PromptTemplate.load(tmp_path / "b.txt")


def test_the_cot_prompts_load():
    from pillagerbench.teams.cot.team import PROMPTS

    assert {"system", "user", "retry", "code_format", "people_said"} <= set(PROMPTS)
    assert PROMPTS["user"].placeholders == {
        "last_code",
        "last_errors",
        "last_chat",
        "nearby_blocks",
        "nearby_entities",
        "team_name",
        "team_players",
        "scenario",
        "task",
        "people_said",  # what the team's people said (people_said.txt; empty without a person)
    }
