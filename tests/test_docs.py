"""The docs a newcomer acts on: nothing points outside the repository, every page they name exists,
the README says which paper this is and how to give keys, docs/faithful.md's table is the one the
measurement log holds, and the defaults the docs state are the ones a run gets."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from pillagerbench.config.compose import load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.teams import team_from_config

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", ROOT / "CONTRIBUTING.md", *sorted((ROOT / "docs").glob("*.md"))]


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_no_page_points_outside_the_repository_or_to_a_missing_page(page):
    text = page.read_text(encoding="utf-8")
    assert "../shared" not in text and "shared/reference" not in text, page.name
    for name in set(re.findall(r"docs/([\w-]+\.md)", text)):
        assert (ROOT / "docs" / name).exists(), f"{page.name} names docs/{name}, which does not exist"


def test_the_readme_says_which_paper_where_the_original_lives_and_how_to_give_keys():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    for needed in (
        "arXiv:2509.06235",
        "https://github.com/aialt/PillagerBench",
        "OPENAI_API_KEY",
        "OPENROUTER_API_KEY",
    ):
        assert needed in readme, needed
    assert "paper=true" in readme and "plan=true" in readme
    assert "`random` (the Random baseline: random executable actions, no LLM)" in readme


def rows(text: str) -> dict[tuple[str, str], list[str]]:
    out = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) > 3 and cells[0] in ("Mushroom War", "Dash & Dine"):
            out[(cells[0], cells[1])] = cells[2:]
    return out


def test_the_faithful_pages_table_is_the_measurement_logs():
    faithful = rows((ROOT / "docs" / "faithful.md").read_text(encoding="utf-8"))
    log = rows((ROOT / "docs" / "fidelity.md").read_text(encoding="utf-8").split("\n## ")[1])
    assert len(faithful) == 8 and set(faithful) == set(log)
    for key, (ours, reference, ratio) in faithful.items():
        assert ours == log[key][0] and ratio == log[key][1] and reference == log[key][4], key


def test_cots_answer_cap_is_the_one_docs_agents_states():
    team = team_from_config(RunConfig.of(load_config(["red=cot"])).red, "mushroom_war")
    stated = re.search(r"`max_tokens` \((\d+)", (ROOT / "docs" / "agents.md").read_text(encoding="utf-8"))
    assert stated and team.max_tokens == int(stated.group(1)) == 4096
