"""A scripted team in one file: both players harvest their team's giant mushrooms in Mushroom War.

PYTHONPATH=examples pillagerbench run red=scripted_team:Harvesters blue=do_nothing
"""

from __future__ import annotations

import asyncio

from pillagerbench.teams import Team, TeamContext

# JavaScript run by each player's bot; `mineBlock` is one of the scenario's primitives
HARVEST = """
const home = new Vec3({center})
while (true) {{
  await mineBlock(bot, '{block}', {per_trip}, home, {radius})
  await bot.waitForTicks(10)
}}
"""


class Harvesters(Team):
    name = "harvesters"
    scenarios = ("mushroom_war",)
    options_declared = {"per_trip": 4}  # red.per_trip=8 changes it

    async def play(self, ctx: TeamContext) -> None:
        place = ctx.scenario.placeholders(ctx.side.key)
        code = HARVEST.format(
            center=place["team_center"],
            block=place["team_block"],
            radius=place["area_radius"],
            per_trip=int(self.options.get("per_trip", 4)),
        )
        self.iterations = [0] * len(ctx.players)

        async def keep_harvesting(k: int, name: str) -> None:
            while ctx.time_left() > 0:  # the match stops the code at the whistle
                self.iterations[k] += 1
                await ctx.players[name].run(code)
                await ctx.sleep(1.0, player=name)  # a second of game time, to the whistle at most

        await asyncio.gather(*(keep_harvesting(k, n) for k, n in enumerate(ctx.side.player_names)))
