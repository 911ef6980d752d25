"""Built-in opponents: one JavaScript script per player, on the control primitives, with the
scenario's data substituted for `$placeholders`. Each player runs its script until the whistle; a
script that throws or ends is started again (at most `max_runs` = 10 runs in all, as upstream's 10 steps);
with none left the player rests to the whistle (on the lockstep clock its bot no longer holds the world).
"""

from __future__ import annotations

import asyncio
import string
from pathlib import Path
from typing import ClassVar

from pillagerbench.players import events as ev
from pillagerbench.scenarios.upstream import UPSTREAM_STEPS
from pillagerbench.teams.base import Team, TeamContext

SCRIPTS = Path(__file__).parent / "scripts"


def render(template: str, values: dict) -> str:
    return string.Template(template).substitute(values)


class ScriptedTeam(Team):
    """Subclasses set `scenarios = (key,)` and `scripts`: one file name per player (under scripts/<scenario>/),
    or `parts`: per player, a list of behaviour calls run in a loop after the scenario's behaviours.js."""

    scripts: ClassVar[tuple[str, ...]] = ()
    parts: ClassVar[tuple[tuple[str, ...], ...]] = ()
    max_runs: ClassVar[int] = UPSTREAM_STEPS  # upstream's runner: at most 10 steps per player

    def code_for(self, ctx: TeamContext, index: int) -> str:
        folder = SCRIPTS / ctx.scenario.key
        values = ctx.scenario.placeholders(ctx.side.key)
        if self.parts:
            library = (folder / "behaviours.js").read_text()
            calls = "\n".join(f"  await {call}" for call in self.parts[index])
            return render(library, values) + f"\nwhile (true) {{\n  await bot.waitForTicks(20)\n{calls}\n}}\n"
        return render((folder / self.scripts[index]).read_text(), values)

    async def play(self, ctx: TeamContext) -> None:
        await asyncio.gather(*(self._keep_running(ctx, i, player) for i, player in enumerate(ctx.players.values())))

    async def _keep_running(self, ctx: TeamContext, index: int, player) -> None:
        code = self.code_for(ctx, index)
        runs = 0
        while ctx.time_left() > 0 and runs < self.max_runs:
            runs += 1
            events = await player.run(code)  # the match stops it at the whistle
            if ctx.time_left() > 0 and ev.errors(events):
                await ctx.sleep(0.5, player.name)
        self.iterations.append(runs)
        await ctx.sleep(ctx.time_left(), player.name)  # no runs left: it rests (lockstep: the world goes on)
