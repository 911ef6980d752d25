'use strict'
// The server's packets to each player leave in one write per tick instead of one per packet:
// profiles of a match showed a third of the server's CPU in those system calls (the tick sends
// each player the moves of every entity it sees). See js/bot/batch.js.
const { batchWrites } = require('../../bot/batch')

module.exports.player = function (player) {
  batchWrites(player._client.socket)
}
