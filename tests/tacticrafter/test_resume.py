"""A TactiCrafter series killed mid-episode (SIGKILL to its process group) and resumed with
resume=RUN_DIR, on the fake provider: the resumed pre-game asks the model exactly what the
uninterrupted series asked before the kill (causal update, opponent model, tactics update: the same
graph, opponent model, tactics and world chat of the last finished episode)."""

from __future__ import annotations

import json
import os
import shutil
import signal
import time
from pathlib import Path

import pytest

from pillagerbench.llm.fake_server import FakeLLMServer
from tests.support.cli import start_cli

from .conftest import good_rules

# the pre-game's update requests, told apart from the first episode's by their role and text
UPDATES = {
    "causal": "The causal graph so far",
    "opponent": "",
    "tactics": "A round has been played",
}


def updates(requests: list) -> dict[str, list]:
    return {
        role: [r.messages for r in requests if r.role == role and text in r.prompt] for role, text in UPDATES.items()
    }


def args(fake_url: str) -> list[str]:
    return [
        "experiment=main_benchmark",
        "experiment.scenarios=[mushroom_war]",
        "experiment.opponents=[passive]",
        "experiment.episodes=2",
        "experiment.repetitions=1",
        "experiment.team_options.iterations=2",
        "episode_length=12",
        "clock=lockstep",  # what the resumed team asks, not game time: the game's seconds, fast
        "llm=fake",
        f"llm.base_url={fake_url}",
        "llm.timeout=10",
        "parallel=1",
        "display=plain",
    ]


def live_status(series: Path) -> dict:
    try:
        return json.loads((series / "live.json").read_text())
    except (OSError, ValueError):
        return {}


def kill_in_episode_1(proc, run: Path) -> Path:
    deadline = time.monotonic() + 150
    try:
        while time.monotonic() < deadline:
            found = list((run / "series").glob("*")) if (run / "series").exists() else []
            if found and live_status(found[0]).get("episode") == 1 and live_status(found[0]).get("t", 0) >= 2:
                break  # episode 1's pre-game is over, its game under way
            assert proc.poll() is None, proc.stdout.read()
            time.sleep(0.2)
        else:
            pytest.fail("the series never reached episode 1")
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    return found[0]


@pytest.fixture(scope="module")
def killed(tmp_path_factory):
    """A series killed in episode 1, the requests the model got before the kill, and a copy of the run."""
    with FakeLLMServer() as fake:
        fake.add(*good_rules())
        run = tmp_path_factory.mktemp("resume") / "run"
        series = kill_in_episode_1(start_cli("run", *args(fake.url), f"run_dir={run}"), run)
        copy = run.parent / "copy"
        shutil.copytree(run, copy)
        yield fake, run, series, copy


def test_a_killed_tacticrafter_series_resumes_with_what_it_had_learned(killed):
    fake, run, series, _ = killed
    before = updates(fake.requests)
    assert {role: len(asked) for role, asked in before.items()} == {"causal": 1, "opponent": 1, "tactics": 1}
    seen = len(fake.requests)

    resumed = start_cli("run", *args(fake.url), f"resume={run}")
    out, _ = resumed.communicate(timeout=180)
    assert resumed.returncode == 0, out
    assert "resume after 1 finished episode(s)" in out
    after = updates(fake.requests[seen:])
    for role, asked in before.items():
        assert after[role], f"the resumed pre-game did not ask the {role} model (the team started from scratch)"
        assert after[role][0] == asked[0], f"the resumed {role} prompt differs from the uninterrupted one"
    assert "<Byte> " in after["opponent"][0][-1]["content"]  # what the opponent said last episode

    ep1 = series / "episode_001" / "red"
    record = json.loads((ep1 / "tacticrafter.json").read_text())
    assert record["memory_from_episodes"] == 1
    assert json.loads((ep1 / "tactics.json").read_text())["source"] == "updated"


def test_a_series_whose_team_state_is_gone_is_not_resumed_from_scratch(killed):
    fake, _, series, copy = killed
    series = copy / "series" / series.name
    state = series / "state" / "episode_000" / "red" / "team.json"
    state.unlink()

    resumed = start_cli("run", *args(fake.url), f"resume={copy}")
    out, _ = resumed.communicate(timeout=120)
    assert f"cannot resume: red's state after episode 0 is missing ({state})" in out
    assert [json.loads(x)["episode"] for x in (series / "episodes.jsonl").read_text().splitlines()] == [0]
