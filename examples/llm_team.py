"""An LLM team in one file: in the pre-game it asks the model for one program per player (through
the benchmark's LLM client, so every call is in the ledger, cached and within the budget), then
runs each player's program until the whistle.

    PYTHONPATH=examples pillagerbench run red=llm_team:OneShot blue=passive llm=openai llm.model=gpt-4o-mini
"""

from __future__ import annotations

import asyncio
import re

from pillagerbench.llm import LLMError
from pillagerbench.players import primitives
from pillagerbench.teams import Team, TeamContext

CODE = re.compile(r"```(?:javascript|js)\n(.*?)```", re.S)


class OneShot(Team):
    name = "one_shot"
    uses_llm = True  # the match hands this team an LLM client as ctx.llm

    async def pre_game(self, ctx: TeamContext) -> None:
        self.code: dict[str, str] = {}
        for name in ctx.side.player_names:
            prompt = (
                f"{ctx.scenario.description()}\n\nYou control {name} of {ctx.side.team_name}. "
                f"You may call these functions:\n{primitives.docs(list(ctx.scenario.primitives))}\n\n"
                "Answer with one ```javascript block: the body of an async function of `bot`."
            )
            try:
                answer = await ctx.llm.complete(prompt, role="action")
            except LLMError as exc:
                self.problems.append(f"{name}: no program: {exc}")
                continue
            found = CODE.search(answer.text)
            if found:
                self.code[name] = found.group(1)
            else:
                self.problems.append(f"{name}: the answer held no javascript block")

    async def play(self, ctx: TeamContext) -> None:
        self.iterations = [0] * len(ctx.players)

        async def keep_running(k: int, name: str) -> None:
            while ctx.time_left() > 0 and name in self.code:
                self.iterations[k] += 1
                await ctx.players[name].run(self.code[name])
                await ctx.sleep(1.0, player=name)

        await asyncio.gather(*(keep_running(k, n) for k, n in enumerate(ctx.side.player_names)))
