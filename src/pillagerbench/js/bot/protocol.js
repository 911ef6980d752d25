'use strict'
// The bot's stdio protocol as main.js meets it: read from its declaration, bot_protocol.json (each op's
// arguments and answer, the settings, the observation; read by Python too: pillagerbench/players/
// bot_protocol.py). main.js refuses to start when its settings are not the declared ones or its handlers
// not the declared ops (`refuse`), and every request is checked here before its handler runs (`parse`).
const PROTOCOL = require('./bot_protocol.json')
const DECLARED = PROTOCOL.ops

// The scalar types checked on the wire; the others (positions, equipment) their handlers read.
const SCALARS = {
  string: v => typeof v === 'string',
  integer: v => Number.isInteger(v),
  number: v => typeof v === 'number' && Number.isFinite(v),
  boolean: v => typeof v === 'boolean',
  names: v => Array.isArray(v) && v.every(n => typeof n === 'string')
}

const answerOf = (op) => DECLARED[op].answer || 'reply'

// What differs between `handlers` ({answer kind: {op: handler}}) and the declared ops with their answers.
function undeclared (handlers) {
  const problems = []
  for (const op of Object.keys(DECLARED)) {
    if (!Object.hasOwn(handlers[answerOf(op)] || {}, op)) problems.push(`op ${op} is declared but has no handler (answered by ${answerOf(op)})`)
  }
  for (const [answer, table] of Object.entries(handlers)) {
    for (const op of Object.keys(table)) {
      if (!Object.hasOwn(DECLARED, op)) problems.push(`op ${op} has a handler but is not declared`)
      else if (answerOf(op) !== answer) problems.push(`op ${op} is answered by ${answer}, declared ${answerOf(op)}`)
    }
  }
  return problems
}

// What is wrong with `values` against declared fields {name: type or {type}} ('?': optional; null is none).
function mismatches (values, fields, what) {
  const problems = []
  for (const name of Object.keys(values)) {
    if (!Object.hasOwn(fields, name)) problems.push(`${what}: ${JSON.stringify(name)} is not declared (declared: ${Object.keys(fields).join(', ') || 'none'})`)
  }
  for (const [name, field] of Object.entries(fields)) {
    const declared = typeof field === 'string' ? field : field.type
    const type = declared.replace(/\?$/, '')
    const value = values[name]
    if (value === undefined || value === null) {
      if (!declared.endsWith('?')) problems.push(`${what}: ${JSON.stringify(name)} is missing`)
    } else if (SCALARS[type] && !SCALARS[type](value)) {
      problems.push(`${what}: ${JSON.stringify(name)} must be ${PROTOCOL.types[type].wire}, got ${JSON.stringify(value)}`)
    }
  }
  return problems
}

// What is wrong with the settings main.js was started with.
const settingsProblems = (settings) => mismatches(settings, PROTOCOL.settings, 'settings')

// The bot does not start with `problems`: each said on stderr, exit code 2.
function refuse (problems) {
  if (!problems.length) return
  process.stderr.write(problems.map(p => `[bot] ${p}\n`).join(''))
  process.exit(2)
}

// A request line parsed and checked: {msg, op} or {msg, error} (msg is {} when the line is no JSON object).
function parse (line) {
  let msg
  try { msg = JSON.parse(line) } catch (err) { return { msg: {}, error: `bad request: ${err.message}` } }
  if (msg === null || typeof msg !== 'object' || Array.isArray(msg)) return { msg: {}, error: 'bad request: not a JSON object' }
  if (!Object.hasOwn(DECLARED, msg.op)) return { msg, error: `unknown op ${JSON.stringify(msg.op)} (valid: ${Object.keys(DECLARED).join(', ')})` }
  const args = Object.fromEntries(Object.entries(msg).filter(([k]) => k !== 'id' && k !== 'op'))
  const wrong = mismatches(args, DECLARED[msg.op].args, `op ${msg.op}`)
  return wrong.length ? { msg, error: wrong.join('; ') } : { msg, op: msg.op }
}

module.exports = { DECLARED, answerOf, undeclared, settingsProblems, refuse, parse }
