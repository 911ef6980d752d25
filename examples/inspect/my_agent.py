"""An Inspect agent as PillagerBench's team (docs/inspect.md, "An Inspect agent as the team"):

    inspect eval pillagerbench/mushroom_war -T team=agent --solver examples/inspect/my_agent.py --model openai/gpt-4o

Inspect's react() loop with the game's tools (one per player action, observe, status), told to plan for
both players each turn; it plays until the run is over or one of Inspect's limits ends it.
"""

from inspect_ai.agent import Agent, AgentPrompt, AgentState, agent, react

from pillagerbench.inspect_tasks.tools import game_over, pillagerbench_tools

PLAN = """You command a Minecraft team through tools: the message below says the game, your team and its \
players. Each turn, first `observe` what changed, then give every player one action in the same turn \
(their calls run at once). Keep going until `status` says the phase is "over"."""


async def keep_playing(state: AgentState) -> bool | str:
    if game_over():
        return False
    if not state.output.message.tool_calls:
        return "The game goes on: give your players their next actions."
    return True


@agent
def my_agent() -> Agent:
    return react(
        prompt=AgentPrompt(instructions=PLAN, assistant_prompt=None),
        tools=pillagerbench_tools(),
        submit=False,
        on_continue=keep_playing,
    )
