'use strict'
/* global document, window */
// A page with only the map (replay/map_page.py; `pillagerbench layout show`): the world at one
// moment, drawn by map.js from the data embedded in the page as JSON (id "replay-data"). No network.
;(function () {
  const D = JSON.parse(document.getElementById('replay-data').textContent)
  const arena = window.arenaMap(D, document.getElementById('map'), document.getElementById('legend'))
  arena.draw(0)
  window.replay = { map: arena, markers: arena.markers } // for tests and the console
})()
