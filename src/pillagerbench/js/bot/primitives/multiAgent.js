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

    async function waitSignal (_bot, task = null, timeoutDuration = 30000) {
      const expected = `[${bot.username} signal]`
      ctx.chat('[waiting signal]')
      const signal = new Promise(resolve => {
        const timer = setTimeout(() => { run.unlisten(bot, 'chat', onChat); resolve(false) }, timeoutDuration)
        run.cleanups.push(() => clearTimeout(timer))
        function onChat (username, message) {
          if (username === bot.username || String(message).trim() !== expected) return
          clearTimeout(timer)
          run.unlisten(bot, 'chat', onChat)
          resolve(true)
        }
        run.listen(bot, 'chat', onChat)
      })
      const work = typeof task === 'function' ? task() : task
      const [got] = await run.race(Promise.all([signal, work]))
      ctx.chat(got ? '[signal recieved]' : '[signal timeout]')
      return got
    }

    return { sendSignal, waitSignal }
  }
}
