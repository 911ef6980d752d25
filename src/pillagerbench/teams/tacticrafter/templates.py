"""TactiCrafter's prompt files (prompts/*.txt, `$placeholder` templates; see docs/agents.md)."""

from __future__ import annotations

from pathlib import Path

from pillagerbench.agents.prompts import load_prompts

PROMPTS = load_prompts(Path(__file__).parent / "prompts")
