'use strict'
// Host prototypes that agent code can reach are made read-only. The facade hands agent code real
// host objects (bot.entity, bot.world, bot.inventory, blocks, items, Vec3); through
// Object.getPrototypeOf it reaches their classes' prototypes and, up the chain, EventEmitter's and
// Object's. Replacing a method there would run agent code with `this` bound to whatever host
// object calls it next — EventEmitter.prototype.emit is called on the bot itself, whose `_client`
// is the raw protocol client (and its socket the network). So every prototype reachable from the
// roots is frozen.
//
// Freezing a prototype makes a later `instance.name = x` fail when `name` is a data property of
// the prototype (the "override mistake": `this.name = 'StopError'` in an Error subclass would
// throw). As SES does, each writable data property of a library's prototype (and of
// Error.prototype) becomes a getter/setter pair whose setter gives the instance its own property
// and refuses only the prototype itself. The engine's own prototypes (Object, Array, Function,
// Promise, iterators …) are plainly frozen: turning their methods into accessors would defeat V8's
// fast paths, and Node's own code uses the copies it took at start-up.

const MAX_OBJECTS = 20000

function allowOverride (proto, key, desc) {
  const value = desc.value
  Object.defineProperty(proto, key, {
    get () { return value },
    set (v) {
      if (this === proto) throw new TypeError(`Cannot assign to read only property '${String(key)}' of a shared prototype`)
      Object.defineProperty(this, key, { value: v, writable: true, enumerable: true, configurable: true })
    },
    enumerable: desc.enumerable,
    configurable: false
  })
}

const nativeCode = (fn) => typeof fn === 'function' && /\{\s*\[native code\]\s*\}\s*$/.test(Function.prototype.toString.call(fn))

function lockObject (obj) {
  if (!Object.isExtensible(obj)) return
  const ctor = Object.getOwnPropertyDescriptor(obj, 'constructor')
  // (the engine's function prototypes already had their constructor replaced by a read-only thrower)
  const intrinsic = obj !== Error.prototype && (!ctor || !ctor.writable || nativeCode(ctor.value))
  for (const key of Reflect.ownKeys(obj)) {
    const desc = Object.getOwnPropertyDescriptor(obj, key)
    if (!desc || !desc.configurable) continue // e.g. EventEmitter.prototype[kCapture]: instances assign it
    if (!('value' in desc)) Object.defineProperty(obj, key, { configurable: false })
    else if (!intrinsic && desc.writable) allowOverride(obj, key, desc)
    else Object.defineProperty(obj, key, { writable: false, configurable: false })
  }
  Object.preventExtensions(obj)
}

const isObject = (v) => v !== null && (typeof v === 'object' || typeof v === 'function')

// Lock every prototype (and the constructor functions owning them) found by walking own properties
// and prototype chains from `roots`. Returns how many objects were locked.
function lockPrototypes (roots) {
  const seen = new Set()
  const queue = [...roots]
  const locked = new Set()
  const lock = (proto) => {
    if (!isObject(proto) || locked.has(proto)) return
    locked.add(proto)
    lockObject(proto)
  }
  for (let i = 0; i < queue.length && seen.size < MAX_OBJECTS; i++) {
    const v = queue[i]
    if (!isObject(v) || seen.has(v)) continue
    seen.add(v)
    if (ArrayBuffer.isView(v) || (Array.isArray(v) && v.length > 256)) continue
    for (let p = Object.getPrototypeOf(v); p; p = Object.getPrototypeOf(p)) {
      lock(p)
      queue.push(p)
      const ctor = Object.getOwnPropertyDescriptor(p, 'constructor')
      if (ctor && typeof ctor.value === 'function') queue.push(ctor.value)
    }
    if (typeof v === 'function' && isObject(v.prototype)) { lock(v.prototype); queue.push(v.prototype) }
    for (const key of Reflect.ownKeys(v)) {
      const desc = Object.getOwnPropertyDescriptor(v, key)
      if (desc && 'value' in desc) queue.push(desc.value)
    }
  }
  return locked.size
}

module.exports = { lockPrototypes, lockObject }
