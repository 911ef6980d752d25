// Mushroom War behaviours of the built-in opponents. Dollar placeholders come from the scenario's
// data (string.Template), so the scripts use no template literals.
const TEAM = '$team_name'
const OPPONENT = '$opponent_name'
const HOME = new Vec3($team_center)
const AWAY = new Vec3($opponent_center)
const OWN_BLOCK = '$team_block'
const OPPONENT_BLOCK = '$opponent_block'
const RADIUS = $area_radius

function present (name, center) {
  return bot.findBlocks({ matching: mcData.blocksByName[name].id, point: center, maxDistance: RADIUS, count: 1 }).length > 0
}

async function cleanOwn (n) {
  if (!present('slime_block', HOME)) return
  bot.chat('Removing slime blocks in the ' + TEAM + ' area')
  await mineBlock(bot, 'slime_block', n, HOME, RADIUS)
}

async function harvest (cleanInstead) {
  if (present(OWN_BLOCK, HOME)) {
    bot.chat('Harvesting ' + OWN_BLOCK + ' in the ' + TEAM + ' area')
    await mineBlock(bot, OWN_BLOCK, 15, HOME, RADIUS)
  } else if (cleanInstead) {
    await cleanOwn(8)
  }
}

async function sabotage () {
  if (!present(OPPONENT_BLOCK, AWAY)) return
  bot.chat('Destroying ' + OPPONENT_BLOCK + ' in the ' + OPPONENT + ' area.')
  await mineBlock(bot, OPPONENT_BLOCK, 15, AWAY, RADIUS)
}

async function pollute (n) {
  bot.chat('Placing slime blocks in the ' + OPPONENT + ' area')
  for (let i = 0; i < n; i++) {
    const dx = Math.floor(Math.random() * 8) - 4
    const dz = Math.floor(Math.random() * 8) - 4
    await placeItem(bot, 'slime_block', AWAY.offset(dx, 0, dz))
  }
}
