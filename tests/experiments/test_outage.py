"""Waiting out an outage (experiments/outage.py, `outage_wait_s`): after an episode in which the provider
could not be reached, a series probes it with growing waits and plays on once it answers, the spoiled
episode spending no retry; past the wait the series stops with one line and `resume=RUN_DIR` plays the
rest; a kill during the wait resumes into the same wait, nothing given up twice. Real series of cot
against do_nothing on the lockstep clock (what is tested is which episodes count, not real time), the
provider our fake one: stopped and started again on its port (connection refused), or answering 503.
`retries=0` throughout: an episode spoiled by an ordinary fault would be given up at once, so every
replay below is the waiting's."""

from __future__ import annotations

import asyncio
import json
import time
from pathlib import Path

import pytest

from pillagerbench.cli import commands as cli
from pillagerbench.config.compose import load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.experiments import outage
from pillagerbench.experiments.outage import FILE, OUTAGE, Status, read_status, unreachable
from pillagerbench.experiments.series import run_series
from pillagerbench.llm import fake_server
from pillagerbench.llm.fake_server import FakeLLMServer, Rule
from pillagerbench.rundir import EpisodeRecord, RunDir, SeriesSpec, faults, progress
from tests.support.cli import kill_run, refused_in_process, start_cli
from tests.support.waiting_cot import ANSWER, overrides

ROOT = Path(__file__).resolve().parents[2]


def game(fake: FakeLLMServer, episodes: int, *extra: str) -> list[str]:
    return overrides(fake, episodes, "retries=0", *extra)


def down_after_one(fake: FakeLLMServer) -> None:
    """The preflight and episode 0's call answered, every other request 503 (a probe's too)."""
    fake.reset()
    fake.add(Rule(role="preflight"), Rule(role="probe", status=503), Rule(reply=ANSWER, times=1), Rule(status=503))


def back(fake: FakeLLMServer) -> None:
    fake.reset()
    fake.add(Rule(reply=ANSWER))


def waited_out(rec: EpisodeRecord) -> bool:
    return any(f.whose == "harness" and f.kind == OUTAGE for f in faults(rec))


@pytest.fixture
def quick(monkeypatch):
    monkeypatch.setattr(outage, "FIRST_WAIT_S", 0.5)  # probes 0.5 s, 1 s, 2 s ... apart


async def test_an_outage_in_the_middle_of_a_series_is_waited_out_and_spends_no_retry(tmp_path, quick, monkeypatch):
    run = tmp_path / "run"
    # a connection per request: once stopped, the provider refuses every one (a kept-alive connection
    # would go on being answered by the stopped server's handler thread)
    monkeypatch.setattr(fake_server._Handler, "protocol_version", "HTTP/1.0")
    with FakeLLMServer() as fake:
        fake.add(Rule(reply=ANSWER))
        cfg = RunConfig.of(load_config(game(fake, 2)))
        spec = SeriesSpec("run", 0, "run", "mushroom_war", "cot", "do_nothing", "cot", "do_nothing", 2, 0, cfg)
        seen: list[Status | None] = []

        def after(rec: EpisodeRecord) -> None:
            if rec.episode == 0:
                fake.stop()  # connection refused from now on, until the series waits

        async def provider_back_once_waiting() -> Status | None:
            while (status := read_status(run)) is None:
                await asyncio.sleep(0.05)
            fake.start()
            return status

        returns = asyncio.ensure_future(provider_back_once_waiting())
        summary = await run_series(spec, run, on_episode=after, on_outage=seen.append, say=lambda _: None)
        written = returns.result() if returns.done() else returns.cancel() and None
    assert written is not None, "the series never waited"
    records = RunDir(run).finished()
    assert sorted(records) == [0, 1, 2] and "outage" not in summary
    assert waited_out(records[1]) and not any(waited_out(records[i]) for i in (0, 2))
    assert "LLMConnectionError" in records[1].problems["red"][0]  # the episode as it happened
    assert RunDir(run).files(1).record() == records[1]  # episode.json says what its line says
    done = progress(records, 2, 0)  # with retries=0 an ordinary spoiled try would be given up
    assert (done.complete, done.used, done.spoiled, done.given_up) == (True, 2, 1, 0)
    assert written.since <= written.next_probe <= written.until and "LLMConnectionError" in written.what
    assert seen[-1] is None and "unreachable since" in seen[0].line() and "next probe in" in seen[0].line()
    assert not (run / FILE).exists()


def test_a_kill_during_the_wait_resumes_into_the_wait_and_past_it_the_run_stops_with_one_line(
    tmp_path, monkeypatch, capsys
):
    """Killed while waiting; resumed with the provider still down (its preflight too): the resume waits again,
    and past the wait stops with one line and exit 1; resumed once the provider is back: it plays the
    episode, and nothing was given up (nor a retry spent)."""
    run = tmp_path / "run"
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    with FakeLLMServer() as fake:
        down_after_one(fake)
        proc = start_cli("run", *game(fake, 2, "outage_wait_s=3", "display=plain", f"run_dir={run}"), cwd=ROOT)
        deadline = time.monotonic() + 120
        try:
            while not (run / FILE).exists():
                assert proc.poll() is None, proc.stdout.read() if proc.stdout else ""
                assert time.monotonic() < deadline, "the run never waited"
                time.sleep(0.02)
            kill_run(proc)
        finally:
            if proc.poll() is None:
                proc.kill()
        killed = RunDir(run).finished()
        assert sorted(killed) == [0, 1] and waited_out(killed[1])

        fake.reset()
        fake.add(Rule(status=503))  # everything down: the resume's preflight too
        assert cli.main(["run", f"resume={run}"]) == 1
        out = capsys.readouterr().out
        assert "no answer; waiting for it, up to outage_wait_s=3 s" in out, out
        said = [line for line in out.splitlines() if line.startswith("gave up waiting")]
        assert len(said) == 1 and f"1 planned episode(s) not played: resume={run} plays them" in said[0], out
        assert "did not answer since" in said[0] and "ProviderError" in said[0]
        assert RunDir(run).finished() == killed and not (run / FILE).exists()

        back(fake)
        assert cli.main(["run", f"resume={run}"]) == 0
    records = RunDir(run).finished()
    assert sorted(records) == [0, 1, 2] and records[1] == killed[1] and not waited_out(records[2])
    done = progress(records, 2, 0)  # with retries=0 an ordinary spoiled try would be given up
    assert (done.complete, done.used, done.spoiled, done.given_up) == (True, 2, 1, 0)


@pytest.mark.parametrize(
    "value, expected",
    [
        ("-1", "pillagerbench run: outage_wait_s=-1: input should be greater than or equal to 0"),
        ("abc", "pillagerbench run: outage_wait_s='abc': input should be a valid number"),
        ("inf", "pillagerbench run: outage_wait_s=inf: input should be a finite number"),
    ],
)
def test_a_bad_outage_wait_is_one_line_and_exit_2(tmp_path, monkeypatch, capsys, value, expected):
    (line,) = refused_in_process(monkeypatch, capsys, tmp_path, "run", f"outage_wait_s={value}")
    assert line.startswith(expected), line


def test_what_is_waited_for_the_provider_on_its_errors_and_a_remote_teams_server():
    cfg = RunConfig.of(
        load_config(
            ["red=cot", "blue=remote", "blue.url=http://127.0.0.1:9", "llm=fake", "llm.base_url=http://127.0.0.1:9/v1"]
        )
    )

    def rec(**problems: list[str]) -> EpisodeRecord:
        return EpisodeRecord("mushroom_war", "cot", "remote", 0, problems=problems)

    refused = "llm failed on all 1 call(s); last: LLMConnectionError: Connection error."
    assert unreachable(rec(red=[refused]), cfg) == {"red": "llm"}
    assert unreachable(rec(red=["llm failed on all 3 call(s); last: ProviderError: 503"]), cfg) == {"red": "llm"}
    # an answer, not an outage: a refused key, a replay's cache miss, the team's own budget
    for last in ("AuthenticationFailed: 401", "CacheMiss: replay", "BudgetExceeded: max_calls"):
        assert unreachable(rec(red=[f"llm failed on all 1 call(s); last: {last}"]), cfg) == {}
    failed = EpisodeRecord("mushroom_war", "cot", "remote", 0, status="failed", error="LLMTimeout: 20 s")
    assert unreachable(failed, cfg) == {"red": "llm"}  # the whole episode: every side with an LLM
    gone = "remote /postgame: cannot reach http://127.0.0.1:9/postgame: [Errno 111] Connection refused"
    assert unreachable(rec(blue=[gone]), cfg) == {"blue": "team"}  # at the episode's end
    assert unreachable(rec(blue=["remote /events: HTTP 500 from http://127.0.0.1:9/events"]), cfg) == {}  # back since
    assert unreachable(rec(blue=["remote /postgame: no answer from http://127.0.0.1:9 within 5 s"]), cfg) == {}
    off = cfg.updated({"llm": {"preflight": False}})  # no probe where the preflight is off
    assert unreachable(rec(red=[refused]), off) == {}
    down = asyncio.run(outage.probe(cfg, {"red": "llm", "blue": "team"}))
    assert set(down) == {"red", "blue"} and "LLMConnectionError" in down["red"] and "does not answer" in down["blue"]


def test_the_experiment_display_shows_one_line_for_the_series_waiting(tmp_path):
    from pillagerbench.experiments.progress import waiting_line

    now = time.time()
    a = Status("fake model m at http://x/v1: LLMConnectionError: refused", now - 65, now + 10, now + 835, 4)
    b = Status("the same", now - 5, now + 3, now + 895, 1)
    spec_a, spec_b = type("S", (), {"id": "s0"})(), type("S", (), {"id": "s1"})()
    line = waiting_line([(spec_b, b), (spec_a, a)])
    assert line.startswith("s0 (and 1 more series): unreachable since ") and "(1 min 5 s)" in line
    assert "next probe in 10 s" in line and line.endswith("LLMConnectionError: refused")
    outage.write_status(tmp_path, a)
    assert read_status(tmp_path) == a and json.loads((tmp_path / FILE).read_text())["probes"] == 4
    outage.write_status(tmp_path, None)
    assert read_status(tmp_path) is None
