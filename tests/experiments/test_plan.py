"""`pillagerbench run ... plan=true` (experiments/plan.py): series, episodes, wall time, LLM calls and
cost, and nothing played: no server, no series, no run directory."""

from pathlib import Path

import pytest

from pillagerbench.cli import commands as cli
from pillagerbench.experiments import plan as P
from pillagerbench.experiments.spec import SeriesSpec, launch_order
from tests.support.configs import run_config


@pytest.fixture
def nothing_played(monkeypatch, tmp_path):
    """Any server start, series or match fails the test; the command runs in an empty directory."""

    def played(*args, **kw):
        raise AssertionError("plan=true played something")

    import pillagerbench.experiments.plain_run
    import pillagerbench.experiments.runner
    import pillagerbench.server

    monkeypatch.setattr(pillagerbench.server.ArenaServer, "start", played)
    monkeypatch.setattr(pillagerbench.experiments.runner, "run_series", played)
    monkeypatch.setattr(pillagerbench.experiments.runner, "write_experiment", played)
    monkeypatch.setattr(pillagerbench.experiments.plain_run, "run_match", played)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def plan_output(capsys, *args: str) -> str:
    assert cli.main(["run", *args, "plan=true"]) == 0
    out, err = capsys.readouterr()
    assert not err
    return out


def test_main_benchmark_plan_prints_150_episodes_and_plays_none(nothing_played: Path, capsys):
    out = plan_output(capsys, "experiment=main_benchmark", "parallel=2")
    assert "series: 30\n" in out and "episodes: 150 of 120 s\n" in out and "parallel: 2 at once\n" in out
    assert "000_mushroom_war_tacticrafter_vs_do_nothing_r0: 5 episode(s), red tacticrafter@local (LLM " in out
    assert "LLM calls (openai_compatible local):" in out
    # the default preset is a local server: no price is known, and the plan says so
    assert "cost (openai_compatible local): unknown (" in out and "llm.price.input_per_1m=USD" in out
    assert list(nothing_played.iterdir()) == []  # no run directory


def test_plain_run_plan_with_a_priced_model(nothing_played: Path, capsys):
    out = plan_output(capsys, "red=cot", "llm=openai", "llm.model=gpt-4o", "episodes=2", "episode_length=60")
    assert "series: 1\n" in out and "episodes: 2 of 60 s\n" in out and "parallel: 1 at once\n" in out
    assert "red cot@gpt-4o (LLM openai gpt-4o) vs blue passive" in out
    # cot: one call per episode, up to `attempts` (3) when answers cannot be used
    assert "LLM calls (openai gpt-4o): 2 to 6;" in out
    assert "at $2.5 / $10 per million input / output tokens (genai-prices 0.2.3: openai gpt-4o)" in out
    assert list(nothing_played.iterdir()) == []


def test_plain_run_plan_without_llm_has_a_point_wall_time(nothing_played: Path, capsys):
    out = plan_output(capsys, "red=balanced", "blue=passive", "episodes=3", "episode_length=100")
    assert "LLM calls: none" in out
    wall = P.RUN_OVERHEAD_S + P.SERIES_OVERHEAD_S + 3 * (100 + P.EPISODE_OVERHEAD_S)
    assert f"wall time: {P.duration(wall)};" in out


def test_unpriced_model_cost_is_unknown(nothing_played: Path, capsys):
    out = plan_output(capsys, "red=cot", "llm=fake")
    assert "cost (fake fake-model): unknown (3 calls unpriced: unknown: genai-prices 0.2.3 has no price" in out
    assert "$" not in out.split("cost (fake fake-model)")[1].split("\n")[0].replace("=USD", "")


def test_tacticrafter_calls_per_episode():
    from pillagerbench.llm.settings import LLMSettings
    from pillagerbench.teams import declared_options

    options = declared_options("tacticrafter")
    calls = P.team_calls("tacticrafter", options, LLMSettings(max_tokens=512), "mushroom_war", range(2), False)
    # episode 0: causal, tactics, 2 first codes; episode 1: + opponent. High: x3 attempts, + 9 x 2 per player
    assert calls.low == 4 + 5
    assert calls.high == 3 * (4 + 5) + 2 * (2 * 9 * 2)
    assert calls.in_high > calls.in_low > 0 and calls.out_high == calls.high * 512


def test_schedule_follows_parallel_and_dependencies():
    def spec(i: int, after: str | None = None) -> SeriesSpec:
        ckpt = {"red": {"series": after, "episode": 0}} if after else {}
        return SeriesSpec(f"s{i}", i, "x", "mushroom_war", "a", "b", "a", "b", 1, 0, run_config(), checkpoint=ckpt)

    specs = [spec(0), spec(1), spec(2, after="s0")]
    durations = {"s0": 30.0, "s1": 10.0, "s2": 10.0}
    assert P.schedule(specs, durations, 1) == 50.0
    assert P.schedule(specs, durations, 2) == 40.0  # a slot is free at 10 s, but s2 waits for s0 (30 s)
    assert P.schedule(specs, durations, 3) == 40.0
    assert P.schedule(specs[:2], durations, 2) == 30.0


def test_the_plan_answers_how_many_episodes_a_question_needs(capsys):
    import math

    from pillagerbench.cli import main
    from pillagerbench.stats.sample_size import fixed_test
    from pillagerbench.suite.figures import widest_spread

    assert main(["run", "red=passive", "blue=balanced", "plan=true", "plan_width=1.5", "plan_difference=4"]) == 0
    (line,) = [x for x in capsys.readouterr().out.splitlines() if x.startswith("how many (mushroom_war;")]
    sd = widest_spread("mushroom_war")
    assert f"± 1.5 points on a mean: {math.ceil((1.959964 * sd / 1.5) ** 2)} episodes" in line
    assert f"4 points apart against one opponent: {fixed_test(sd * math.sqrt(2), 4)} episodes each" in line
    assert "with `pillagerbench compare`" in line
    assert main(["run", "plan=true", "plan_width=0"]) == 2
    assert "plan_width=0" in capsys.readouterr().err


def test_series_start_with_the_most_work_first_and_the_plan_agrees():
    def spec(i: int, scenario: str, episodes: int, length: float = 120.0) -> SeriesSpec:
        cfg = run_config(f"episode_length={length}")
        return SeriesSpec(f"s{i}", i, "x", scenario, "a", "b", "a", "b", episodes, 0, cfg)

    mw, dd, short, long = (
        spec(0, "mushroom_war", 10),
        spec(1, "dash_and_dine", 10),
        spec(2, "mushroom_war", 2),
        spec(3, "mushroom_war", 10, 240.0),
    )
    assert [s.id for s in launch_order([mw, dd, short, long, spec(4, "mushroom_war", 10)])] == [
        "s3",
        "s1",
        "s0",
        "s4",
        "s2",
    ]
    # the plan starts them so too: s3 and s1, then s0, then s2 (220 s); in the given order it would be
    # s2 and s0, then s1, then s3 alone to 300 s
    durations = {"s0": 100.0, "s1": 100.0, "s2": 20.0, "s3": 200.0}
    assert P.schedule([short, mw, dd, long], durations, 2) == 220.0
    assert P.schedule([short, mw, dd, long], durations, 1) == 420.0
