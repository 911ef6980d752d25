"""PillagerBench: competitive team-vs-team Minecraft scenarios for LLM multi-agent systems."""

__version__ = "0.1.0"
