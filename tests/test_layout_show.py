"""`pillagerbench layout show`: the page draws the layout's own blocks and players (headless
Chromium, read from the canvas), loads nothing; `--json` writes a file that `layout=FILE.json`
plays back as the same layout; every bad input is one line naming the problem, exit 2, nothing
written. In-process (cli.main)."""

from __future__ import annotations

import json
import re

import pytest

from pillagerbench.cli import commands as cli
from pillagerbench.scenarios import make_scenario
from tests.support.browser import chromium
from tests.support.map_cells import at_spawns, drawn, probe_cells


def layout(capsys, *argv: str) -> str:
    assert cli.main(["layout", "show", *argv]) == 0
    out, err = capsys.readouterr()
    assert err == "", err
    return out.strip().removeprefix("layout: ")


@pytest.mark.parametrize("name", ["mushroom_war", "dash_and_dine"])
def test_the_page_draws_the_layouts_blocks_and_its_players_at_their_spawns(tmp_path, monkeypatch, capsys, name):
    chromium()
    monkeypatch.chdir(tmp_path)
    page = tmp_path / layout(capsys, name, "42")
    assert page.name == f"layout_{name}_42.html"
    text = page.read_text()
    assert not re.search(r"""(src|href)=["']?https?:""", text)  # self-contained: no network
    scenario, paper = make_scenario(name, layout=42), make_scenario(name)
    players = scenario.all_players()
    near = [(p.spawn[0], p.spawn[2]) for p in players] + [(m[1][0], m[1][2]) for m in scenario.arena.mobs]
    cells = probe_cells(scenario.arena.blocks, paper.arena.blocks, near)
    result = drawn(page, cells, players)
    assert result["console_errors"] == []
    wrong = [c for c in result["cells"] if c[3] != c[4]]
    assert not wrong, wrong[:5]
    assert len(cells) >= 15
    # the paper's map differs there: the page is the layout's, not the paper's
    assert sum(c[2] == "grass_block" for c in result["cells"]) >= 5
    assert set(result["markers"]) == {p.name for p in players}
    assert at_spawns(result, slack=0.5) == []
    assert f"{players[0].name} at {players[0].spawn}" in text  # the spawns, said in words too


@pytest.mark.parametrize(
    "name, key",
    [
        ("mushroom_war", 42),
        ("mushroom_war", 999_999_999),
        ("dash_and_dine", 42),
        ("dash_and_dine", "paper"),
        ("mushroom_war", "paper"),
    ],
)
def test_json_is_a_layout_file_that_plays_back_as_the_same_layout(tmp_path, monkeypatch, capsys, name, key):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / layout(capsys, name, str(key), "--json")
    assert path.name == f"layout_{name}_{key}.json"
    assert json.loads(path.read_text())["scenario"] == name
    again = make_scenario(name, layout=str(path))
    original = make_scenario(name, layout=key)
    assert again.layout.model_copy(update={"key": key}) == original.layout
    assert again.arena == original.arena
    assert layout(capsys, name, str(path), "--json", "--out", "copy.json") == "copy.json"
    assert (tmp_path / "copy.json").read_text() == path.read_text().replace(
        f'"key": {json.dumps(key)}', f'"key": "{path}"'
    )


def broken(tmp_path, name: str, change) -> str:
    data = make_scenario(name, layout=7).layout.model_dump(mode="json")
    change(data)
    path = tmp_path / "broken.json"
    path.write_text(json.dumps(data))
    return str(path)


def moved_mushroom(data):
    data["blue"]["mushrooms"][0] = [data["blue"]["mushrooms"][0][0] + 1, data["blue"]["mushrooms"][0][1]]


BAD = {
    "unknown scenario": (
        lambda p: ["minecraft", "42"],
        "unknown scenario 'minecraft'; known: dash_and_dine, mushroom_war",
    ),
    "a word": (lambda p: ["mushroom_war", "abc"], "layout='abc': valid: paper, a seed"),
    "a negative seed": (lambda p: ["mushroom_war", "-3"], "layout=-3: a seed is an integer from 0 to"),
    "a seed too large": (lambda p: ["dash_and_dine", str(2**53)], "a seed is an integer from 0 to"),
    "no such file": (lambda p: ["mushroom_war", "nowhere.json"], "layout=nowhere.json: no such layout file"),
    "a name with a line break": (lambda p: ["mushroom_war", "two\nlines.json"], "layout=two lines.json: no such"),
    "the other scenario's file": (
        lambda p: ["mushroom_war", broken(p, "dash_and_dine", lambda d: None)],
        "a layout of 'dash_and_dine', not of mushroom_war",
    ),
    "a file failing the rules": (
        lambda p: ["mushroom_war", broken(p, "mushroom_war", moved_mushroom)],
        "blue is not the",
    ),
    "a file of the wrong shape": (
        lambda p: ["dash_and_dine", broken(p, "dash_and_dine", lambda d: d["red"].update(server="here"))],
        "red.server: ",
    ),
    "not JSON": (lambda p: ["mushroom_war", str(p / "x.json")], "not a layout file"),
    "no layout": (lambda p: ["mushroom_war"], "the following arguments are required: SEED|paper|FILE.json"),
    "an unknown action": (lambda p: ["draw", "mushroom_war", "1"], "invalid choice: 'draw'"),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_input_is_one_line_naming_the_problem_and_writes_nothing(tmp_path, monkeypatch, capsys, case):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.json").write_text("{not json")
    args, expected = BAD[case]
    argv = args(tmp_path)
    before = set(tmp_path.iterdir())
    assert cli.main(["layout", *(argv if case == "an unknown action" else ["show", *argv])]) == 2
    out, err = capsys.readouterr()
    assert out == "" and len(err.strip().splitlines()) == 1, err
    assert err.startswith("pillagerbench layout: ") and expected in err, err
    assert set(tmp_path.iterdir()) == before
