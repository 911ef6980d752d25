"""Player health as vanilla's on peaceful difficulty (tables.HEALTH, plugins/player_health.js): natural
regeneration, immunity right after a hit, and sweet berry bushes that hurt a player moving through them."""

from __future__ import annotations

from tests.server.conftest import wait_until
from tests.support.server_clock import tick, wait_ticks

HIT = "bot._client.write('use_entity', {target: bot.players.%s.entity.id, mouse: 1, sneaking: false})"


async def health(arena, name: str) -> float:
    return next(p["health"] for p in await arena.players() if p["name"] == name)


async def full_health(arena, name: str) -> None:
    async def full():
        return await health(arena, name) == 20

    assert await wait_until(full, timeout=25), f"{name} did not come back to full health"


async def sword_hit(arena, bots, area) -> None:
    """bob, beside alice, hits her once at full strength with an iron sword (6)."""
    alice, bob = bots
    await area.put(alice, 0, 0)
    await area.put(bob, 2, 0, {"iron_sword": 1})
    await full_health(arena, "alice")
    await bob.eval(
        "for (let i = 0; i < 60 && !bot.players.alice?.entity; i++) await sleep(50)\n"
        "await bot.equip(mcData.itemsByName.iron_sword.id, 'hand')\nawait sleep(1000)\n" + HIT % "alice"
    )


async def ticked_health(arena, name: str) -> tuple[float, int, int]:
    """A player's health and the server ticks just before and after reading it."""
    before = await tick(arena)
    value = await health(arena, name)
    return value, before, await tick(arena)


def heals_between(a: int, b: int) -> int:
    """Regeneration ticks (every 20th server tick) in (a, b]."""
    return b // 20 - a // 20


async def test_a_hurt_player_heals_one_point_every_twenty_ticks(arena, bots, area):
    await sword_hit(arena, bots, area)
    assert await wait_until(lambda: _below(arena, 20))
    hurt, hurt_lo, hurt_hi = await ticked_health(arena, "alice")
    assert 14 <= hurt <= 15, hurt  # 20 - 6, and perhaps one point healed already
    await wait_ticks(arena, 60)
    healed, healed_lo, healed_hi = await ticked_health(arena, "alice")
    # one point on every 20th tick between the two reads (flying-squid: none)
    least, most = heals_between(hurt_hi, healed_lo), heals_between(hurt_lo, healed_hi)
    assert least >= 3 and least <= healed - hurt <= most, (hurt, healed, least, most)
    await full_health(arena, "alice")


async def test_a_weaker_hit_within_ten_ticks_of_a_hit_does_nothing(arena, bots, area):
    alice, bob = bots
    await sword_hit(arena, bots, area)
    # 7 ticks later: the sword at 60 % strength would do 6 * (0.2 + 0.8 * 0.36) = 2.9, not more than the 6 just taken
    await bob.eval("await sleep(350)\n" + HIT % "alice" + "\nawait sleep(300)")
    after = await health(arena, "alice")
    assert after >= 14, after  # 11.1 without the immunity (12.1 with a point healed)
    # more than 10 ticks after the first hit, a full-strength hit lands again
    await wait_ticks(arena, 14)  # the sword back at full strength (12.5 ticks)
    await bob.eval(HIT % "alice" + "\nawait sleep(300)")
    again = await health(arena, "alice")
    assert after - 6 <= again <= after - 4, (after, again)
    await full_health(arena, "alice")


async def test_walking_through_ripe_berry_bushes_hurts_standing_in_one_does_not(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0)
    await full_health(arena, "alice")
    await arena.set_blocks(blocks=[[*area.at(dx, 4, 0), "sweet_berry_bush", {"age": 3}] for dx in range(1, 10)])
    x0 = area.x0
    await alice.eval(
        "for (let i = 0; bot.blockAt(new Vec3(%d, 4, 0))?.name !== 'sweet_berry_bush'; i++) {"
        " if (i > 100) throw new Error('no bush'); await sleep(50) }" % (x0 + 9)
    )
    # standing in a ripe bush hurts nobody
    await arena.teleport(player="alice", pos=area.at(1.5, 4, 0.5))
    await alice.eval("await sleep(1500)")
    assert await health(arena, "alice") == 20
    # walking east through nine ripe bushes (about 2 s): hurt every 10 ticks, healed every 20
    await alice.eval(
        "await bot.lookAt(new Vec3(%f, 5.6, 0.5), true)\nbot.setControlState('forward', true)\n"
        "await sleep(1800)\nbot.setControlState('forward', false)\nawait sleep(100)" % (x0 + 20)
    )
    walked = await health(arena, "alice")
    assert walked <= 18, walked
    await full_health(arena, "alice")


async def _below(arena, value: float) -> bool:
    return await health(arena, "alice") < value
