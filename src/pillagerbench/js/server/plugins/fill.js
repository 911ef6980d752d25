'use strict'
// /fill x1 y1 z1 x2 y2 z2 block — for people watching with a client (agents cannot use commands);
// the control channel's `fill` uses the same serv.pb.fill.
const { toBlockPos, stateIdOf, ControlError } = require('../util')

const MAX_VOLUME = 32768

module.exports.server = function (serv) {
  serv.pb.fill = async (from, to, name, properties = {}) => {
    const a = toBlockPos(from, 'from')
    const b = toBlockPos(to, 'to')
    const stateId = stateIdOf(serv.registry, name, properties)
    const [x0, x1] = [Math.min(a.x, b.x), Math.max(a.x, b.x)]
    const [y0, y1] = [Math.min(a.y, b.y), Math.max(a.y, b.y)]
    const [z0, z1] = [Math.min(a.z, b.z), Math.max(a.z, b.z)]
    const volume = (x1 - x0 + 1) * (y1 - y0 + 1) * (z1 - z0 + 1)
    if (volume > MAX_VOLUME) throw new ControlError(`fill volume ${volume} is larger than ${MAX_VOLUME} blocks`)
    const jobs = []
    for (let x = x0; x <= x1; x++) for (let y = y0; y <= y1; y++) for (let z = z0; z <= z1; z++) jobs.push(serv.pb.setBlockQuiet(a.set(x, y, z).clone(), stateId))
    await Promise.all(jobs)
    return volume
  }

  serv.commands.add({
    base: 'fill',
    info: 'Fill a box with a block',
    usage: '/fill <x1> <y1> <z1> <x2> <y2> <z2> <block>',
    op: true,
    parse (str) {
      const parts = str.trim().split(/\s+/)
      if (parts.length !== 7 || parts.slice(0, 6).some(v => !Number.isFinite(Number(v)))) return false
      return parts
    },
    async action (parts) {
      const n = parts.slice(0, 6).map(Number)
      const volume = await serv.pb.fill(n.slice(0, 3), n.slice(3, 6), parts[6])
      return `Filled ${volume} blocks`
    }
  })
}
