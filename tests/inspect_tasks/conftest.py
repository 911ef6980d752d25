"""Fixtures for the Inspect tasks' tests: skipped when the inspect extra is not installed; Inspect's
mock model (no network: its token count offline, offline_tokens.py) answering with programs."""

from __future__ import annotations

import importlib.util
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.inspect_tasks.offline_tokens import patch_tiktoken

if importlib.util.find_spec("inspect_ai") is None:  # the inspect extra is not installed: nothing to test
    collect_ignore_glob = ["test_*.py"]

OFFLINE = Path(__file__).resolve().parent / "offline"
ROOT = Path(__file__).resolve().parents[2]

# a program for each Mushroom War player: harvest red mushrooms in red's area
PROGRAM = """async function main(bot) {
  const home = new Vec3(-9, 4, -10)
  while (true) {
    bot.chat("Harvesting red mushrooms")
    if (blockExists(bot, "red_mushroom_block", home, 7)) await mineBlock(bot, "red_mushroom_block", 2, home, 7)
    await bot.waitForTicks(20)
  }
}"""
ANSWER = "Plan: both players harvest.\n" + "\n".join(
    f"Code for bot {i}:\n```javascript\n{PROGRAM}\n```" for i in range(2)
)


@pytest.fixture(autouse=True, scope="session")
def offline_tokens() -> None:
    patch_tiktoken()


def answers(text: str = ANSWER, tokens: int = 1000) -> Iterator[Any]:
    """Inspect's mock model answering `text` every time, each call using `tokens` input tokens."""
    from inspect_ai.model import ModelOutput, ModelUsage

    while True:
        out = ModelOutput.from_content(model="mockllm", content=text)
        out.usage = ModelUsage(input_tokens=tokens, output_tokens=200, total_tokens=tokens + 200)
        yield out


def mock_model(text: str = ANSWER, tokens: int = 1000) -> Any:
    from inspect_ai.model import get_model

    return get_model("mockllm/model", custom_outputs=answers(text, tokens))


def run_eval(tmp_path: Path, task_args: dict[str, Any], **eval_args: Any) -> Any:
    """`inspect_ai.eval()` of pillagerbench/mushroom_war in-process, 20-second episodes; its one log."""
    from inspect_ai import eval as inspect_eval

    args = {"episode_length": 20, "opponents": "passive", "run_dir": str(tmp_path / "runs"), **task_args}
    eval_args.setdefault("model", mock_model())
    logs = inspect_eval(
        "pillagerbench/mushroom_war",
        task_args=args,
        log_dir=str(tmp_path / "logs"),
        display="none",
        limit=1,
        **eval_args,
    )
    assert len(logs) == 1
    return logs[0]
