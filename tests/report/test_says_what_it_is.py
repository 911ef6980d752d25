"""The report says what it is (issue 31, item 7): each run's provenance from its manifests, a table
of contents naming exactly the sections on the page, no empty section, "n = 1" where a value has
no interval, S from upstream's reference σ (with a note) when the runs carry no calibration, both
sides in the timeline, and nothing written outside --out (hand-made runs, no server)."""

from __future__ import annotations

import hashlib
import html
import json
import re
import shutil
from pathlib import Path

import pytest

from pillagerbench.config.schema import RunConfig
from pillagerbench.metrics.calibration import REFERENCE_FALLBACK
from pillagerbench.metrics.reference import REFERENCE_SCORES
from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.build import build_report
from pillagerbench.report.build import main as report_main
from pillagerbench.report.plots import timeline_lines
from pillagerbench.teams.entrant import entrant_of
from tests.metrics.fake_runs import write_run

FIXTURE = Path(__file__).resolve().parents[1] / "replay" / "fixtures" / "episode_000"
REVISION = "0123456789abcdef0123456789abcdef01234567"


def with_manifest(run: Path, **config) -> Path:
    """The run's manifest.json as a real run writes it: git revision, seed, created, and `config` keys."""
    manifest = json.loads((run / "manifest.json").read_text())
    manifest["config"] |= config
    manifest |= {"git_revision": REVISION, "seed": manifest["config"]["seed"], "created": "2026-01-02T03:04:05+0000"}
    (run / "manifest.json").write_text(json.dumps(manifest))
    return run


def table_after(page: str, heading: str) -> list[dict[str, str]]:
    """The rows of the HTML table under the section heading `heading`, as {column: cell}."""
    start = page.index(f">{html.escape(heading)}</h2>")
    body = page[start : page.index("</table>", start)]
    cols = re.findall(r"<th>(.*?)</th>", body)
    rows = re.findall(r"<tr>(.*?)</tr>", body, re.S)
    cells = [re.findall(r"<td>(.*?)</td>", r, re.S) for r in rows]
    return [dict(zip(cols, [html.unescape(c) for c in row])) for row in cells if row]


def headings(page: str) -> list[str]:
    return [html.unescape(h) for h in re.findall(r"<h2 id='section-\d+'>(.*?)</h2>", page)]


def contents(page: str) -> list[str]:
    nav = page[page.index("<nav id='contents'>") : page.index("</nav>")]
    return [html.unescape(h) for h in re.findall(r"<a href='#section-\d+'>(.*?)</a>", nav)]


def test_the_provenance_of_every_run_reads_back_from_the_page(tmp_path):
    llm = with_manifest(
        write_run(tmp_path / "llm", "mushroom_war", "cot", "balanced", [(5, 3), (4, 4)], length=6),
        seed=7,
        llm={"provider": "openai", "model": "gpt-4o"},
        red={"name": "cot", "llm": {"model": "gpt-4o-mini"}},
        scoring="upstream",
        protocol="upstream",
    )
    builtin = with_manifest(write_run(tmp_path / "builtin", "mushroom_war", "passive", "balanced", [(1, 2)], length=6))
    build_report([llm, builtin], tmp_path / "report", with_replays=False)
    page = (tmp_path / "report" / "report.html").read_text()
    rows = {r["run"]: r for r in table_after(page, "Provenance: what each run is, from its manifests")}
    config = json.loads((llm / "manifest.json").read_text())["config"]
    ids = {
        side: entrant_of(RunConfig.of(config), side).id for side in ("red", "blue")
    }  # derived: records before entrants
    assert rows[str(llm)] == {
        "run": str(llm),
        "what": "run",
        "created": "2026-01-02T03:04:05+0000",
        "revision": REVISION[:12],
        "suite": "unversioned",  # a record from before suite versions
        "scenarios": "mushroom_war v1",
        "seeds": "7",
        "episode_length": "6 s",
        "episodes": "2 of 2",
        "models": "cot: openai gpt-4o-mini",
        "entrants": f"cot@gpt-4o-mini ({ids['red']}), balanced ({ids['blue']})",
        "scoring": "upstream",
        "protocol": "upstream",
    }
    assert rows[str(builtin)]["models"] == "no LLM team"
    assert (rows[str(builtin)]["seeds"], rows[str(builtin)]["scoring"]) == ("0", "clean")
    assert headings(page)[0] == "Provenance: what each run is, from its manifests"


def test_the_contents_name_the_sections_present_and_empty_ones_are_left_off(tmp_path):
    run = write_run(tmp_path / "run", "mushroom_war", "passive", "balanced", [(3, 1), (2, 2), (4, 0)])
    build_report([run], tmp_path / "report", with_replays=False)
    out = tmp_path / "report"
    page = (out / "report.html").read_text()
    shown = headings(page)
    assert contents(page) == shown and len(shown) >= 10
    # nothing skipped, no lag, no evaluation groups, no self-play, no fidelity data: off the page ...
    for empty in ("Skipped", "Played under lag", "Groups", "Self-play series"):
        assert not any(h.startswith(empty) for h in shown), empty
    assert not any(h.startswith("Fidelity") for h in shown)
    assert "(empty)" not in page
    # ... while their files are still written (scripts rely on the set of files)
    assert (out / "skipped.csv").exists() and (out / "groups.png").exists() and (out / "lagged.md").exists()
    assert (
        "Summary per red entrant (all scenarios and opponents)" in shown and "Points over time: Mushroom War" in shown
    )


def test_a_one_episode_run_says_n_is_1(tmp_path):
    run = write_run(tmp_path / "run", "mushroom_war", "passive", "balanced", [(5, 3)])
    result = build_report([run], tmp_path / "report", with_replays=False)
    assert any(n.startswith("n = 1: 1 of 1 pairing(s) rest on a single episode") for n in result["notes"])
    page = (tmp_path / "report" / "report.html").read_text()
    (summary,) = table_after(page, "Summary per red entrant (all scenarios and opponents)")
    assert summary["P"] == "5.00 (n = 1)" and summary["D"] == "2.00 (n = 1)"
    assert "| passive | 1 | 1 | 5.00 (n = 1) |" in (tmp_path / "report" / "summary.md").read_text()


def test_without_calibration_s_comes_from_the_reference_sigma_with_a_note(tmp_path):
    run = write_run(tmp_path / "run", "mushroom_war", "passive", "balanced", [(5, 3), (3, 5)])
    result = build_report([run], tmp_path / "report", with_replays=False)
    sigma = REFERENCE_SCORES["mushroom_war"]["balanced"]
    pairing = next(
        line for line in (tmp_path / "report" / "pairings.csv").read_text().splitlines() if ",balanced," in line
    )
    assert float(pairing.split(",")[6]) == pytest.approx(sigma - 4)  # S = σ_blue − the opponent's mean points
    assert any(n.startswith(f"σ_blue for mushroom_war from {REFERENCE_FALLBACK}") for n in result["notes"])
    assert not any("S is left empty" in n for n in result["notes"])
    # a run that carries its own σ (do_nothing-red episodes) keeps it: no fallback
    own = write_run(tmp_path / "own", "mushroom_war", "do_nothing", "balanced", [(0, 10), (0, 12)])
    notes = build_report([run, own], tmp_path / "own_report", with_replays=False)["notes"]
    assert not any(REFERENCE_FALLBACK in n for n in notes)
    assert "mushroom_war,balanced,11.0," in (tmp_path / "own_report" / "calibration.csv").read_text()


def test_the_timeline_draws_both_sides(tmp_path):
    run = write_run(tmp_path / "run", "mushroom_war", "passive", "balanced", [(6, 2), (4, 4)])
    df = load_runs([run]).episodes
    lines = timeline_lines(df, "mushroom_war")
    assert [(x["red"], x["side"]) for x in lines] == [("passive", "red"), ("passive", "blue")]
    red, blue = lines
    assert red["mean"][-1] == pytest.approx(5.0) and blue["mean"][-1] == pytest.approx(3.0)
    assert blue["half"] is not None and blue["half"][-1] > 0  # its own 95 % band
    assert "balanced" not in red["label"] and "opponents (blue)" in blue["label"]


def tree(path: Path) -> dict[str, str]:
    return {
        str(p.relative_to(path)): hashlib.sha256(p.read_bytes()).hexdigest() for p in path.rglob("*") if p.is_file()
    }


def test_report_writes_nothing_into_the_run_directories(tmp_path, capsys):
    run = write_run(tmp_path / "run", "mushroom_war", "passive", "balanced", [(4, 4), (1, 2)])
    shutil.copy(FIXTURE / "replay.jsonl.gz", run / "episode_000")
    before = tree(tmp_path)
    assert report_main([str(run), "--out", str(tmp_path / "out")]) == 0
    after = tree(tmp_path)
    assert {k: v for k, v in after.items() if not k.startswith("out/")} == before
    assert "out/replays/run/episode_000.html" in after and "out/report.html" in after
    assert f"report: {tmp_path / 'out' / 'report.html'}" in capsys.readouterr().out
