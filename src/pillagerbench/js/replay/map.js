'use strict'
/* global window, document */
// The arena's top-down map, drawn on a canvas: blocks (the highest one of each column), mobs, items
// on the ground, players with facing, trail and label. Shared by the replay page (page.js, which
// moves the time) and the layout page (`pillagerbench layout show`, one moment: the arena as built).
// `window.arenaMap(D, canvas, legend)` reads D.map {box, palette, blocks, ground}, D.changes,
// D.mobs, D.items, D.tracks and D.sides (docs/replays.md) and returns {draw(t), ...}.

// ---- colours: block kinds by name, then a stable hue for anything else ----
const COLOURS = {
  grass_block: '#6aa84f', dirt: '#8b5a2b', coarse_dirt: '#7a4f27', farmland: '#5c3a1e', grass_path: '#a58a4f', stone: '#8a8a8a',
  cobblestone: '#777', bedrock: '#333', sand: '#e3d59b', gravel: '#8f8580', water: '#3f76e4', lava: '#e8601c',
  oak_log: '#6b5030', oak_planks: '#b8945f', spruce_planks: '#7a5a34', birch_planks: '#d7c185', jungle_log: '#58461f',
  red_mushroom: '#d63a2f', brown_mushroom: '#9c6b4a', red_mushroom_block: '#b3261e', brown_mushroom_block: '#8d6346',
  mushroom_stem: '#d8d0c0', slime_block: '#7fdc6a', mycelium: '#7b6a78', podzol: '#6b4a26',
  chest: '#a0722a', crafting_table: '#9a6b3c', furnace: '#5f5f5f', hay_block: '#c9a826', composter: '#7d5a2d',
  wheat: '#d8c056', carrots: '#f08a1c', potatoes: '#c2a25a', beetroots: '#a2303b', sugar_cane: '#8fd16a',
  melon: '#5aa02c', melon_stem: '#7fa34a', attached_melon_stem: '#7fa34a', pumpkin: '#e0861b', pumpkin_stem: '#8aa34a',
  attached_pumpkin_stem: '#8aa34a', sweet_berry_bush: '#3f6e3a', cocoa: '#8a4b1f', cake: '#f3e1d1',
  red_wool: '#b02e26', blue_wool: '#3c44aa', white_wool: '#e9ecec', red_concrete: '#8e2121', blue_concrete: '#2c2e8f',
  red_terracotta: '#8f3d2e', blue_terracotta: '#4a3b5b', glass: '#c0e8f0', torch: '#ffd24a', fence: '#9a7a4a',
  oak_fence: '#9a7a4a', cobblestone_wall: '#6f6f6f', barrier: '#f0f0f0', iron_block: '#dcdcdc', gold_block: '#f5d33c'
}
function colourOf (name) {
  if (COLOURS[name]) return COLOURS[name]
  let h = 0
  for (const c of name) h = (h * 31 + c.charCodeAt(0)) % 360
  return `hsl(${h}, 45%, 55%)`
}

// ---- the world at a time: the initial blocks plus the changes up to it ----
// worldAt(t) of the map D: the world kept from the last call, rebuilt from the start when t goes back.
function worldTimeline (D) {
  const initial = new Map() // "x,y,z" -> name
  for (const [x, y, z, i] of D.map.blocks) initial.set(`${x},${y},${z}`, D.map.palette[i])
  let world = null
  let worldT = -1
  let nextChange = 0
  return function worldAt (t) {
    if (world === null || t < worldT) { world = new Map(initial); nextChange = 0 }
    while (nextChange < D.changes.length && D.changes[nextChange][0] <= t) {
      const [, x, y, z, name] = D.changes[nextChange++]
      if (name === 'air') world.delete(`${x},${y},${z}`)
      else world.set(`${x},${y},${z}`, name)
    }
    worldT = t
    return world
  }
}
function topBlocks (blocks) { // "x,z" -> [y, name] of the highest block per column
  const tops = new Map()
  for (const [k, name] of blocks) {
    const [x, y, z] = k.split(',').map(Number)
    const c = `${x},${z}`
    const old = tops.get(c)
    if (!old || y > old[0]) tops.set(c, [y, name])
  }
  return tops
}

// Track samples: name -> [[t, x, y, z, yaw, held], ...]
function sampleAt (track, t) { // the last sample at or before t (binary search)
  let lo = 0; let hi = track.length - 1
  if (hi < 0 || track[0][0] > t) return null
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1
    if (track[mid][0] <= t) lo = mid; else hi = mid - 1
  }
  return track[lo]
}

// ---- drawing: `grid` is the canvas's {ctx, cell, px, pz} (px, pz: a block coordinate's canvas offset) ----
function drawBlocks (grid, tops, ground) { // the kinds drawn
  const { ctx, cell, px, pz } = grid
  const kinds = new Set()
  for (const [c, [y, name]] of tops) {
    const [x, z] = c.split(',').map(Number)
    ctx.fillStyle = colourOf(name)
    ctx.fillRect(px(x), pz(z), cell, cell)
    if (y > ground) { ctx.fillStyle = 'rgba(255,255,255,0.12)'; ctx.fillRect(px(x), pz(z), cell, cell / 4) }
    kinds.add(name)
  }
  return kinds
}

function drawMobs (grid, mobs, t) {
  const { ctx, cell, px, pz } = grid
  for (const m of mobs) {
    if (m.from > t || m.to <= t) continue
    const cx = px(m.pos[0]); const cz = pz(m.pos[2])
    ctx.fillStyle = '#f4c2c2'; ctx.strokeStyle = '#000'
    ctx.beginPath(); ctx.moveTo(cx, cz - cell * 0.5); ctx.lineTo(cx + cell * 0.45, cz + cell * 0.35); ctx.lineTo(cx - cell * 0.45, cz + cell * 0.35); ctx.closePath(); ctx.fill(); ctx.stroke()
  }
}

// items lying in the world
function drawItems (grid, items, t) {
  const { ctx, cell, px, pz } = grid
  for (const it of items) {
    if (it.from > t || it.to <= t) continue
    const cx = px(it.pos[0]); const cz = pz(it.pos[2]); const s = Math.max(3, cell * 0.4)
    ctx.fillStyle = colourOf(it.item); ctx.strokeStyle = '#fff'; ctx.lineWidth = 1
    ctx.fillRect(cx - s / 2, cz - s / 2, s, s); ctx.strokeRect(cx - s / 2, cz - s / 2, s, s)
  }
}

// A player: trail (last 10 s), marker, facing, label; returns the marker's canvas point.
function drawPlayer (grid, name, track, now, t, colour) {
  const { ctx, cell, px, pz } = grid
  ctx.strokeStyle = colour; ctx.globalAlpha = 0.55; ctx.lineWidth = Math.max(1, cell / 6)
  ctx.beginPath()
  let first = true
  for (const s of track) {
    if (s[0] < t - 10) continue
    if (s[0] > t) break
    if (first) { ctx.moveTo(px(s[1]), pz(s[3])); first = false } else ctx.lineTo(px(s[1]), pz(s[3]))
  }
  ctx.stroke(); ctx.globalAlpha = 1
  const cx = px(now[1]); const cz = pz(now[3]); const r = Math.max(4, cell * 0.45)
  const yaw = now[4] * Math.PI / 180
  ctx.strokeStyle = '#000'; ctx.lineWidth = 2
  ctx.beginPath(); ctx.moveTo(cx, cz); ctx.lineTo(cx - Math.sin(yaw) * r * 2.2, cz + Math.cos(yaw) * r * 2.2); ctx.stroke()
  ctx.fillStyle = colour
  ctx.beginPath(); ctx.arc(cx, cz, r, 0, 2 * Math.PI); ctx.fill(); ctx.stroke()
  ctx.font = 'bold 12px system-ui, sans-serif'; ctx.lineWidth = 3; ctx.strokeStyle = '#fff'; ctx.fillStyle = '#000'
  const label = name + (now[5] ? ` (${now[5]})` : '')
  ctx.strokeText(label, cx + r + 2, cz - r); ctx.fillText(label, cx + r + 2, cz - r)
  return [cx, cz]
}

// legend(kinds) into legendEl: the block kinds drawn, then the markers; rewritten only when the kinds change.
function mapLegend (legendEl) {
  let legendKey = ''
  return function legend (kinds) {
    const names = [...kinds].sort()
    const key = names.join(',')
    if (key === legendKey) return
    legendKey = key
    legendEl.textContent = ''
    for (const n of names) {
      const row = document.createElement('span')
      const sw = document.createElement('i')
      sw.style.background = colourOf(n)
      row.append(sw, n.replace(/_/g, ' '))
      legendEl.append(row)
    }
    for (const [label, cls] of [['player (facing, 10 s trail)', 'pl'], ['item on the ground', 'it'], ['mob', 'mob']]) {
      const row = document.createElement('span')
      const sw = document.createElement('i')
      sw.className = cls
      row.append(sw, label)
      legendEl.append(row)
    }
  }
}

window.arenaMap = function (D, canvas, legendEl) {
  const worldAt = worldTimeline(D)

  // ---- layout ----
  const [[x0, , z0], [x1, , z1]] = D.map.box
  const W = x1 - x0 + 1
  const H = z1 - z0 + 1
  const cell = Math.max(4, Math.floor(Math.min(760 / W, 620 / H)))
  canvas.width = W * cell
  canvas.height = H * cell
  const ctx = canvas.getContext('2d')
  const px = (x) => (x - x0) * cell
  const pz = (z) => (z - z0) * cell
  const grid = { ctx, cell, px, pz }

  const sideOf = {}
  for (const [key, side] of Object.entries(D.sides)) for (const p of side.players) sideOf[p] = key
  const SIDE_COLOURS = { red: '#e53935', blue: '#1e63d6' }
  const sideColour = (key) => SIDE_COLOURS[key] || '#555'

  const legend = mapLegend(legendEl)
  const shown = {} // what was drawn last: name -> [canvas x, canvas y]
  function draw (t) {
    const tops = topBlocks(worldAt(t))
    ctx.fillStyle = '#1b1b1b'
    ctx.fillRect(0, 0, canvas.width, canvas.height)
    legend(drawBlocks(grid, tops, D.map.ground))
    drawMobs(grid, D.mobs, t)
    drawItems(grid, D.items, t)
    // players: trail (last 10 s), marker, facing, label
    for (const [name, track] of Object.entries(D.tracks)) {
      const now = sampleAt(track, t)
      if (!now) { delete shown[name]; continue }
      shown[name] = drawPlayer(grid, name, track, now, t, sideColour(sideOf[name]))
    }
  }

  return {
    draw,
    sampleAt,
    sideOf,
    sideColour,
    colourOf,
    cellCentre: (x, z) => [px(x) + cell / 2, pz(z) + cell / 2], // the canvas point of block column (x, z)
    markers: () => JSON.parse(JSON.stringify(shown))
  }
}
