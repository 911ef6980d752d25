"""`pillagerbench try scenario=mushroom_war player=Ryn code=FILE.js`: run agent code by hand.

Builds the scenario's arena on a fresh server (a flat arena when the scenario cannot be built),
logs the player in at its spawn, runs the file as that player's code and prints every event as one
JSON line as it happens, ending with the `observe` event. Exits 1 (with the error on stderr) when
the code failed, 2 on bad arguments.

Options (key=value): scenario, player, code (a file, or - for stdin), layout (paper, a seed or a
layout file, as `run` takes it: docs/layouts.md; default paper), timeout (seconds, default 120),
inventory (JSON object, e.g. inventory='{"bread": 2}'), pos (x,y,z), full=true (print every event's
whole state, not only the final observe), log_dir.
"""

from __future__ import annotations

import asyncio
import json
import sys
from pathlib import Path

from pillagerbench.config.compose import ConfigError
from pillagerbench.players.player import Player, PlayerError
from pillagerbench.scenarios import SCENARIOS, Scenario, make_scenario
from pillagerbench.scenarios.layout import PAPER, LayoutKey, parse_layout
from pillagerbench.server import ArenaServer

USAGE = (
    "usage: pillagerbench try scenario=mushroom_war player=Ryn code=FILE.js [layout=paper|SEED|FILE.json] "
    "[timeout=120] [inventory='{...}'] [pos=x,y,z] [full=true]"
)


def parse_args(argv: list[str]) -> dict[str, str]:
    out: dict[str, str] = {}
    for arg in argv:
        if "=" not in arg:
            raise ValueError(f"expected key=value, got {arg!r}")
        k, v = arg.split("=", 1)
        out[k.strip().lstrip("+")] = v
    unknown = set(out) - {"scenario", "player", "code", "layout", "timeout", "inventory", "pos", "full", "log_dir"}
    if unknown:
        raise ValueError(f"unknown option(s) {', '.join(sorted(unknown))}")
    if "code" not in out:
        raise ValueError("code=FILE.js is required")
    return out


def load_scenario(key: str, layout: LayoutKey = PAPER) -> Scenario | None:
    """The registered scenario `key` (scenarios.SCENARIOS) on `layout`, or None when there is none by
    that name (a layout then has nothing to lay out: ConfigError)."""
    if key not in SCENARIOS:
        if layout != PAPER:
            raise ConfigError(
                f"layout={layout}: scenario {key!r} has no layouts; valid scenarios: {', '.join(SCENARIOS)}"
            )
        return None
    return make_scenario(key, layout=layout)


async def _main(opts: dict[str, str], scenario: Scenario | None) -> int:
    scenario_key = opts.get("scenario", "mushroom_war")
    player_name = opts.get("player", "Ryn")
    code_arg = opts["code"]
    code = sys.stdin.read() if code_arg == "-" else Path(code_arg).read_text(encoding="utf-8")
    timeout = float(opts.get("timeout", 120))
    inventory = json.loads(opts["inventory"]) if "inventory" in opts else {}
    full = opts.get("full", "false").lower() in ("1", "true", "yes")

    spawn = None
    primitives = None
    if scenario is not None:
        for spec in scenario.all_players():
            if spec.name == player_name:
                spawn = tuple(spec.spawn)
        primitives = list(scenario.primitives or []) or None
    if "pos" in opts:
        spawn = tuple(float(v) for v in opts["pos"].split(","))
    if spawn is None:
        print(
            f"pillagerbench try: no player {player_name!r} in scenario {scenario_key!r}; give pos=x,y,z",
            file=sys.stderr,
        )
        return 2

    def show(event: list) -> None:
        kind, data = event
        line = event if (full or kind == "observe") else [kind, data.get(kind)]
        print(json.dumps(line), flush=True)

    async with ArenaServer() as server:
        built = False
        if scenario is not None:
            try:
                await scenario.arena.build(server)
                built = True
            except Exception as exc:  # noqa: BLE001 - a flat arena still lets the code run
                print(
                    f"pillagerbench try: could not build the {scenario_key} arena ({exc}); using a flat arena",
                    file=sys.stderr,
                )
        if not built:
            print(f"pillagerbench try: flat arena ({scenario_key} not built)", file=sys.stderr)
        assert server.port is not None  # the server has started
        player = Player(
            player_name,
            server.port,
            server=server,
            primitives=primitives,
            log_dir=Path(opts["log_dir"]) if "log_dir" in opts else None,
        )
        try:
            await player.start()
            await player.reset(position=spawn, inventory=inventory)
            events = await player.run(code, timeout=timeout, on_event=show)
        finally:
            await player.close()
    errs = [e[1].get("onError") for e in events if e[0] == "onError"]
    if errs:
        print(f"pillagerbench try: the code failed: {errs[0]}", file=sys.stderr)
        return 1
    return 0


def main(argv: list[str]) -> int:
    if argv and argv[0] in ("-h", "--help", "help"):
        print(USAGE + "\n\n" + (__doc__ or ""))
        return 0
    try:
        opts = parse_args(argv)
    except ValueError as exc:
        print(f"pillagerbench try: {exc}\n{USAGE}", file=sys.stderr)
        return 2
    try:
        scenario = load_scenario(opts.get("scenario", "mushroom_war"), parse_layout(opts.get("layout", PAPER)))
        return asyncio.run(_main(opts, scenario))
    except (OSError, json.JSONDecodeError, PlayerError, ConfigError) as exc:
        print(f"pillagerbench try: {exc}", file=sys.stderr)
        return 2
