"""The task's solver under `-T team=agent` when `--solver` gives none: Inspect's `react()` agent with the
game's tools (tools.py). The sample's input is the briefing (the scenario's description and the team's
players, teams/tools/surface.py `briefing`). A game ends by time, not by an answer: no submit tool, and
the agent is told to go on (`on_continue`) until `status` says the run is over.
"""

from __future__ import annotations

from inspect_ai.agent import Agent, AgentPrompt, AgentState, react

from .tools import game_over, pillagerbench_tools

INSTRUCTIONS = """You play a team in a Minecraft game against another team, through tools. Each acting tool \
(run_code, wait, chat and the primitives such as mineBlock) is an action of one of your players, and takes \
game time; calls for different players in one turn run at the same time. `observe` shows what a player sees \
and holds, `status` the phase, the time left and the scores. The game may last several episodes: play each \
one to its end, and keep playing until `status` says the phase is "over". Think briefly before each turn \
about what your players should do next."""


async def until_over(state: AgentState) -> bool:
    """Go on (with Inspect's nudge when the model called no tool) until the run is over."""
    return not game_over()


def team_agent() -> Agent:
    """react() playing the team until the run is over."""
    return react(
        prompt=AgentPrompt(instructions=INSTRUCTIONS, assistant_prompt=None),
        tools=pillagerbench_tools(),
        submit=False,
        on_continue=until_over,
    )
