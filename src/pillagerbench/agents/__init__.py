"""Shared toolkit for LLM agents (CoT baseline, TactiCrafter): code blocks checked with a real
JavaScript parser (`code`), prompt templates (`prompts`), observations and events as prompt text
(`context`). See docs/agents.md."""

from pillagerbench.agents.code import (
    CodeError,
    JSParser,
    ParsedJS,
    Program,
    ProgramsResult,
    check_program,
    extract_code_blocks,
    parse_js,
    programs_from_answer,
)
from pillagerbench.agents.prompts import PromptError, PromptTemplate, load_prompts

__all__ = [
    "CodeError",
    "JSParser",
    "ParsedJS",
    "Program",
    "ProgramsResult",
    "PromptError",
    "PromptTemplate",
    "check_program",
    "extract_code_blocks",
    "load_prompts",
    "parse_js",
    "programs_from_answer",
]
