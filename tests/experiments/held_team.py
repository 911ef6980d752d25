"""A team for the kill tests (by import path `tests.experiments.held_team:HeldPassive`): passive that
stops at one moment of one episode while a file the test controls exists, so the test can kill
the run exactly there. `hold_at`: "pre_game" (the record of the episode before is written, nothing
of this one played), "play" (mid-episode, the clock running) or "save" (half way through writing its
state after the episode: its team.json torn). It writes `<hold>.reached` when it gets there."""

from __future__ import annotations

import asyncio
import json
import time
from pathlib import Path

from pillagerbench.rundir import last_seen_json
from pillagerbench.teams.mushroom_war import Passive


class HeldPassive(Passive):
    name = "held_passive"
    options_declared = {"hold": "", "hold_at": "play", "hold_episode": 1}

    def _holds(self, at: str, episode: int) -> bool:
        """Whether this is the moment and the hold file exists (after the test removed it: not)."""
        hold = Path(str(self.options.get("hold") or "/nonexistent"))
        return (
            at == self.options.get("hold_at") and episode == int(self.options.get("hold_episode", 1)) and hold.exists()
        )

    def _here(self, at: str, episode: int) -> Path | None:
        """The hold file if this is the moment (`<hold>.reached` written: the test may kill from now on)."""
        if not self._holds(at, episode):
            return None
        hold = Path(str(self.options.get("hold")))
        hold.with_name(hold.name + ".reached").write_text(at)
        return hold

    async def pre_game(self, ctx) -> None:
        hold = self._here("pre_game", ctx.episode)
        while hold and hold.exists():
            await asyncio.sleep(0.05)
        await super().pre_game(ctx)

    async def play(self, ctx) -> None:
        hold = self._here("play", ctx.episode)
        if hold:
            await asyncio.sleep(2)  # some of the game played first
        while hold and hold.exists():
            await asyncio.sleep(0.05)
        await super().play(ctx)

    def save_checkpoint(self, directory: Path) -> Path:
        self.saves = getattr(self, "saves", 0) + 1  # once after each episode, from episode 0
        if self._holds("save", self.saves - 1):
            directory.mkdir(parents=True, exist_ok=True)
            text = json.dumps({"team": self.name, "state": self.state()})
            (directory / "team.json").write_text(text[: len(text) // 2])
            hold = self._here("save", self.saves - 1)  # reached once the torn half is on disk
            while hold and hold.exists():  # the event loop stands still here, as in a slow disk write
                time.sleep(0.05)
        return super().save_checkpoint(directory)


SEEN = "seen.json"


class SeeingPassive(HeldPassive):
    """HeldPassive that writes what it is given of its last episode, in the form a remote team is sent
    it (`seen.json` in its side's directory of each episode), before it holds."""

    name = "seeing_passive"

    async def pre_game(self, ctx) -> None:
        ctx.out_dir.mkdir(parents=True, exist_ok=True)
        seen = last_seen_json(ctx.last_episode) if ctx.last_episode else None
        (ctx.out_dir / SEEN).write_text(json.dumps(seen, default=str))
        await super().pre_game(ctx)
