// melon_pumpkin, second player: pumpkin pies from pumpkins, sugar cane and eggs.
const SERVER = '$server_name'
while (true) {
  await getItemFromChest(bot, new Vec3($egg_chest), { egg: 16 })
  await bot.waitForTicks(20)
  await harvestSugarCane(bot, $ground_y)
  await harvestPumpkins(bot, new Vec3($melon_pumpkin_farm).offset(-1, 0, 0))
  await craftItem(bot, 'sugar', 3)
  await craftItem(bot, 'pumpkin_pie', 3)
  await giveToPlayer(bot, 'pumpkin_pie', SERVER, -1)
}
