'use strict'
// Crafting recipe matching against minecraft-data's recipes: shaped (also mirrored) and shapeless.
// A grid is an array of item ids (or null) of size width*height, row-major.

function trim (grid, width) {
  const height = grid.length / width
  let minX = width; let maxX = -1; let minY = height; let maxY = -1
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      if (grid[y * width + x] != null) {
        minX = Math.min(minX, x); maxX = Math.max(maxX, x); minY = Math.min(minY, y); maxY = Math.max(maxY, y)
      }
    }
  }
  if (maxX < 0) return null
  const rows = []
  for (let y = minY; y <= maxY; y++) rows.push(grid.slice(y * width + minX, y * width + maxX + 1))
  return rows
}

function trimShape (shape) {
  const width = Math.max(...shape.map(r => r.length))
  const flat = []
  for (const row of shape) for (let x = 0; x < width; x++) flat.push(row[x] ?? null)
  return trim(flat, width)
}

const sameRows = (a, b) => a.length === b.length && a.every((row, y) => row.length === b[y].length && row.every((v, x) => (v ?? null) === (b[y][x] ?? null)))

function shapedMatches (recipe, rows) {
  const shape = trimShape(recipe.inShape)
  if (!shape) return false
  return sameRows(shape, rows) || sameRows(shape.map(r => [...r].reverse()), rows)
}

function shapelessMatches (recipe, ids) {
  if (recipe.ingredients.length !== ids.length) return false
  const want = [...recipe.ingredients].sort((a, b) => a - b)
  const got = [...ids].sort((a, b) => a - b)
  return want.every((v, i) => v === got[i])
}

// Returns the matching recipe ({result: {id, count}, ...}) or null. Grid side 2 or 3.
function matchRecipe (recipesByResult, grid, width) {
  const rows = trim(grid, width)
  if (!rows) return null
  const ids = grid.filter(v => v != null)
  for (const list of Object.values(recipesByResult)) {
    for (const recipe of list) {
      if (recipe.inShape ? shapedMatches(recipe, rows) : shapelessMatches(recipe, ids)) {
        if (recipe.inShape && (recipe.inShape.length > width || recipe.inShape.some(r => r.length > width))) continue
        return recipe
      }
    }
  }
  return null
}

// Index by first ingredient to avoid scanning all 500+ recipes per click.
function indexRecipes (recipesByResult) {
  const byIngredient = new Map()
  for (const list of Object.values(recipesByResult)) {
    for (const recipe of list) {
      const ids = recipe.inShape ? recipe.inShape.flat().filter(v => v != null) : recipe.ingredients
      const key = Math.min(...ids)
      if (!byIngredient.has(key)) byIngredient.set(key, [])
      byIngredient.get(key).push(recipe)
    }
  }
  return (grid, width) => {
    const ids = grid.filter(v => v != null)
    if (!ids.length) return null
    return matchRecipe({ candidates: byIngredient.get(Math.min(...ids)) || [] }, grid, width)
  }
}

module.exports = { matchRecipe, indexRecipes, trim }
