// berries, first player: keep harvesting the berry farm and serve sweet berries.
const SERVER = '$server_name'
while (true) {
  await harvestBerries(bot, new Vec3($berry_farm))
  await plantSweetBerryBushes(bot)
  await bot.waitForTicks(20)
  await giveToPlayer(bot, 'sweet_berries', SERVER, -1)
}
