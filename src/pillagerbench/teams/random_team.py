"""The Random baseline (paper, Experiments): every player keeps doing random actions until the
whistle: a random primitive or raw mineflayer call from those the scenario allows, with arguments
drawn from what the player sees (nearby blocks, mobs, its inventory, chests, its teammates and its
team's server), pausing about a second every few actions.

Each action is generated in Python from the player's latest observation by `RandomActions`, a
generator seeded with the episode's seed, the side and the player's index, and run on its own
(`player.run`), so its final observation feeds the next choice. The same seed and the same
observations give the same actions. Simple checks keep every action executable: an action is
only a candidate when what it needs is there (an item to place or give, a mob to attack, a hoe to
till, seeds to plant, a chest to open ...). The actions of an episode go to `<out_dir>/random.json`.
"""

from __future__ import annotations

import asyncio
import json
import random
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import ClassVar

from pydantic import Field

from pillagerbench.host.node import JS_DIR
from pillagerbench.players import events as ev
from pillagerbench.players import primitives as prim
from pillagerbench.players.observation import Observation
from pillagerbench.teams.base import Team, TeamContext
from pillagerbench.teams.options import TeamOptions

UNMINABLE = {"air", "cave_air", "void_air", "bedrock", "barrier", "water", "lava", "fire"}
SEEDS = {
    "plantWheatSeeds": "wheat_seeds",
    "plantPotatoes": "potato",
    "plantCarrots": "carrot",
    "plantBeetrootSeeds": "beetroot_seeds",
    "plantMelonSeeds": "melon_seeds",
    "plantPumpkinSeeds": "pumpkin_seeds",
    "plantSweetBerryBushes": "sweet_berries",
    "plantCocoaBeans": "cocoa_beans",
    "plantSugarCane": "sugar_cane",
}
HARVESTS = (
    "harvestWheat",
    "harvestPotatoes",
    "harvestCarrots",
    "harvestBeetroot",
    "harvestBerries",
    "harvestCocoa",
    "harvestMelons",
    "harvestPumpkins",
)
# Things worth trying to craft (craftItem explains what is missing when the recipe cannot be done).
CRAFTABLE = (
    "bread",
    "cookie",
    "cake",
    "pumpkin_pie",
    "beetroot_soup",
    "golden_carrot",
    "sugar",
    "mushroom_stew",
    "bowl",
    "stick",
    "crafting_table",
    "oak_planks",
    "chest",
    "furnace",
    "wooden_hoe",
)
FUEL = "coal"
# Furnace inputs: what the server can smelt (its SMELTING table, js/server/smelting.json); anything else is refused
SMELTABLE = frozenset(json.loads((JS_DIR / "server" / "smelting.json").read_text(encoding="utf-8")))


def js(value: object) -> str:
    """A Python value as a JavaScript literal."""
    return json.dumps(value)


def compact(obs: Observation) -> dict:
    """The parts of an observation the random choices read (stored with each action in random.json)."""
    status = obs.get("status") or {}
    return {
        "voxels": sorted(obs.get("voxels") or []),
        "inventory": dict(obs.get("inventory") or {}),
        "nearbyChests": dict(obs.get("nearbyChests") or {}),
        "status": {"position": status.get("position"), "entities": dict(status.get("entities") or {})},
    }


@dataclass(frozen=True)
class Action:
    kind: str  # the function or bot method it calls
    code: str  # the JavaScript run for it

    def to_dict(self) -> dict:
        return {"kind": self.kind, "code": self.code}


@dataclass(frozen=True)
class Seen:
    """The parts of an observation the choices depend on, in a fixed order."""

    blocks: tuple[str, ...]
    mobs: tuple[str, ...]
    items: tuple[tuple[str, int], ...]
    chests: tuple[tuple[tuple[int, int, int], tuple[tuple[str, int], ...]], ...]
    pos: tuple[int, int, int]

    @classmethod
    def of(cls, obs: Observation) -> Seen:
        status = obs.get("status") or {}
        p = status.get("position") or {"x": 0, "y": 4, "z": 0}
        chests = []
        for key, content in sorted((obs.get("nearbyChests") or {}).items()):
            try:
                xyz = tuple(int(round(float(v))) for v in key.strip("()").split(","))
            except ValueError:
                continue
            if content == "Invalid" or len(xyz) != 3:
                continue
            inside = tuple(sorted((k, int(v)) for k, v in content.items() if v)) if isinstance(content, dict) else ()
            chests.append((xyz, inside))
        return cls(
            blocks=tuple(sorted(set(obs.get("voxels") or []) - UNMINABLE)),
            mobs=tuple(sorted(status.get("entities") or {})),
            items=tuple(sorted((k, int(v)) for k, v in (obs.get("inventory") or {}).items() if v)),
            chests=tuple(chests),
            pos=(int(p["x"] // 1), int(p["y"] // 1), int(p["z"] // 1)),
        )

    def has(self, item: str) -> bool:
        return any(name == item for name, _ in self.items)

    def has_like(self, part: str) -> bool:
        return any(part in name for name, _ in self.items)


Builder = Callable[["RandomActions", Seen], str]


def _code(code: str) -> Builder:
    """A builder of a fixed action."""
    return lambda g, s: code


class RandomActions:
    """Seeded random actions for one player. `next(obs)` -> Action."""

    def __init__(self, seed: object, primitives: Sequence[str], players: Sequence[str] = ()):
        self.rng = random.Random(f"random-team/{seed}")
        self.available = set(prim.functions(list(primitives)))
        self.players = tuple(players)  # who the player can give to: teammates and its team's server

    # --- helpers drawing arguments ----------------------------------------------------------

    def offset(self, s: Seen, reach: int, dy: tuple[int, int] = (0, 0)) -> tuple[int, int, int]:
        r = self.rng
        return (s.pos[0] + r.randint(-reach, reach), s.pos[1] + r.randint(*dy), s.pos[2] + r.randint(-reach, reach))

    def vec(self, p: tuple[int, int, int]) -> str:
        return f"new Vec3({p[0]}, {p[1]}, {p[2]})"

    def item(self, s: Seen) -> tuple[str, int]:
        return self.rng.choice(s.items)

    def at_random_block(self, name: str, body: str) -> str:
        """Code running `body` with `block` = one of the nearby blocks called `name` (index drawn here)."""
        k = self.rng.randrange(1000)
        return (
            f"const ids = mcData.blocksByName[{js(name)}]\n"
            f"const found = ids ? bot.findBlocks({{ matching: ids.id, maxDistance: 32, count: 16 }}) : []\n"
            f"if (found.length) {{\n  const block = bot.blockAt(found[{k} % found.length])\n"
            f"  if (block) {{\n    {body}\n  }}\n}}"
        )

    # --- the actions: the ACTIONS table's rows whose check passes -----------------------------

    def candidates(self, s: Seen) -> list[tuple[str, Builder]]:
        """The actions possible now, in ACTIONS' order: their check passes and the scenario allows them."""
        return [
            (kind, build)
            for kind, ok, build in ACTIONS
            if ok(self, s) and (kind in self.available or kind.startswith("bot."))
        ]

    def next(self, obs: Observation) -> Action:
        seen = Seen.of(obs)
        kind, build = self.rng.choice(self.candidates(seen))
        return Action(kind, build(self, seen))


Check = Callable[["RandomActions", Seen], bool]


def _always(g: RandomActions, s: Seen) -> bool:
    return True


def _holding(item: str) -> Check:
    """A check: the player has `item`."""
    return lambda g, s: s.has(item)


# --- one builder per kind of action: the JavaScript, with arguments drawn from g.rng --------------


def _mine_block(g: RandomActions, s: Seen) -> str:
    r = g.rng
    return (
        f"await mineBlock(bot, {js(r.choice(s.blocks))}, {r.randint(1, 5)}, "
        f"{g.vec(g.offset(s, 8, (-1, 1))) if r.random() < 0.5 else 'null'}, {r.randint(8, 32)})"
    )


def _place_item(g: RandomActions, s: Seen) -> str:
    name = g.item(s)[0]
    return f"if (mcData.blocksByName[{js(name)}]) await placeItem(bot, {js(name)}, {g.vec(g.offset(s, 3, (0, 1)))})"


def _kill_mob(g: RandomActions, s: Seen) -> str:
    return f"await killMob(bot, {js(g.rng.choice(s.mobs))}, {g.rng.randint(5, 20)})"


def _give_to_player(g: RandomActions, s: Seen) -> str:
    r = g.rng
    return f"await giveToPlayer(bot, {js(g.item(s)[0])}, {js(r.choice(g.players))}, {r.choice([-1, *range(1, 10)])})"


def _go_to_player(g: RandomActions, s: Seen) -> str:
    return f"await goToPlayer(bot, {js(g.rng.choice(g.players))}, {g.rng.randint(1, 4)})"


def _send_signal(g: RandomActions, s: Seen) -> str:
    return f"await sendSignal(bot, {js(g.rng.choice(g.players))})"


def _wait_signal(g: RandomActions, s: Seen) -> str:
    return f"await waitSignal(bot, null, {g.rng.randint(1, 5) * 1000})"


def _craft_item(g: RandomActions, s: Seen) -> str:
    return f"await craftItem(bot, {js(g.rng.choice(CRAFTABLE))}, {g.rng.randint(1, 3)})"


def _smeltable(s: Seen) -> list[str]:
    return [name for name, _ in s.items if name in SMELTABLE]


def _smelt_item(g: RandomActions, s: Seen) -> str:
    return f"await smeltItem(bot, {js(g.rng.choice(_smeltable(s)))}, {js(FUEL)}, {g.rng.randint(1, 2)})"


def _get_item_from_chest(g: RandomActions, s: Seen) -> str:
    r = g.rng
    chest = r.choice(s.chests)
    if chest[1]:
        return f"await getItemFromChest(bot, {g.vec(chest[0])}, {{ {js(r.choice(chest[1])[0])}: {r.randint(1, 9)} }})"
    return f"await checkItemInsideChest(bot, {g.vec(chest[0])})"


def _deposit_item_into_chest(g: RandomActions, s: Seen) -> str:
    r = g.rng
    return (
        f"await depositItemIntoChest(bot, {g.vec(r.choice(s.chests)[0])}, {{ {js(g.item(s)[0])}: {r.randint(1, 9)} }})"
    )


def _harvest_sugar_cane(g: RandomActions, s: Seen) -> str:
    return f"await harvestSugarCane(bot, {s.pos[1] - 1})"


def _destroy_crop(g: RandomActions, s: Seen) -> str:
    return f"await destroyCrop(bot, {js(g.rng.choice(s.blocks))})"


# raw mineflayer actions


def _goto(g: RandomActions, s: Seen) -> str:
    p = g.offset(s, 12)
    return f"await bot.pathfinder.goto(new GoalNear({p[0]}, {p[1]}, {p[2]}, {g.rng.randint(1, 3)}))"


def _look_at(g: RandomActions, s: Seen) -> str:
    return f"await bot.lookAt({g.vec(g.offset(s, 5, (-1, 2)))})"


def _equip(g: RandomActions, s: Seen) -> str:
    return (
        f"{{ const it = bot.inventory.items().find(i => i.name === {js(g.item(s)[0])}); "
        f'if (it) await bot.equip(it, "hand") }}'
    )


def _activate_block(g: RandomActions, s: Seen) -> str:
    return g.at_random_block(
        g.rng.choice(s.blocks),
        "await bot.lookAt(block.position.offset(0.5, 0.5, 0.5)); await bot.activateBlock(block)",
    )


def _use_on(g: RandomActions, s: Seen) -> str:
    return f"{{ const e = bot.nearestEntity(e => e.name === {js(g.rng.choice(s.mobs))}); if (e) bot.useOn(e) }}"


# Every kind of action: (the function or bot method it calls, when it can work, its builder), in the
# order the generator draws from (changing the order changes a seed's actions).
ACTIONS: tuple[tuple[str, Check, Builder], ...] = (
    ("mineBlock", lambda g, s: bool(s.blocks), _mine_block),
    ("placeItem", lambda g, s: bool(s.items), _place_item),
    ("killMob", lambda g, s: bool(s.mobs), _kill_mob),
    ("giveToPlayer", lambda g, s: bool(s.items and g.players), _give_to_player),
    ("goToPlayer", lambda g, s: bool(g.players), _go_to_player),
    ("sendSignal", lambda g, s: bool(g.players), _send_signal),
    ("waitSignal", _always, _wait_signal),
    ("craftItem", _always, _craft_item),
    ("smeltItem", lambda g, s: bool(_smeltable(s)), _smelt_item),
    ("getItemFromChest", lambda g, s: bool(s.chests), _get_item_from_chest),
    ("depositItemIntoChest", lambda g, s: bool(s.chests and s.items), _deposit_item_into_chest),
    ("tillLand", lambda g, s: s.has_like("_hoe"), _code('await tillLand(bot, ["dirt", "grass_block"])')),
    *((fn, _holding(seed_item), _code(f"await {fn}(bot)")) for fn, seed_item in SEEDS.items()),
    *((fn, _always, _code(f"await {fn}(bot, null)")) for fn in HARVESTS),
    ("harvestSugarCane", _always, _harvest_sugar_cane),
    ("milkCow", lambda g, s: s.has("bucket") and "cow" in s.mobs, _code("await milkCow(bot)")),
    ("equipBucket", lambda g, s: s.has("bucket"), _code("await equipBucket(bot)")),
    ("destroyCrop", lambda g, s: bool(s.blocks), _destroy_crop),
    ("bot.pathfinder.goto", _always, _goto),
    ("bot.lookAt", _always, _look_at),
    ("bot.equip", lambda g, s: bool(s.items), _equip),
    ("bot.activateBlock", lambda g, s: bool(s.blocks), _activate_block),
    ("bot.activateItem", lambda g, s: bool(s.items), _code("await bot.activateItem()")),
    ("bot.useOn", lambda g, s: bool(s.mobs), _use_on),
)


class RandomOptions(TeamOptions):
    """random's options (`red.KEY=VALUE`; conf/team/random.yaml repeats them)."""

    pause_every: int = Field(default=5, ge=1, description="actions between pauses")
    pause_s: float = Field(default=1.0, ge=0, description="length of a pause")
    action_timeout_s: float = Field(
        default=20.0, gt=0, description="an action still running after this long is stopped"
    )


class RandomTeam(Team):
    name = "random"
    uses_llm = False
    max_actions: ClassVar[int] = 100_000
    Options = RandomOptions

    def __init__(self, **options: object):
        super().__init__(**options)
        o = RandomOptions.model_validate(options)
        self.pause_every, self.pause_s, self.action_timeout_s = o.pause_every, o.pause_s, o.action_timeout_s
        self.actions: dict[str, list[dict]] = {}

    @staticmethod
    def seed_of(ctx: TeamContext, index: int) -> str:
        return f"{ctx.seed}/{ctx.side.key}/{index}"

    @staticmethod
    def recipients(ctx: TeamContext, index: int) -> list[str]:
        """Whom player `index` may give to or signal: its teammates, then its team's server (Dash & Dine)."""
        others = [n for n in ctx.side.player_names if n != ctx.side.player_names[index]]
        server = ctx.scenario.placeholders(ctx.side.key).get("server_name")
        return [*others, *([server] if server else [])]

    def generator(self, ctx: TeamContext, index: int) -> RandomActions:
        return RandomActions(self.seed_of(ctx, index), ctx.scenario.primitives, self.recipients(ctx, index))

    async def play(self, ctx: TeamContext) -> None:
        names = ctx.side.player_names
        self.iterations = [0] * len(names)
        self.actions = {n: [] for n in names}
        await asyncio.gather(*(self._act(ctx, k, name) for k, name in enumerate(names)))

    async def _act(self, ctx: TeamContext, k: int, name: str) -> None:
        player = ctx.players[name]
        gen = self.generator(ctx, k)
        obs = ev.last_observation(ctx.observations.get(name) or [])
        start = ctx.deadline - ctx.episode_length if ctx.deadline else ctx.clock.now()
        for n in range(self.max_actions):
            if ctx.time_left() <= 0:
                break
            if n and n % self.pause_every == 0:
                await ctx.sleep(self.pause_s, name)
            action = gen.next(obs)
            self.iterations[k] += 1
            entry = {"t": round(ctx.clock.now() - start, 2), **action.to_dict(), "saw": compact(obs)}
            self.actions[name].append(entry)
            try:
                events = await player.run(action.code, timeout=min(self.action_timeout_s, max(0.1, ctx.time_left())))
            except Exception as exc:  # noqa: BLE001 - a bot that cannot run code now: note it, wait a little, go on
                entry["error"] = f"{type(exc).__name__}: {exc}"
                await ctx.sleep(1.0, name)
                continue
            errors = ev.errors(events)
            if errors:
                entry["error"] = errors[0]
            obs = ev.last_observation(events) or obs

    async def post_game(self, ctx: TeamContext) -> None:
        ctx.out_dir.mkdir(parents=True, exist_ok=True)
        names = ctx.side.player_names
        (ctx.out_dir / "random.json").write_text(
            json.dumps(
                {
                    "seeds": {n: self.seed_of(ctx, k) for k, n in enumerate(names)},
                    "recipients": {n: self.recipients(ctx, k) for k, n in enumerate(names)},
                    "primitives": list(ctx.scenario.primitives),
                    "actions": self.actions,
                },
                indent=1,
            )
        )
