'use strict'
// sendSignal(bot, username), waitSignal(bot, task = null, timeoutDuration = 30000)
const { checkString } = require('./util')

module.exports = {
  name: 'multiAgent',
  make (ctx) {
    const { bot, run } = ctx

    async function sendSignal (_bot, username) {
      checkString(username, 'username for sendSignal')
      ctx.chat(`[${username} signal]`)
    }

    // As upstream's: chats '[waiting signal]'; when another player chats '[<own name> signal]' it chats
    // '[signal recieved]' (sic, upstream's spelling) at once, or '[signal timeout]' when the time is up;
    // `task(bot)` runs meanwhile, and waitSignal returns when both are done.
    async function waitSignal (_bot, task = null, timeoutDuration = 30000) {
      const expected = `[${bot.username} signal]`
      ctx.chat('[waiting signal]')
      const signal = new Promise(resolve => {
        const timer = setTimeout(() => {
          run.unlisten(bot, 'chat', onChat)
          if (run.active) ctx.chat('[signal timeout]')
          resolve(false)
        }, timeoutDuration)
        run.cleanups.push(() => clearTimeout(timer))
        function onChat (username, message) {
          if (username === bot.username || String(message).trim() !== expected) return
          clearTimeout(timer)
          run.unlisten(bot, 'chat', onChat)
          ctx.chat('[signal recieved]')
          resolve(true)
        }
        run.listen(bot, 'chat', onChat)
      })
      const work = typeof task === 'function' ? task(_bot) : task
      const [got] = await run.race(Promise.all([signal, work]))
      return got
    }

    return { sendSignal, waitSignal }
  }
}
