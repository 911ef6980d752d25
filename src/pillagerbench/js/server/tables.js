'use strict'
// The rules of our Minecraft, as data. Plugins read these tables; nothing here runs.

// Block drops (vanilla 1.16/1.19 loot tables). count: [min, max] uniform (values below 0 clamp to 0, as
// vanilla's mushroom blocks: uniform -6..2 gives 0 with p=7/9, mean 1/3); bonus: [n, p] adds a
// binomial(n, p) to the count (loot function binomial_with_bonus_count: extra 3, p 0.5714286);
// chance: the drop happens with this probability. `ripe` = at the crop's maximum age (tables.GROWTH),
// `young` otherwise; sweet berry bushes list a rule per age (SweetBerryBushBlock.use: 1-2 berries
// at age 2, one more at age 3).
const BONUS = [3, 0.5714286]
const BLOCK_DROPS = {
  red_mushroom_block: [{ item: 'red_mushroom', count: [-6, 2] }],
  brown_mushroom_block: [{ item: 'brown_mushroom', count: [-6, 2] }],
  mushroom_stem: [],
  grass_block: [{ item: 'dirt', count: [1, 1] }],
  farmland: [{ item: 'dirt', count: [1, 1] }],
  melon: [{ item: 'melon_slice', count: [3, 7] }],
  sugar_cane: [{ item: 'sugar_cane', count: [1, 1] }],
  wheat: { ripe: [{ item: 'wheat', count: [1, 1] }, { item: 'wheat_seeds', count: [1, 1], bonus: BONUS }], young: [{ item: 'wheat_seeds', count: [1, 1] }] },
  carrots: { ripe: [{ item: 'carrot', count: [2, 2], bonus: BONUS }], young: [{ item: 'carrot', count: [1, 1] }] },
  potatoes: {
    ripe: [{ item: 'potato', count: [2, 2], bonus: BONUS }, { item: 'poisonous_potato', count: [1, 1], chance: 0.02 }],
    young: [{ item: 'potato', count: [1, 1] }]
  },
  beetroots: { ripe: [{ item: 'beetroot', count: [1, 1] }, { item: 'beetroot_seeds', count: [1, 1], bonus: BONUS }], young: [{ item: 'beetroot_seeds', count: [1, 1] }] },
  cocoa: { ripe: [{ item: 'cocoa_beans', count: [3, 3] }], young: [{ item: 'cocoa_beans', count: [1, 1] }] },
  sweet_berry_bush: { byAge: { 2: [{ item: 'sweet_berries', count: [1, 2] }], 3: [{ item: 'sweet_berries', count: [2, 3] }] }, young: [] },
  melon_stem: [{ item: 'melon_seeds', count: [0, 1] }],
  pumpkin_stem: [{ item: 'pumpkin_seeds', count: [0, 1] }],
  attached_melon_stem: [{ item: 'melon_seeds', count: [0, 1] }],
  attached_pumpkin_stem: [{ item: 'pumpkin_seeds', count: [0, 1] }]
}

// Crop growth by vanilla random ticks (plugins/crops.js). Each tick a section of 16x16x16 blocks gets
// `randomTickSpeed` random ticks at uniformly drawn positions, so a block gets randomTickSpeed / 4096
// random ticks per game tick. On its random tick a crop grows one step with its `chance`:
// 'crop' = CropBlock's 1 / (floor(25 / f) + 1), f its growth speed from the farmland around it
// (CropBlock.getGrowthSpeed); 'beetroot' = that, on 2 of 3 random ticks (BeetrootBlock.randomTick);
// a number = a fixed chance (CocoaBlock and SweetBerryBushBlock: 1 in 5; sugar cane: every tick, a new
// block after 16 of them, SugarCaneBlock). A ripe stem (age 7) tries, with the 'crop' chance, to grow
// its fruit on a random side (StemBlock.randomTick). A block with `attachedTo` is an attached stem: it
// turns back into a ripe stem as soon as its fruit is gone (AttachedStemBlock.updateShape).
const GROWTH = {
  wheat: { prop: 'age', max: 7, chance: 'crop' },
  carrots: { prop: 'age', max: 7, chance: 'crop' },
  potatoes: { prop: 'age', max: 7, chance: 'crop' },
  beetroots: { prop: 'age', max: 3, chance: 'beetroot' },
  cocoa: { prop: 'age', max: 2, chance: 0.2 },
  sweet_berry_bush: { prop: 'age', max: 3, chance: 0.2 },
  melon_stem: { prop: 'age', max: 7, chance: 'crop', fruit: 'melon', attached: 'attached_melon_stem' },
  pumpkin_stem: { prop: 'age', max: 7, chance: 'crop', fruit: 'pumpkin', attached: 'attached_pumpkin_stem' },
  attached_melon_stem: { attachedTo: 'melon', stem: 'melon_stem' },
  attached_pumpkin_stem: { attachedTo: 'pumpkin', stem: 'pumpkin_stem' },
  sugar_cane: { prop: 'age', max: 15, chance: 1, column: 3 }
}
const SECTION_BLOCKS = 4096

// Planting: item -> block it becomes and what it must stand on (or hang on, for cocoa).
const PLANTING = {
  wheat_seeds: { block: 'wheat', soil: ['farmland'] },
  carrot: { block: 'carrots', soil: ['farmland'] },
  potato: { block: 'potatoes', soil: ['farmland'] },
  beetroot_seeds: { block: 'beetroots', soil: ['farmland'] },
  melon_seeds: { block: 'melon_stem', soil: ['farmland'] },
  pumpkin_seeds: { block: 'pumpkin_stem', soil: ['farmland'] },
  sweet_berries: { block: 'sweet_berry_bush', soil: ['grass_block', 'dirt', 'coarse_dirt', 'podzol', 'farmland'] },
  // on sugar cane, or on soil with water beside it (SugarCaneBlock.canSurvive)
  sugar_cane: { block: 'sugar_cane', soil: ['grass_block', 'dirt', 'coarse_dirt', 'podzol', 'sand', 'red_sand', 'sugar_cane'], water: ['grass_block', 'dirt', 'coarse_dirt', 'podzol', 'sand', 'red_sand'] },
  cocoa_beans: { block: 'cocoa', side: ['jungle_log', 'jungle_wood'] }
}
const FRUIT_SOIL = ['farmland', 'dirt', 'grass_block', 'coarse_dirt', 'podzol']
const TILLABLE = ['grass_block', 'dirt', 'grass_path']
const HOES = ['wooden_hoe', 'stone_hoe', 'iron_hoe', 'golden_hoe', 'diamond_hoe', 'netherite_hoe']

// Smelting: input item -> output item, in smelting.json (Python's Random baseline reads it too:
// teams/random_team.py). Ticks per item and fuel burn ticks (vanilla numbers).
const SMELTING = require('./smelting.json')
const SMELT_TICKS = 200
const FUEL_TICKS = {
  coal: 1600,
  charcoal: 1600,
  coal_block: 16000,
  lava_bucket: 20000,
  blaze_rod: 2400,
  dried_kelp_block: 4000,
  stick: 100,
  bamboo: 50,
  oak_planks: 300,
  spruce_planks: 300,
  birch_planks: 300,
  jungle_planks: 300,
  oak_log: 300,
  spruce_log: 300,
  birch_log: 300,
  jungle_log: 300,
  crafting_table: 300,
  wooden_sword: 200,
  wooden_pickaxe: 200,
  wooden_axe: 200,
  wooden_shovel: 200,
  wooden_hoe: 200
}
// Fuel items that leave something behind in the fuel slot.
const FUEL_LEFTOVER = { lava_bucket: 'bucket' }

// Crafting ingredients that stay in the grid as another item.
const CRAFT_LEFTOVER = { milk_bucket: 'bucket', water_bucket: 'bucket', lava_bucket: 'bucket', honey_bottle: 'glass_bottle' }

// Mobs: health, loot.
const MOBS = {
  cow: { health: 10, loot: [{ item: 'beef', count: [1, 3] }, { item: 'leather', count: [0, 2] }] },
  chicken: { health: 4, loot: [{ item: 'chicken', count: [1, 1] }, { item: 'feather', count: [0, 2] }] },
  pig: { health: 10, loot: [{ item: 'porkchop', count: [1, 3] }] },
  sheep: { health: 8, loot: [{ item: 'mutton', count: [1, 2] }, { item: 'white_wool', count: [1, 1] }] }
}
// Attack damage by held item (vanilla 1.16 values); anything else does 1.
const ATTACK_DAMAGE = {
  wooden_sword: 4, golden_sword: 4, stone_sword: 5, iron_sword: 6, diamond_sword: 7, netherite_sword: 8,
  wooden_axe: 7, golden_axe: 7, stone_axe: 9, iron_axe: 9, diamond_axe: 9, netherite_axe: 10
}

// Item pickup (vanilla 1.16): a player picks up an item entity whose box touches the player's
// box grown by `reach` (Player.aiStep: getBoundingBox().inflate(1.0, 0.5, 1.0)), once the item's
// pickup delay has run out. Delays in game ticks, by what made the item: a broken block or a
// harvested bush (Block.popResource) and a killed mob's loot (Entity.spawnAtLocation) use the
// default delay, 10; a player's toss (Player.drop) 40.
const PICKUP = {
  player: { width: 0.6, height: 1.8 },
  item: { width: 0.25, height: 0.25 },
  reach: { horizontal: 1.0, vertical: 0.5 },
  delayTicks: { block: 10, mob: 10, toss: 40 }
}

// Fair play: vanilla 1.16.5's limits on what a survival player can do (docs/fair-play.md gives the
// source of each number). Distances are squared, as vanilla compares them.
const REACH = {
  // ServerPlayerGameMode.handleBlockBreakAction: from (feet + 1.5) to the block's centre, "too far" when > 36
  digEyeHeight: 1.5,
  digSq: 36,
  // ServerGamePacketListenerImpl.handleUseItemOn: from the feet to the clicked block's centre, only when < 64
  // (placing a block and using one: chests, furnaces, crafting tables, farmland with a hoe …)
  useBlockSq: 64,
  // ChestContainer / AbstractFurnaceContainer / WorkbenchContainer.stillValid, checked every tick: an open
  // window closes when the feet are farther than this from the container block's centre
  containerSq: 64,
  // ServerGamePacketListenerImpl.handleInteract: feet to the entity's position, only when < 36 (attack and use)
  entitySq: 36
}

// Digging: a block is broken only if the time since the player started digging it is at least this
// share of its dig time with the held tool (vanilla: destroy progress >= 0.7 at STOP_DESTROY_BLOCK).
// slackMs: a start and a finish packet handled in one turn of a busy server's event loop (bots in
// real time on a loaded machine) must not make an honest dig "too fast"; 3 ticks.
const DIG = { minProgress: 0.7, slackMs: 150 }

// Movement, checked on every position packet (plugins/movement.js). Vanilla's own check
// ("moved too quickly": squared distance of one packet, less the squared expected velocity, > 100)
// lets a client move up to 10 blocks a packet; ours is the tighter bound an honest client keeps.
// Honest figures (per 50 ms tick): sprint-jumping peaks near 0.6 blocks horizontally, a jump rises
// 0.42, a step up is 0.6, terminal falling speed is 3.92.
const MOVEMENT = {
  maxStep: 1.0, // blocks horizontally in one packet
  maxRise: 1.0, // blocks up in one packet
  maxFall: 4.0, // blocks down in one packet
  speed: 10, // blocks per second horizontally, averaged by a bucket that holds `burst` blocks
  burst: 10, // (a client catching up after a lag sends several ticks' moves at once)
  jumpHeight: 1.35, // highest rise above the last place it stood (a jump reaches 1.25)
  supportDepth: 0.6, // a player stands when a block with a collision box (or water, a ladder …) is within this below its feet
  hoverMs: 2000, // in the air without falling for longer: brought down (an honest jump rises for ~0.35 s)
  flyMs: 4000 // in the air for longer: brought down (vanilla kicks for flying after 80 ticks, 4 s)
}
// Blocks a player stands in or climbs without a collision box.
const SUPPORTING = ['water', 'lava', 'ladder', 'vine', 'scaffolding', 'cobweb', 'bubble_column', 'twisting_vines', 'weeping_vines', 'twisting_vines_plant', 'weeping_vines_plant']

// Placing: blocks a placed block may replace (vanilla's Material.isReplaceable()).
const REPLACEABLE = ['air', 'cave_air', 'void_air', 'water', 'lava', 'grass', 'fern', 'dead_bush', 'tall_grass', 'large_fern',
  'vine', 'snow', 'seagrass', 'tall_seagrass', 'fire', 'soul_fire', 'nether_sprouts', 'crimson_roots', 'warped_roots', 'structure_void']

// Attack speed (attacks per second at full strength) by held item, vanilla 1.16 (attribute
// generic.attack_speed: 4.0 base plus the item's modifier). The attack strength after t ticks since the
// last attack or item change is clamp((t + 0.5) / (20 / speed), 0, 1) and a hit does
// damage × (0.2 + 0.8 × strength²) (Player.getAttackStrengthScale, Player.attack).
const ATTACK_SPEED = {
  hand: 4.0,
  wooden_sword: 1.6, stone_sword: 1.6, iron_sword: 1.6, golden_sword: 1.6, diamond_sword: 1.6, netherite_sword: 1.6,
  wooden_axe: 0.8, stone_axe: 0.8, iron_axe: 0.9, golden_axe: 1.0, diamond_axe: 1.0, netherite_axe: 1.0,
  wooden_pickaxe: 1.2, stone_pickaxe: 1.2, iron_pickaxe: 1.2, golden_pickaxe: 1.2, diamond_pickaxe: 1.2, netherite_pickaxe: 1.2,
  wooden_shovel: 1.0, stone_shovel: 1.0, iron_shovel: 1.0, golden_shovel: 1.0, diamond_shovel: 1.0, netherite_shovel: 1.0,
  wooden_hoe: 1.0, stone_hoe: 2.0, iron_hoe: 3.0, golden_hoe: 1.0, diamond_hoe: 4.0, netherite_hoe: 4.0,
  trident: 1.1
}

// Player health (vanilla 1.16/1.19, peaceful difficulty as both scenarios; plugins/player_health.js):
// - regeneration: a living player below full health heals `amount` every `everyTicks` game ticks
//   (Player.aiStep, peaceful with naturalRegeneration);
// - hurt immunity: a player hurt at full damage is immune for `immuneTicks` ticks, when a further hit
//   does only what it exceeds the last one by (LivingEntity.hurt: invulnerableTime 20, checked > 10);
// - thorny blocks: a living player whose box overlaps the block (age > minAge) and that moved at least
//   `minMove` horizontally since the last tick takes `damage` (SweetBerryBushBlock.entityInside; the
//   slow-down it also applies is the client's, which vanilla does not check and mineflayer does not do).
const HEALTH = {
  max: 20,
  regeneration: { everyTicks: 20, amount: 1 },
  immuneTicks: 10,
  thorny: { sweet_berry_bush: { minAge: 0, damage: 1, minMove: 0.003 } }
}

module.exports = {
  HEALTH, PICKUP, BLOCK_DROPS, GROWTH, SECTION_BLOCKS, PLANTING, FRUIT_SOIL, TILLABLE, HOES, SMELTING, SMELT_TICKS, FUEL_TICKS,
  FUEL_LEFTOVER, CRAFT_LEFTOVER, MOBS, ATTACK_DAMAGE, REACH, DIG, MOVEMENT, SUPPORTING, REPLACEABLE, ATTACK_SPEED
}
