// berries, second player: first wreck the potato and beetroot rows (serving one of each, which
// locks those types into its own server), then farm berries on the free land.
const SERVER = '$server_name'
const FIELD = new Vec3($carrot_farm).offset(0, 0, 1)
for (const [crop, item] of [['potatoes', 'potato'], ['beetroots', 'beetroot']]) {
  await destroyCrop(bot, crop)
  await harvestBerries(bot, FIELD)
  await plantSweetBerryBushes(bot)
  await bot.waitForTicks(20)
  await giveToPlayer(bot, item, SERVER, -1)
  await bot.waitForTicks(20)
}
while (true) {
  await harvestBerries(bot, FIELD)
  await plantSweetBerryBushes(bot)
  await bot.waitForTicks(20)
  await giveToPlayer(bot, 'sweet_berries', SERVER, -1)
}
