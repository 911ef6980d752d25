'use strict'
/* global document, window, requestAnimationFrame, performance */
// The replay page (written by `pillagerbench replay`, see docs/replays.md): a top-down map of the
// arena, players with facing and trail, items and mobs, a timeline, the chat and events feed and
// both teams' scores, all from the data embedded in the page as JSON (id "replay-data"). No network.
;(function () {
  const D = JSON.parse(document.getElementById('replay-data').textContent)
  const $ = (id) => document.getElementById(id)

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
  const [[x0, , z0], [x1, , z1]] = D.map.box
  const W = x1 - x0 + 1
  const H = z1 - z0 + 1
  const initial = new Map() // "x,y,z" -> name
  for (const [x, y, z, i] of D.map.blocks) initial.set(`${x},${y},${z}`, D.map.palette[i])
  let world = null
  let worldT = -1
  let nextChange = 0
  function worldAt (t) {
    if (world === null || t < worldT) { world = new Map(initial); nextChange = 0 }
    while (nextChange < D.changes.length && D.changes[nextChange][0] <= t) {
      const [, x, y, z, name] = D.changes[nextChange++]
      if (name === 'air') world.delete(`${x},${y},${z}`)
      else world.set(`${x},${y},${z}`, name)
    }
    worldT = t
    return world
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

  // ---- layout ----
  const map = $('map')
  const cell = Math.max(4, Math.floor(Math.min(760 / W, 620 / H)))
  map.width = W * cell
  map.height = H * cell
  const ctx = map.getContext('2d')
  const px = (x) => (x - x0) * cell
  const pz = (z) => (z - z0) * cell

  const sideOf = {}
  for (const [key, side] of Object.entries(D.sides)) for (const p of side.players) sideOf[p] = key
  const SIDE_COLOURS = { red: '#e53935', blue: '#1e63d6' }
  const sideColour = (key) => SIDE_COLOURS[key] || '#555'

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

  const shown = {} // what was drawn last: name -> [canvas x, canvas y]
  function drawMap (t) {
    const tops = topBlocks(worldAt(t))
    ctx.fillStyle = '#1b1b1b'
    ctx.fillRect(0, 0, map.width, map.height)
    const kinds = new Set()
    for (const [c, [y, name]] of tops) {
      const [x, z] = c.split(',').map(Number)
      ctx.fillStyle = colourOf(name)
      ctx.fillRect(px(x), pz(z), cell, cell)
      if (y > D.map.ground) { ctx.fillStyle = 'rgba(255,255,255,0.12)'; ctx.fillRect(px(x), pz(z), cell, cell / 4) }
      kinds.add(name)
    }
    legend(kinds)
    // mobs
    for (const m of D.mobs) {
      if (m.from > t || m.to <= t) continue
      const cx = px(m.pos[0]); const cz = pz(m.pos[2])
      ctx.fillStyle = '#f4c2c2'; ctx.strokeStyle = '#000'
      ctx.beginPath(); ctx.moveTo(cx, cz - cell * 0.5); ctx.lineTo(cx + cell * 0.45, cz + cell * 0.35); ctx.lineTo(cx - cell * 0.45, cz + cell * 0.35); ctx.closePath(); ctx.fill(); ctx.stroke()
    }
    // items lying in the world
    for (const it of D.items) {
      if (it.from > t || it.to <= t) continue
      const cx = px(it.pos[0]); const cz = pz(it.pos[2]); const s = Math.max(3, cell * 0.4)
      ctx.fillStyle = colourOf(it.item); ctx.strokeStyle = '#fff'; ctx.lineWidth = 1
      ctx.fillRect(cx - s / 2, cz - s / 2, s, s); ctx.strokeRect(cx - s / 2, cz - s / 2, s, s)
    }
    // players: trail (last 10 s), marker, facing, label
    for (const [name, track] of Object.entries(D.tracks)) {
      const now = sampleAt(track, t)
      if (!now) { delete shown[name]; continue }
      const colour = sideColour(sideOf[name])
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
      shown[name] = [cx, cz]
    }
  }

  let legendKey = ''
  function legend (kinds) {
    const names = [...kinds].sort()
    const key = names.join(',')
    if (key === legendKey) return
    legendKey = key
    const el = $('legend')
    el.textContent = ''
    for (const n of names) {
      const row = document.createElement('span')
      const sw = document.createElement('i')
      sw.style.background = colourOf(n)
      row.append(sw, n.replace(/_/g, ' '))
      el.append(row)
    }
    for (const [label, cls] of [['player (facing, 10 s trail)', 'pl'], ['item on the ground', 'it'], ['mob', 'mob']]) {
      const row = document.createElement('span')
      const sw = document.createElement('i')
      sw.className = cls
      row.append(sw, label)
      el.append(row)
    }
  }

  // ---- feed ----
  const feed = $('feed')
  const rows = D.feed.map(([t, kind, text]) => {
    const row = document.createElement('div')
    row.className = 'ev ' + kind
    row.dataset.t = t
    const when = document.createElement('b')
    when.textContent = clock(t)
    row.append(when, ' ' + text)
    row.addEventListener('click', () => setTime(t))
    feed.append(row)
    return row
  })
  let lastShown = -2
  function drawFeed (t) {
    let last = -1
    for (let i = 0; i < rows.length; i++) {
      const visible = D.feed[i][0] <= t
      rows[i].hidden = !visible
      rows[i].classList.remove('now')
      if (visible) last = i
    }
    if (last >= 0) rows[last].classList.add('now')
    if (last !== lastShown && last >= 0) feed.scrollTop = feed.scrollHeight
    lastShown = last
  }

  // ---- scores ----
  const chart = $('scores')
  const cctx = chart.getContext('2d')
  function drawScores (t) {
    const w = chart.width; const h = chart.height; const pad = 28
    cctx.fillStyle = '#fff'; cctx.fillRect(0, 0, w, h)
    const T = Math.max(D.length, duration, 1)
    let top = 1
    for (const s of D.scores) for (const k of Object.keys(D.sides)) top = Math.max(top, s[k] || 0)
    const X = (v) => pad + (w - 2 * pad) * v / T
    const Y = (v) => h - pad - (h - 2 * pad) * v / top
    cctx.strokeStyle = '#999'; cctx.lineWidth = 1; cctx.beginPath(); cctx.moveTo(pad, pad / 2); cctx.lineTo(pad, h - pad); cctx.lineTo(w - pad / 2, h - pad); cctx.stroke()
    cctx.fillStyle = '#444'; cctx.font = '11px system-ui, sans-serif'
    cctx.fillText(String(Math.round(top * 100) / 100), 2, pad / 2 + 8); cctx.fillText('0', 12, h - pad)
    cctx.fillText('0 s', pad, h - 8); cctx.fillText(`${Math.round(T)} s`, w - pad - 20, h - 8)
    for (const k of Object.keys(D.sides)) {
      cctx.strokeStyle = sideColour(k); cctx.lineWidth = 2; cctx.beginPath()
      D.scores.forEach((s, i) => { if (i === 0) cctx.moveTo(X(s.t), Y(s[k] || 0)); else cctx.lineTo(X(s.t), Y(s[k] || 0)) })
      cctx.stroke()
    }
    cctx.strokeStyle = '#000'; cctx.setLineDash([4, 3]); cctx.beginPath(); cctx.moveTo(X(t), pad / 2); cctx.lineTo(X(t), h - pad); cctx.stroke(); cctx.setLineDash([])
    let cur = null
    for (const s of D.scores) if (s.t <= t) cur = s
    $('score-now').textContent = Object.entries(D.sides).map(([k, s]) => `${k} ${s.team}: ${cur ? cur[k] : 0}`).join('   ')
  }

  // ---- players panel ----
  function drawPlayers (t) {
    const body = $('players')
    body.textContent = ''
    for (const [name, track] of Object.entries(D.tracks)) {
      const s = sampleAt(track, t)
      let runs = 0; let errors = 0
      for (const p of D.programs[name] || []) {
        if (p[0] > t) break
        if (p[1] === 'start') runs++
        if (p[1] === 'error') errors++
      }
      const tr = document.createElement('tr')
      for (const v of [name, sideOf[name] || '', s && s[5] ? s[5] : '-', s ? `${s[1].toFixed(1)}, ${s[2].toFixed(1)}, ${s[3].toFixed(1)}` : '-', runs, errors]) {
        const td = document.createElement('td'); td.textContent = v; tr.append(td)
      }
      tr.style.color = sideColour(sideOf[name])
      body.append(tr)
    }
  }

  // ---- time ----
  function clock (t) { const s = Math.max(0, t); return `${Math.floor(s / 60)}:${(s % 60).toFixed(1).padStart(4, '0')}` }
  const duration = D.duration
  const slider = $('time')
  slider.max = duration
  let current = 0
  let playing = false
  let last = 0
  function setTime (t) {
    current = Math.max(0, Math.min(duration, Number(t)))
    slider.value = current
    $('clock').textContent = `${clock(current)} / ${clock(duration)}`
    drawMap(current); drawFeed(current); drawScores(current); drawPlayers(current)
  }
  function frame (now) {
    if (!playing) return
    const dt = (now - last) / 1000
    last = now
    setTime(current + dt * Number($('speed').value))
    if (current >= duration) { playing = false; $('play').textContent = '▶ play'; return }
    requestAnimationFrame(frame)
  }
  $('play').addEventListener('click', () => {
    playing = !playing
    $('play').textContent = playing ? '⏸ pause' : '▶ play'
    if (playing) { if (current >= duration) setTime(0); last = performance.now(); requestAnimationFrame(frame) }
  })
  slider.addEventListener('input', () => setTime(slider.value))
  document.addEventListener('keydown', (e) => { if (e.key === ' ' && e.target === document.body) { e.preventDefault(); $('play').click() } })

  // For tests and the console: the state of the page.
  window.replay = {
    setTime,
    time: () => current,
    duration,
    markers: () => JSON.parse(JSON.stringify(shown)),
    visibleFeed: () => rows.filter(r => !r.hidden).map(r => [Number(r.dataset.t), r.textContent])
  }
  const start = Number((window.location.hash.match(/t=([0-9.]+)/) || [])[1] || 0)
  setTime(start)
})()
