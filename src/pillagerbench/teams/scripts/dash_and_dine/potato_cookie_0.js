// potato_cookie, first player: potatoes, baked in the furnaces; clears the berry bushes and tills.
const SERVER = '$server_name'
const FIELD = new Vec3($potato_farm).offset(0, 0, -1)
const FURNACE = new Vec3($furnace)
await getItemFromChest(bot, new Vec3($tool_chest), { netherite_hoe: 1 })
await harvestPotatoes(bot, FIELD)
await plantPotatoes(bot)
await destroyCrop(bot, 'sweet_berry_bush')
await tillLand(bot)
while (true) {
  await harvestPotatoes(bot, FIELD)
  await plantPotatoes(bot)
  await bot.waitForTicks(20)
  if (bot.inventory.items().some(it => it.name === 'potato')) {
    await bot.pathfinder.goto(new GoalNear(FURNACE.x, FURNACE.y, FURNACE.z, 3))
    await smeltItem(bot, 'potato', 'coal', 8)
  }
  await giveToPlayer(bot, 'baked_potato', SERVER, -1)
  await giveToPlayer(bot, 'potato', SERVER, -1)
}
