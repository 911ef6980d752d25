'use strict'
// Small helpers shared by the control channel and the plugins: validated names and positions.
const { Vec3 } = require('vec3')

class ControlError extends Error {}

const MAX_XZ = 29999999

function toPos (p, what = 'position') {
  const arr = Array.isArray(p) ? p : (p && typeof p === 'object' ? [p.x, p.y, p.z] : null)
  if (!arr || arr.length !== 3 || !arr.every(n => typeof n === 'number' && Number.isFinite(n))) {
    throw new ControlError(`${what} must be [x, y, z] numbers, got ${JSON.stringify(p)}`)
  }
  const [x, y, z] = arr
  if (y < 0 || y > 255) throw new ControlError(`${what} y=${y} is out of range 0..255`)
  if (Math.abs(x) > MAX_XZ || Math.abs(z) > MAX_XZ) throw new ControlError(`${what} ${JSON.stringify(arr)} is out of the world`)
  return new Vec3(x, y, z)
}

function toBlockPos (p, what) { return toPos(p, what).floored() }

function closeNames (names, wanted, n = 5) {
  const w = String(wanted)
  const hits = names.filter(k => k.includes(w) || w.includes(k)).slice(0, n)
  return hits.length ? ` (did you mean: ${hits.join(', ')}?)` : ''
}

function blockByName (registry, name) {
  const b = registry.blocksByName[name]
  if (!b) throw new ControlError(`unknown block '${name}'${closeNames(Object.keys(registry.blocksByName), name)}`)
  return b
}

function itemByName (registry, name) {
  const it = registry.itemsByName[name]
  if (!it) throw new ControlError(`unknown item '${name}'${closeNames(Object.keys(registry.itemsByName), name)}`)
  return it
}

// State id of a block with some of its properties set, e.g. ('wheat', {age: 7}).
function stateIdOf (registry, name, properties = {}) {
  const block = blockByName(registry, name)
  if (!block.states || block.states.length === 0) {
    if (Object.keys(properties).length) throw new ControlError(`block '${name}' has no properties`)
    return block.defaultState
  }
  let data = 0
  let offset = 1
  let base = block.defaultState - block.minStateId
  for (let i = block.states.length - 1; i >= 0; i--) {
    const st = block.states[i]
    let value = base % st.num_values
    base = Math.floor(base / st.num_values)
    if (properties[st.name] !== undefined) value = propertyIndex(name, st, properties[st.name])
    data += offset * value
    offset *= st.num_values
  }
  for (const key of Object.keys(properties)) {
    if (!block.states.some(s => s.name === key)) {
      throw new ControlError(`block '${name}' has no property '${key}' (has: ${block.states.map(s => s.name).join(', ')})`)
    }
  }
  return block.minStateId + data
}

function propertyIndex (blockName, st, value) {
  let idx
  if (st.type === 'bool') idx = (value === true || value === 'true') ? 0 : (value === false || value === 'false') ? 1 : -1
  else if (st.type === 'enum') idx = st.values.indexOf(String(value))
  else idx = Number(value) - (st.values ? Number(st.values[0]) : 0)
  if (!(idx >= 0 && idx < st.num_values)) {
    throw new ControlError(`bad value ${JSON.stringify(value)} for ${blockName}.${st.name}` +
      (st.values ? ` (valid: ${st.values.join(', ')})` : ''))
  }
  return idx
}

// {age: 3, ...} of a block object from prismarine-block
function propertiesOf (block) {
  return block.getProperties ? block.getProperties() : {}
}

module.exports = { ControlError, toPos, toBlockPos, blockByName, itemByName, stateIdOf, propertiesOf, Vec3 }

// A count drawn uniformly from [lo, hi], negative results meaning none (vanilla's way of giving
// mushroom blocks 0-2 mushrooms, 0 with probability 7/9).
function rollCount ([lo, hi], random = Math.random) {
  return Math.max(0, lo + Math.floor(random() * (hi - lo + 1)))
}
module.exports.rollCount = rollCount
