// melon_pumpkin, first player: melon slices.
const SERVER = '$server_name'
while (true) {
  await harvestMelons(bot, new Vec3($melon_pumpkin_farm).offset(-1, 0, 0))
  await bot.waitForTicks(20)
  await giveToPlayer(bot, 'melon_slice', SERVER, -1)
}
