'use strict'
// The attack cooldown of vanilla 1.16: a hit does damage × (0.2 + 0.8 × strength²), where the
// strength grows from 0 to 1 over 20 / attack speed ticks since the player's last attack or change
// of held item (tables.ATTACK_SPEED; maths in ../limits.js). Spamming attacks does little damage;
// waiting for the cooldown does full damage. Loaded after mobs.js, which sets the weapon's damage.
const { attackStrength, damageScale } = require('../limits')

module.exports.player = function (player, serv) {
  player.pbAttackResetTick = 0
  const reset = () => { player.pbAttackResetTick = serv.tickCount }
  player._client.on('held_item_slot', reset)
  player.on('attack_cancel', (data) => {
    const held = player.inventory.slots[36 + player.heldItemSlot]
    const strength = attackStrength(serv.tickCount - player.pbAttackResetTick, held?.name ?? 'hand')
    data.damage = (data.damage ?? 1) * damageScale(strength)
    data.attackStrength = strength
    reset()
  })
}
