// cake_beetroot, second player: beetroot soup; clears the melon and pumpkin stems for beetroot.
const SERVER = '$server_name'
const FIELD = new Vec3($beetroot_farm)
await getItemFromChest(bot, new Vec3($bowl_chest), { bowl: 64 })
await harvestBeetroot(bot, FIELD)
await plantBeetrootSeeds(bot)
// up to 20 melon and pumpkin stems within 32 blocks, nearest first, broken by hand
bot.chat('Destroying melon and pumpkin stems')
const STEMS = ['melon_stem', 'pumpkin_stem', 'attached_melon_stem', 'attached_pumpkin_stem'].map(n => mcData.blocksByName[n].id)
let destroyed = 0
for (const p of bot.findBlocks({ matching: STEMS, maxDistance: 32, count: 20 })) {
  const b = bot.blockAt(p)
  if (!b || !STEMS.includes(b.type)) continue
  await bot.pathfinder.goto(new GoalNear(p.x, p.y, p.z, 3))
  await bot.dig(bot.blockAt(p))
  destroyed++
}
bot.chat('Destroyed ' + destroyed + ' melons and pumpkin stems')
await plantBeetrootSeeds(bot)
while (true) {
  await harvestBeetroot(bot, FIELD)
  await plantBeetrootSeeds(bot)
  await bot.waitForTicks(20)
  const beetroot = bot.inventory.items().filter(it => it.name === 'beetroot').reduce((n, it) => n + it.count, 0)
  if (beetroot >= 6) {
    await craftItem(bot, 'beetroot_soup', 1)
    await giveToPlayer(bot, 'beetroot_soup', SERVER, -1)
  }
}
