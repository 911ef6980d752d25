"""benchmarks/day_of_play.py's summary of a league (--league): processes that come and go with the
series are summarized per kind, and the growth is read against the episodes of every round."""

import importlib.util
import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def load():
    spec = importlib.util.spec_from_file_location("day_of_play", ROOT / "benchmarks" / "day_of_play.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_a_league_is_summarized_per_kind_over_every_round(tmp_path):
    dop = load()
    run = tmp_path / "run"
    (run / "league.yaml").parent.mkdir()
    (run / "league.yaml").write_text("scenarios: [mushroom_war]\n")
    for rnd, series in (("round_000", "000_a"), ("round_000", "001_b"), ("round_001", "000_c")):
        d = run / "matches" / rnd / "series" / series
        d.mkdir(parents=True)
        (d / "episodes.jsonl").write_text(
            "".join(json.dumps({"duration_s": 3.0, "server_tps": 100.0, "status": "ok"}) + "\n" for _ in range(10))
        )
    assert dop.episodes_done(run) == 30 and len(dop.records_of(run)) == 30
    samples = []
    for i in range(31):
        procs = {"python": {"rss_mb": 100.0 + (i > 20), "fds": 23.0, "n": 1}}
        if i % 10:  # between two series no node process is alive
            procs |= {"server": {"rss_mb": 150.0, "fds": 28.0, "n": 1}, "bot": {"rss_mb": 100.0, "fds": 23.0, "n": 4}}
        samples.append({"t": i * 5.0, "episodes": i, "load": 1.0, "procs": procs})
    (tmp_path / dop.SAMPLES).write_text("".join(json.dumps(s) + "\n" for s in samples))
    (tmp_path / "command.txt").write_text("python -m pillagerbench.cli league run play  # for 3600 s of wall time\n")
    summary = dop.summarize(tmp_path)
    assert summary["episodes"] == 30 and summary["warm_up_episode"] == 6
    assert summary["processes"]["python"]["rss_mb"]["growth_pct"] == 1.0
    assert summary["processes"]["bot"]["most_alive"] == 4 and summary["processes"]["bot"]["after_last_sample"] == 0
    assert summary["processes"]["server"]["rss_mb"]["growth_pct"] == 0.0 and summary["flat"]


def test_a_restarted_bot_is_judged_by_its_own_growth_since_the_restart(tmp_path):
    dop = load()
    (tmp_path / "run").mkdir()
    record = json.dumps({"duration_s": 3.0, "server_tps": 100.0, "status": "ok"}) + "\n"
    (tmp_path / "run" / "episodes.jsonl").write_text(record * 100)
    (tmp_path / "command.txt").write_text("python -m pillagerbench.cli run clock=lockstep\n")
    samples = []
    for i in range(101):  # restarted at episode 50: it starts afresh at 100 MB, then stays
        bot = {"rss_mb": 150.0 if i < 50 else 100.0, "fds": 23, "pids": [1 if i < 50 else 2]}
        samples.append({"t": i * 5.0, "episodes": i, "load": 1.0, "procs": {"bot:Ryn": bot}})
    (tmp_path / dop.SAMPLES).write_text("".join(json.dumps(s) + "\n" for s in samples))
    ryn = dop.summarize(tmp_path)["processes"]["bot:Ryn"]
    assert ryn["restarts"] == 1 and ryn["rss_mb"]["growth_pct"] == -33.3
    assert ryn["since_restart"]["episode"] == 50 and ryn["since_restart"]["growth_pct"] == 0.0
