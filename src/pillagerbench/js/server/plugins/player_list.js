'use strict'
// The tab list (player_info) goes to everyone, the new player included. flying-squid sent it only
// to the others, so a player never learned the names of those who logged in before it, and its
// client (mineflayer) could not tell which spawned entity was which player: `bot.players[name].entity`
// stayed empty for them and giving items to them failed. flying-squid re-assigns its version at
// every login, so ours is installed as a property that keeps itself.
module.exports.server = function (serv) {
  function sendPlayerList () {
    const data = serv.players.map(p => ({
      uuid: p.uuid, name: p.username, properties: p.profileProperties, gamemode: p.gameMode, ping: p._client.latency
    }))
    for (const p of serv.players) p._client.write('player_info', { action: 'add_player', data })
  }
  Object.defineProperty(serv, '_sendPlayerList', { get: () => sendPlayerList, set: () => {}, configurable: true })
}
