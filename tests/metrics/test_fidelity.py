"""The fidelity check on run directories written by hand: the table against upstream's reference
scores, each of the paper's claims (holding and failing), and the one-line notes on bad input."""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest

from pillagerbench.metrics.calibration import resolve
from pillagerbench.metrics.fidelity import CLAIMS, claims_table, fidelity_table
from pillagerbench.metrics.formulas import Estimate
from pillagerbench.metrics.reference import REFERENCE_SCORES
from pillagerbench.metrics.runs import ReportError
from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.build import build_report
from pillagerbench.report.fidelity import main as fidelity_main
from pillagerbench.suite.figures import reference_figures
from tests.metrics.fake_runs import write_run
from tests.support.cli import run_cli

TEN = 10
AS_REFERENCES = {"length": 120, "protocol": "upstream"}  # the references' conditions (paper=true)


def test_each_opponent_beside_its_reference_with_ratio_and_verdict(tmp_path):
    # passive: 25.0 against 25.23 (ratio 0.99 ✓); slimy 11 against 22.18 (0.50 ✗); berries 350 raw = 35.0
    write_run(tmp_path / "p", "mushroom_war", "do_nothing", "passive", [(0, 24), (0, 26)] * 5, **AS_REFERENCES)
    write_run(tmp_path / "s", "mushroom_war", "do_nothing", "slimy", [(1, 11)] * TEN, **AS_REFERENCES)
    write_run(tmp_path / "b", "dash_and_dine", "do_nothing", "berries", [(0, 340), (0, 360)] * 5, **AS_REFERENCES)
    table, notes = fidelity_table(load_runs([tmp_path / x for x in "psb"]).episodes)
    assert len(notes) == 1 and notes[0].startswith(
        f"fidelity: vs_suite compares with {reference_figures().suite}'s own reference"
    )
    rows = {r.opponent: r for r in table.itertuples()}
    # the suite's own reference (suite/reference_figures.json): passive 27.40 ± 4.04 agrees with
    # 25.0 ± 0.75, slimy 23.80 ± 2.84 does not with 11 ± 0
    mine = reference_figures().scenarios["mushroom_war"]
    passive, slimy = mine["passive"]["clean"], mine["slimy"]["clean"]
    assert abs(passive.mean - 25) < passive.ci and slimy.mean - slimy.ci > 11  # the premise
    assert (rows["passive"].suite_reference, rows["passive"].vs_suite) == (passive.mean, "✓")
    assert (rows["slimy"].suite_reference, rows["slimy"].suite_reference_ci, rows["slimy"].vs_suite) == (
        slimy.mean,
        slimy.ci,
        "✗",
    )
    assert rows["passive"].ratio == pytest.approx(25 / 25.23) and rows["passive"].within_25pct == "✓"
    assert rows["passive"].points_ci > 0 and rows["passive"].episodes == TEN and rows["passive"].side == "blue"
    assert rows["slimy"].within_25pct == "✗" and rows["slimy"].do_nothing == 1
    assert rows["berries"].points == pytest.approx(35.0) and rows["berries"].within_25pct == "✓"
    assert set(table["scoring"]) == {"clean"}


def test_an_upstream_scored_run_gives_a_row_per_scoring_and_the_red_side_its_own_row(tmp_path):
    write_run(
        tmp_path / "u",
        "mushroom_war",
        "do_nothing",
        "aggressive",
        [(0, 10)] * TEN,
        upstream=[(0, 20)] * TEN,
        **AS_REFERENCES,
    )
    write_run(tmp_path / "r", "mushroom_war", "aggressive", "do_nothing", [(16, 0)] * TEN, **AS_REFERENCES)
    with pytest.raises(
        ReportError,
        match=r"conditions: unversioned \[protocol=upstream, scoring=upstream\] in .*u; unversioned \[protocol=upstream\] in",
    ):
        load_runs([tmp_path / "u", tmp_path / "r"])  # upstream's headline scores beside clean ones: asked for only
    table, _ = fidelity_table(load_runs([tmp_path / "u", tmp_path / "r"], mix_suites=True).episodes)
    got = {(r.side, r.scoring): (r.points, r.within_25pct) for r in table.itertuples()}
    assert got == {("blue", "clean"): (10, "✗"), ("blue", "upstream"): (20, "✓"), ("red", "clean"): (16, "✓")}


def test_episodes_played_unlike_the_references_get_no_reference_and_say_what_differs(tmp_path):
    # 30 s episodes of our own protocol: upstream's 120 s figures under its protocol do not apply
    write_run(tmp_path / "short", "mushroom_war", "do_nothing", "passive", [(0, 6)] * TEN, length=30)
    table, notes = fidelity_table(load_runs([tmp_path / "short"]).episodes)
    (row,) = table.itertuples()
    assert (row.points, row.within_25pct, row.vs_suite, row.conditions) == (6, "–", "–", "")
    assert pd.isna(row.reference) and pd.isna(row.ratio) and pd.isna(row.suite_reference)
    assert notes == [
        "fidelity: no reference for these conditions (protocol=pillagerbench, episode_length=30): mushroom_war passive "
        "(blue); the references are 120 s episodes with protocol=upstream on the paper's layout (paper=true)"
    ]
    # the same scores under the references' conditions are compared with them
    write_run(tmp_path / "paper", "mushroom_war", "do_nothing", "passive", [(0, 24)] * TEN, **AS_REFERENCES)
    table, notes = fidelity_table(load_runs([tmp_path / "paper"]).episodes)
    assert table.iloc[0].within_25pct == "✓" and table.iloc[0].conditions == "protocol=upstream"
    assert not [n for n in notes if "no reference" in n]


def test_the_lockstep_clock_is_checked_against_the_same_references(tmp_path):
    # lockstep is the same game on another clock: upstream's figures and the suite's apply, and say so
    write_run(
        tmp_path / "ls", "mushroom_war", "do_nothing", "passive", [(0, 24)] * TEN,
        conditions={"clock.mode": "lockstep"}, **AS_REFERENCES,
    )  # fmt: skip
    table, notes = fidelity_table(load_runs([tmp_path / "ls"]).episodes)
    (row,) = table.itertuples()
    assert (row.within_25pct, row.vs_suite) == ("✓", "✓")
    assert row.conditions == "clock.mode=lockstep, protocol=upstream"
    assert not [n for n in notes if "no reference" in n]
    # a rule that is another game is still refused
    write_run(
        tmp_path / "tps", "mushroom_war", "do_nothing", "passive", [(0, 24)] * TEN,
        conditions={"server.tps": 10}, **AS_REFERENCES,
    )  # fmt: skip
    table, _ = fidelity_table(load_runs([tmp_path / "tps"]).episodes)
    assert table.iloc[0].within_25pct == "–"


def test_bad_input_is_one_line_each_and_the_rest_is_printed(tmp_path, capsys):
    write_run(tmp_path / "few", "mushroom_war", "do_nothing", "balanced", [(0, 16), (0, 17)], **AS_REFERENCES)
    write_run(tmp_path / "other", "capture_the_flag", "do_nothing", "rusher", [(0, 5)] * TEN, **AS_REFERENCES)
    assert fidelity_main([str(tmp_path / "few"), str(tmp_path / "other")]) == 0
    out = capsys.readouterr().out.splitlines()
    assert [line for line in out if "too few episodes" in line] == [
        "fidelity: too few episodes for the check (≥ 10 per opponent and side): mushroom_war balanced (blue): 2"
    ]
    assert [line for line in out if "no reference values" in line] == [
        "fidelity: no reference values for capture_the_flag (upstream measured mushroom_war, dash_and_dine only): "
        "listed without a ratio"
    ]
    assert any(line.startswith("| mushroom_war | balanced | blue | clean | 2 | 16.50 ± 6.35 |") for line in out)
    assert any(line.startswith("| capture_the_flag | rusher | blue | clean | 10 | 5.00 ± 0.00 |") for line in out)


def test_no_do_nothing_episodes_is_one_line(tmp_path, capsys):
    write_run(tmp_path / "a", "mushroom_war", "balanced", "passive", [(20, 10)] * 3)
    assert fidelity_main([str(tmp_path / "a")]) == 0
    out = capsys.readouterr().out.splitlines()
    assert [line for line in out if line.startswith("fidelity:")] == [
        "fidelity: no built-in opponent played against do_nothing in these runs, so no table against upstream's references "
        "(play experiment=fidelity)"
    ]


def test_not_a_run_directory_is_one_line(tmp_path, capsys):
    assert fidelity_main([str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "not a run directory" in err[0]


# -- the claims ---------------------------------------------------------------------------------
MW_POINTS = {"do_nothing": 2, "aggressive": 12, "balanced": 14, "passive": 25, "slimy": 20}
MW_HITS = {"aggressive": 6, "balanced": 7, "passive": 0, "slimy": 5, "do_nothing": 0}
DD_POINTS = {"do_nothing": 0, "berries": 300, "cake_beetroot": 140, "melon_pumpkin": 140, "potato_cookie": 120}
DD_HITS = {"berries": 80, "do_nothing": 0, "cake_beetroot": 0, "melon_pumpkin": 0, "potato_cookie": 0}
DD_SPECIAL = {("potato_cookie", "berries"): 270}  # potato_cookie destroys the berry bushes
DD_FIRST = {"do_nothing": 60, "berries": 10, "melon_pumpkin": 15, "cake_beetroot": 40, "potato_cookie": 35}


def round_robin(root, scenario, points, hits, special=None, first=None, episodes=3):
    """Every pairing as a run: a side scores its points less what the other side destroys of them."""

    def hit(a, b):
        return (special or {}).get((a, b), hits[a])

    runs = []
    for red in points:
        for blue in points:
            r, b = max(0, points[red] - hit(blue, red)), max(0, points[blue] - hit(red, blue))
            runs.append(
                write_run(
                    root / f"{scenario}_{red}_{blue}",
                    scenario,
                    red,
                    blue,
                    [(r, b)] * episodes,
                    length=60,
                    first_points=[(first or {}).get(red, 2)] * episodes,
                )
            )
    return runs


def sigma_of(scenario, points, scale=1.0, less=1.0):
    """σ_blue from another calibration: each opponent's points against do_nothing, less `less`."""
    return {(scenario, t): Estimate((p - less) * scale, 0.5, 20) for t, p in points.items()}


def verdicts(df, sigma):
    table, notes = claims_table(df, sigma)
    return {r.claim: r.holds for r in table.itertuples()}, table, notes


def test_every_claim_holds_on_a_round_robin_like_the_papers(tmp_path):
    runs = round_robin(tmp_path, "mushroom_war", MW_POINTS, MW_HITS)
    runs += round_robin(tmp_path, "dash_and_dine", DD_POINTS, DD_HITS, DD_SPECIAL, DD_FIRST)
    sigma = {**sigma_of("mushroom_war", MW_POINTS), **sigma_of("dash_and_dine", DD_POINTS, 0.1, 10)}
    got, table, notes = verdicts(load_runs(runs).episodes, sigma)
    assert notes == []
    assert got == {c.text: "✓" for c in CLAIMS}
    evidence = dict(zip(table["claim"], table["evidence"]))
    assert evidence[CLAIMS[0].text] == "P: passive 21.40 ± 1.72, next slimy 16.40 ± 1.72"
    assert "win rate of berries as red: do_nothing 1.00" in evidence[CLAIMS[5].text]
    assert "potato_cookie 0.00" in evidence[CLAIMS[5].text]
    assert evidence[CLAIMS[6].text].startswith("mean time to first points (non-do_nothing teams as red): 25.0 s here")


@pytest.mark.parametrize(
    ("change", "claim"),
    [
        ({"mw_points": {"passive": 10}}, 0),  # passive no longer highest in points
        ({"mw_points": {"slimy": 5}}, 1),  # slimy far from passive in win rate
        ({"mw_hits": {"passive": 9}}, 2),  # a non-breaker sabotages more than the breakers
        ({"mw_points": {"do_nothing": 0}}, 3),  # do_nothing scores nothing
        ({"dd_points": {"melon_pumpkin": 400}}, 4),  # melon_pumpkin leads in points
        ({"dd_special": {}}, 5),  # berries beats potato_cookie too
        ({"dd_first": {"berries": 1, "melon_pumpkin": 1, "cake_beetroot": 1, "potato_cookie": 1}}, 6),
        ({"dd_first": {"berries": 50}}, 7),  # berries slower than the builders
    ],
)
def test_a_claim_that_fails_shows_a_cross(tmp_path, change, claim):
    mw_points = {**MW_POINTS, **change.get("mw_points", {})}
    mw_hits = {**MW_HITS, **change.get("mw_hits", {})}
    dd_points = {**DD_POINTS, **change.get("dd_points", {})}
    special = change.get("dd_special", DD_SPECIAL)
    runs = round_robin(tmp_path, "mushroom_war", mw_points, mw_hits)
    runs += round_robin(
        tmp_path, "dash_and_dine", dd_points, DD_HITS, special, {**DD_FIRST, **change.get("dd_first", {})}
    )
    sigma = {**sigma_of("mushroom_war", mw_points), **sigma_of("dash_and_dine", dd_points, 0.1, 10)}
    got, _, _ = verdicts(load_runs(runs).episodes, sigma)
    assert got[CLAIMS[claim].text] == "✗"


def test_claims_that_cannot_be_checked_say_why(tmp_path):
    # Dash & Dine alone, without potato_cookie, two episodes per pairing
    points = {k: v for k, v in DD_POINTS.items() if k != "potato_cookie"}
    runs = round_robin(tmp_path, "dash_and_dine", points, DD_HITS, None, DD_FIRST, episodes=2)
    got, _, notes = verdicts(load_runs(runs).episodes, sigma_of("dash_and_dine", points, 0.1))
    assert got[CLAIMS[6].text] == "–" and got[CLAIMS[5].text] == "–"
    assert (
        "claims: dash_and_dine: cannot check “the time to the first points is longer than in Mushroom War”: "
        "no mushroom_war round robin among these runs" in notes
    )
    assert any(n.startswith("claims: too few episodes per pairing (≥ 3 for the claims): dash_and_dine") for n in notes)


def test_the_report_has_the_fidelity_sections_and_says_which_scoring_and_protocol(tmp_path):
    write_run(tmp_path / "u", "mushroom_war", "do_nothing", "passive", [(0, 12)] * TEN, upstream=[(0, 25)] * TEN)
    result = build_report([tmp_path / "u"], tmp_path / "report")
    assert f"{tmp_path / 'u'}: scoring upstream; LLM teams' protocol pillagerbench" in result["notes"]
    assert any(n.startswith("claims: no round robin of the built-in opponents") for n in result["notes"])
    md = (tmp_path / "report" / "fidelity.md").read_text()
    assert "| mushroom_war | passive | blue | upstream | 10 | 25.00 ± 0.00 |" in md
    assert "Fidelity" in (tmp_path / "report" / "report.html").read_text()


def test_the_command_line_says_what_it_cannot_check_in_one_line_each(tmp_path):
    write_run(tmp_path / "a", "mushroom_war", "balanced", "passive", [(20, 10)] * 2)
    for command in ("fidelity", "report"):
        proc = run_cli(tmp_path, command, str(tmp_path / "a"))
        assert proc.returncode == 0, proc.stderr
        lines = proc.stdout.splitlines()
        assert sum(line.startswith("fidelity: no built-in opponent played against do_nothing") for line in lines) == 1
        assert sum(line.startswith("claims: no round robin") for line in lines) == 1
    proc = run_cli(tmp_path, "fidelity", str(tmp_path / "nothing-here"))
    assert proc.returncode == 2 and proc.stderr.strip().count("\n") == 0 and "not a run directory" in proc.stderr


def test_do_nothing_sabotage_against_upstreams_reference_scores(tmp_path, capsys):
    # σ_blue from the round robin's own do_nothing-red episodes makes do_nothing's S exactly 0 (so
    # the claim cannot hold); `--calibration reference` uses upstream's hard-coded scores instead:
    # the four opponents here score 1 above them against do_nothing (−1 each) and the mirror match
    # keeps its own σ (0), so do_nothing's S is −4/5
    points = {"do_nothing": 2} | {t: v + 1 for t, v in REFERENCE_SCORES["mushroom_war"].items()}
    runs = round_robin(tmp_path, "mushroom_war", points, {t: 0 for t in points})
    claim = CLAIMS[3].text
    own_note = "claims: σ_blue comes from do_nothing-red episodes among these runs"

    assert fidelity_main([str(r) for r in runs]) == 0
    out = capsys.readouterr().out
    assert "S: do_nothing 0.00" in next(line for line in out.splitlines() if claim in line)
    assert sum(line.startswith(own_note) for line in out.splitlines()) == 1

    sigma, notes = resolve(load_runs(runs), Path("reference"))
    assert sigma[("mushroom_war", "passive")].mean == pytest.approx(25.23)
    assert any(n.startswith("σ_blue for mushroom_war from reference") for n in notes)
    assert fidelity_main([*map(str, runs), "--calibration", "reference"]) == 0
    out = capsys.readouterr().out
    line = next(line for line in out.splitlines() if claim in line)
    assert "S: do_nothing -0.80" in line and line.endswith("| ✓ |")
    assert own_note not in out
    # the report's fidelity section says the same as the command
    notes = build_report(runs, tmp_path / "own", with_replays=False)["notes"]
    assert sum(n.startswith(own_note) for n in notes) == 1
    notes = build_report(runs, tmp_path / "ref", calibration=Path("reference"), with_replays=False)["notes"]
    assert not any(n.startswith(own_note) for n in notes)


def test_reference_calibration_scales_dash_and_dine_like_every_reported_score(tmp_path):
    run = write_run(tmp_path / "dd", "dash_and_dine", "do_nothing", "berries", [(0, 300)] * 3)
    sigma, _ = resolve(load_runs([run]), Path("reference"))
    assert sigma[("dash_and_dine", "berries")].mean == pytest.approx(34.73)
    assert ("mushroom_war", "passive") not in sigma  # only the runs' scenarios
