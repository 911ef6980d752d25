'use strict'
/* global document, window, requestAnimationFrame, performance */
// The replay page (written by `pillagerbench replay`, see docs/replays.md): a top-down map of the
// arena (map.js: players with facing and trail, items and mobs), a timeline, the chat and events feed and
// both teams' scores, all from the data embedded in the page as JSON (id "replay-data"). No network.

// ---- feed ----
// The feed's rows in `feed` (a click on one moves the time there) and drawFeed(t), which shows the rows up to t.
function replayFeed (D, feed, setTime) {
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
  return { rows, drawFeed }
}

// ---- scores ----
// drawScores(t): both sides' scores over the episode on `chart`, the cursor at t, the scores at t in `scoreNow`.
function scoresChart (D, chart, scoreNow, sideColour) {
  const cctx = chart.getContext('2d')
  const duration = D.duration
  return function drawScores (t) {
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
    scoreNow.textContent = Object.entries(D.sides).map(([k, s]) => `${k} ${s.team}: ${cur ? cur[k] : 0}`).join('   ')
  }
}

// ---- players panel ----
function drawPlayers (D, arena, body, t) {
  const { sampleAt, sideOf, sideColour } = arena
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

;(function () {
  const D = JSON.parse(document.getElementById('replay-data').textContent)
  const $ = (id) => document.getElementById(id)

  const arena = window.arenaMap(D, $('map'), $('legend')) // the map: js/replay/map.js
  const { rows, drawFeed } = replayFeed(D, $('feed'), setTime)
  const drawScores = scoresChart(D, $('scores'), $('score-now'), arena.sideColour)

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
    arena.draw(current); drawFeed(current); drawScores(current); drawPlayers(D, arena, $('players'), current)
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
    markers: arena.markers,
    map: arena,
    visibleFeed: () => rows.filter(r => !r.hidden).map(r => [Number(r.dataset.t), r.textContent])
  }
  const start = Number((window.location.hash.match(/t=([0-9.]+)/) || [])[1] || 0)
  setTime(start)
})()
