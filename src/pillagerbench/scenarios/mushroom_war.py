"""Mushroom War: two teams harvest giant mushrooms of their colour in their own area, which regrow
only while the area holds few slime blocks; slime keeps coming back; sabotage is allowed.

Where the areas, mushrooms, slime patches and spawns are is the layout's (mushroom_war_layout.py:
upstream's exact positions for `layout=paper`, or a generated variant).
"""

from __future__ import annotations

import asyncio
import random
from dataclasses import dataclass
from typing import ClassVar

from pillagerbench.config.sides import SIDES
from pillagerbench.scenarios import mushroom_war_layout as L
from pillagerbench.scenarios.arena import GROUND_Y, Arena, standing
from pillagerbench.scenarios.base import GameMaster, Scenario, Side, sides_at, vec
from pillagerbench.scenarios.layout import LayoutRules
from pillagerbench.scenarios.upstream import UPSTREAM_STEPS

Y = L.Y  # the layer players stand in
WASTE_CUTOFF = 7  # a team's mushrooms regrow only while its area holds at most this many slime blocks
AREA_RADIUS = L.RADIUS
P_REGROW = 0.1  # per missing cap block per second, while clean
P_SLIME = 0.02  # per original slime position per second, always
# per side: its mushroom blocks, the item they drop (its score), its players
CAP = {"red": "red_mushroom_block", "blue": "brown_mushroom_block"}
ITEM = {"red": "red_mushroom", "blue": "brown_mushroom"}
LAYOUTS = LayoutRules("mushroom_war", L.MushroomWarLayout, L.PAPER_LAYOUT, L.generate, L.problems)
caps, slime, stems = L.caps, L.slime, L.stems


@dataclass
class MushroomWar(Scenario[L.MushroomWarLayout]):
    key = "mushroom_war"
    title = "Mushroom War"
    primitives = ("mineBlock", "placeItem", "multiAgent", "killMob", "giveToPlayer")
    random_tick_speed: ClassVar[int] = 3
    layouts: ClassVar[LayoutRules[L.MushroomWarLayout]] = LAYOUTS

    @property
    def sides(self) -> tuple[Side, ...]:
        areas = {key: self.layout.area(key) for key in SIDES}
        return sides_at(
            {k: [standing(p) for p in a.players] for k, a in areas.items()},
            {k: standing(a.center) for k, a in areas.items()},
        )

    @property
    def arena(self) -> Arena:
        blocks = []
        for key in SIDES:
            area = self.layout.area(key)
            blocks += [(*p, "mushroom_stem") for p in stems(area)]
            blocks += [(*p, CAP[key]) for p in caps(area)]
            blocks += [(*p, "slime_block") for p in slime(area)]
        return Arena(box=L.BOX, blocks=blocks)

    def placeholders(self, key: str) -> dict:
        out = super().placeholders(key)
        other = "blue" if key == "red" else "red"
        out.update(team_block=CAP[key], opponent_block=CAP[other], area_radius=AREA_RADIUS)
        return out

    def description(self) -> str:
        r, b = self.sides
        red = self.layout.red
        return "\n".join(
            [
                f"Mushroom War: two teams of two compete. The red team is {' and '.join(r.player_names)}; "
                f"the blue team is {' and '.join(b.player_names)}.",
                f"The red team's area is centred at ({vec(r.center)}), the blue team's at ({vec(b.center)}). "
                f"The ground is flat; its top layer is at y = {GROUND_Y}, so players stand at y = {Y}.",
                f"A team's area is every block within {AREA_RADIUS} blocks of its centre. Both areas are "
                "polluted with slime blocks.",
                f"The red area holds {len(red.mushrooms)} giant mushrooms made of {len(caps(red)) // len(red.mushrooms)} "
                f"red_mushroom_block each; the blue area holds the same made of brown_mushroom_block.",
                "Mining a mushroom block gives 0 to 2 mushrooms, most often none.",
                f"Mined mushroom blocks grow back only while the team's area contains {WASTE_CUTOFF} slime blocks "
                "or fewer. Removed slime blocks quickly come back.",
                "The game lasts an unknown amount of time.",
                "The red team scores 1 point for every red_mushroom its players hold; the blue team 1 point for every "
                "brown_mushroom its players hold. Items given away or dropped no longer count. The team with the most "
                "points at the end wins.",
                "There are no chests. Sabotaging the other team is allowed.",
            ]
        )

    def game_master(self, server, rng: random.Random) -> MushroomWarMaster:
        return MushroomWarMaster(self, server, rng)


class MushroomWarMaster(GameMaster):
    period_s = 1.0

    async def start(self) -> None:
        # as upstream's: both teams start "dirty" (their areas start with more slime than the cutoff), so the
        # first announcement is a change; teams are named by index, red 0 and blue 1
        self.areas = {key: self.scenario.layout.area(key) for key in SIDES}
        self.clean: dict[str, bool] = {key: False for key in self.areas}
        self.original_slime = [p for area in self.areas.values() for p in slime(area)]
        await self.say("starting cleanup scenario...")

    async def step(self) -> None:
        for key, area in self.areas.items():
            center = list(standing(area.center))
            waste = await self.server.find_blocks(["slime_block"], center, AREA_RADIUS)
            clean = len(waste) <= WASTE_CUTOFF
            if clean != self.clean[key]:
                self.clean[key] = clean
                index = list(self.areas).index(key)
                await self.say(f"Team {index} is clean!" if clean else f"Team {index} is too dirty!")
            if clean:
                present = {tuple(b[:3]) for b in await self.server.find_blocks([CAP[key]], center, AREA_RADIUS)}
                regrow = [p for p in caps(area) if p not in present and self.rng.random() < P_REGROW]
                if regrow:
                    await self.server.set_blocks([[*p, CAP[key]] for p in regrow])
                    self.log.append({"regrow": key, "blocks": len(regrow)})
        respawn = [p for p in self.original_slime if self.rng.random() < P_SLIME]
        if respawn:
            await self.server.set_blocks([[*p, "slime_block"] for p in respawn])

    async def held(self) -> dict[str, int]:
        """Own-colour mushrooms each player holds. Every inventory is asked at once: the server answers
        them in one turn, so neither side's holdings are read before the other's (a mushroom changing
        hands is counted once)."""
        names = {n: side.key for side in self.scenario.sides for n in side.player_names}
        replies = await asyncio.gather(*(self.server.inventory(n) for n in names), return_exceptions=True)
        return {
            n: 0 if isinstance(r, BaseException) else sum(s["count"] for s in r if s["name"] == ITEM[key])
            for (n, key), r in zip(names.items(), replies)
        }  # offline: nothing

    async def scores(self) -> dict[str, float]:
        held = await self.held()
        return {side.key: float(sum(held[n] for n in side.player_names)) for side in self.scenario.sides}

    async def upstream_scores(self, runs: dict[str, int]) -> dict[str, float]:
        """Upstream's quirk: each code run of a player started a counter that adds what it holds (from
        0) and never stops, so a player counts what it holds once per run started (once at least:
        upstream's do_nothing ran one step; at most UPSTREAM_STEPS times)."""
        held = await self.held()
        return {
            side.key: float(sum(held[n] * upstream_multiplier(runs, n) for n in side.player_names))
            for side in self.scenario.sides
        }


# upstream capped every team at 10 steps per player and episode (scripted, CoT and Random runners;
# TactiCrafter's iteration cap in the paper's configs). Our teams may start more runs (Random runs
# one action per run), so the multiplier is capped there.


def upstream_multiplier(runs: dict[str, int], player: str) -> int:
    """How many of upstream's score counters a player had running: one per run started, 1 to 10."""
    return min(UPSTREAM_STEPS, max(1, runs.get(player, 0)))
