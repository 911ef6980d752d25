"""TactiCrafter (`tacticrafter`), the paper's multi-agent system: tactics module, causal model,
opponent model and one base agent per player, with memory across episodes and checkpoints.
See docs/tacticrafter.md; prompts are the .txt files in prompts/."""

from pillagerbench.teams.tacticrafter.team import TactiCrafter

__all__ = ["TactiCrafter"]
