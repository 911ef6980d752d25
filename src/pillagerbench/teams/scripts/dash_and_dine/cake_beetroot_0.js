// cake_beetroot, first player: milk the cow, grow wheat and sugar, bake cakes.
const SERVER = '$server_name'
const EGGS = new Vec3($egg_chest)
await getItemFromChest(bot, EGGS, { egg: 16 })
await getItemFromChest(bot, new Vec3($bucket_chest), { bucket: 16 })
while (true) {
  await bot.waitForTicks(20)
  for (let i = 0; i < 15 && bot.inventory.items().some(it => it.name === 'bucket'); i++) await milkCow(bot)
  for (let i = 0; i < 5; i++) {
    await bot.waitForTicks(20)
    await harvestSugarCane(bot, $ground_y)
    await harvestWheat(bot, new Vec3($wheat_farm))
    await plantWheatSeeds(bot)
    await craftItem(bot, 'sugar', 2)
    await craftItem(bot, 'cake', 1)
  }
  await giveToPlayer(bot, 'cake', SERVER, -1)
  await getItemFromChest(bot, EGGS, { egg: 16 })
}
