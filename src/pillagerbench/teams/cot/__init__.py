"""The Chain-of-Thought baseline team (`cot`); prompts are the .txt files in this folder."""

from pillagerbench.teams.cot.team import ChainOfThought

__all__ = ["ChainOfThought"]
