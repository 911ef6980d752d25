"""An OpenAI Agents SDK agent as PillagerBench's team, through Inspect's agent bridge (docs/inspect.md):

    pip install openai-agents
    inspect eval pillagerbench/mushroom_war -T team=agent --solver examples/inspect/openai_agents_team.py --model openai/gpt-4o

The SDK's agent calls the model "inspect" (the bridge sends it to the evaluation's model) and the game's
tools as its own function tools, each answered by the sample's seat.
"""

import json

from inspect_ai.agent import Agent, AgentState, agent, agent_bridge
from inspect_ai.model import messages_to_openai_responses
from openai import AsyncOpenAI

from agents import Agent as SdkAgent
from agents import FunctionTool, OpenAIResponsesModel, RunContextWrapper, Runner
from pillagerbench.inspect_tasks.tools import current_seat, game_over
from pillagerbench.teams.tools import Seat, ToolSpec


def function_tool(seat: Seat, spec: ToolSpec) -> FunctionTool:
    async def invoke(context: RunContextWrapper, arguments: str) -> str:
        result = await seat.call(spec.name, json.loads(arguments or "{}"))
        return f"error: {result.text}" if result.error else result.text

    return FunctionTool(
        name=spec.name,
        description=spec.description,
        params_json_schema=spec.parameters,
        on_invoke_tool=invoke,
        strict_json_schema=False,  # the game's schemas have optional arguments
    )


@agent
def openai_agents_team() -> Agent:
    async def execute(state: AgentState) -> AgentState:
        seat = current_seat()
        team = SdkAgent(
            name="team",
            instructions="Play the game below through the tools until `status` says the phase is over.",
            tools=[function_tool(seat, spec) for spec in seat.tools],
            # the model "inspect" is the evaluation's: the bridge answers, no OpenAI key is used
            model=OpenAIResponsesModel("inspect", AsyncOpenAI(api_key="unused")),
        )
        async with agent_bridge(state) as bridge:
            conversation = await messages_to_openai_responses(state.messages)
            while not game_over():
                result = await Runner.run(team, conversation, max_turns=1000)
                conversation = result.to_input_list() + [{"role": "user", "content": "The game goes on."}]
            return bridge.state

    return execute
