// cake_beetroot, second player: beetroot soup; clears the melon and pumpkin stems for beetroot.
const SERVER = '$server_name'
const FIELD = new Vec3($beetroot_farm)
await getItemFromChest(bot, new Vec3($bowl_chest), { bowl: 64 })
await harvestBeetroot(bot, FIELD)
await plantBeetrootSeeds(bot)
bot.chat('Destroying melon and pumpkin stems')
let destroyed = 0
for (const name of ['melon_stem', 'pumpkin_stem', 'attached_melon_stem', 'attached_pumpkin_stem']) {
  if (destroyed >= 20) break
  destroyed += await destroyCrop(bot, name)
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
