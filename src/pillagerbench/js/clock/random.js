'use strict'
// The game's chance, seeded per episode: with the game clock, what makes an episode replayable.
// The server seeds its own draws (drops, growth) and Math.random from the episode's seed; each bot
// seeds Math.random, its own and its agent code's, from the seed and its name.

// A small seedable PRNG (mulberry32).
function seededRandom (seed) {
  let a = (Number(seed) >>> 0) || 1
  return function () {
    a = (a + 0x6D2B79F5) >>> 0
    let t = a
    t = Math.imul(t ^ (t >>> 15), t | 1)
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61)
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296
  }
}

// One seed from an episode's seed and a name (FNV-1a over both).
function seedOf (seed, name) {
  let h = 0x811c9dc5
  for (const ch of `${seed}:${name}`) h = Math.imul(h ^ ch.codePointAt(0), 0x01000193) >>> 0
  return h
}

module.exports = { seededRandom, seedOf }
