"""Typed methods held to a declaration of ops (the control channel's, js/server/control_ops.json, and the
bot's, js/bot/bot_protocol.json): each method named as its op, its parameters named as the op's
arguments on the wire (`from_` for `from`) with the declared annotations, an optional one defaulting to
None, and the declared answer."""

from __future__ import annotations

import inspect
from collections.abc import Callable, Collection

from pillagerbench.server.seams import OpSpec


def typed_methods(cls: type, not_ops: Collection[str]) -> dict[str, Callable]:
    """The typed op methods of a class (inherited ones too): its public coroutines but `not_ops`."""
    return {
        n: getattr(cls, n)
        for n in dir(cls)
        if not n.startswith("_") and n not in not_ops and inspect.iscoroutinefunction(getattr(cls, n))
    }


def annotation(spec: OpSpec, arg: str, types: dict[str, dict[str, str]]) -> str:
    python = types[spec.args[arg]]["python"]
    return f"{python} | None" if arg in spec.optional else python


def method_problems(
    name: str,
    method: Callable,
    spec: OpSpec,
    types: dict[str, dict[str, str]],
    *,
    not_wire: Collection[str] = (),
    answers: str | None = None,
) -> list[str]:
    """How one typed method differs from its op's declaration. `not_wire`: parameters that are not
    arguments on the wire (a reply's wait); `answers`: the method's answer when it is not the declared
    result's (a line posted without waiting for its answer: "None")."""
    problems = []
    signature = inspect.signature(method)
    params = {p.name.removesuffix("_"): p for p in list(signature.parameters.values())[1:] if p.name not in not_wire}
    if params.keys() != spec.args.keys():
        problems.append(f"{name}: arguments {sorted(params)}, declared {sorted(spec.args)}")
    for arg in params.keys() & spec.args.keys():
        p = params[arg]
        if (p.default is None) != (arg in spec.optional) or p.default not in (None, inspect.Parameter.empty):
            problems.append(f"{name}: argument {arg} is {'optional' if arg in spec.optional else 'required'}")
        if p.annotation != annotation(spec, arg, types):
            problems.append(f"{name}: argument {arg} is {p.annotation}, declared {annotation(spec, arg, types)}")
    result = answers or types[spec.result]["python"]
    if signature.return_annotation != result:
        problems.append(f"{name}: answers {signature.return_annotation}, declared {result}")
    return problems
