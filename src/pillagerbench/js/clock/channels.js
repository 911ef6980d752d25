'use strict'
// The lockstep clock's messages between the server and a bot: Minecraft plugin-channel packets
// (custom_payload) on the game connection itself, so that a bot's "done" for tick N reaches the server
// after every packet the bot sent during tick N (one TCP stream, read in order).
//   JOIN  bot -> server  this bot runs on the game clock: wait for it from the next tick on
//   TICK  server -> bot  tick N has begun: advance 50 ms of game time (data: N, uint32)
//   DONE  bot -> server  tick N is done: physics, agent code, packets sent (data: N, uint32)
//   IDLE  bot -> server  its run has ended: during a game, hold the clock until its team says what next
//   BUSY  bot -> server  a run has begun: release that hold
const CHANNELS = {
  JOIN: 'pillagerbench:join',
  TICK: 'pillagerbench:tick',
  DONE: 'pillagerbench:done',
  IDLE: 'pillagerbench:idle',
  BUSY: 'pillagerbench:busy'
}

function tickData (n) {
  const b = Buffer.alloc(4)
  b.writeUInt32BE(n >>> 0)
  return b
}

function tickOf (data) {
  return Buffer.isBuffer(data) && data.length >= 4 ? data.readUInt32BE(0) : null
}

const CLOCK_CHANNELS = new Set(Object.values(CHANNELS)) // a plugin-channel packet of the clock's own

module.exports = { CHANNELS, CLOCK_CHANNELS, tickData, tickOf }
