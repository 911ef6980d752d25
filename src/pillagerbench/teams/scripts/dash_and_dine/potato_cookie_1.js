// potato_cookie, second player: wheat and cocoa for cookies; clears the carrots for wheat.
const SERVER = '$server_name'
const WHEAT = new Vec3($wheat_farm)
await harvestWheat(bot, WHEAT)
await plantWheatSeeds(bot)
await destroyCrop(bot, 'carrots')
await plantWheatSeeds(bot)
while (true) {
  await harvestWheat(bot, WHEAT)
  await plantWheatSeeds(bot)
  await bot.waitForTicks(20)
  await harvestCocoa(bot, new Vec3($cocoa_farm))
  await plantCocoaBeans(bot)
  await craftItem(bot, 'cookie', 8)
  await giveToPlayer(bot, 'cookie', SERVER, -1)
}
