"""One registry type for every kind of named thing a configuration chooses: scenarios, teams,
scorings, experiment designs, match parts, LLM presets, layout splits. Each is a read-only mapping
from name to item, filled once where its items are defined, and every lookup by a name that is not
there fails in the same words (`unknown team 'cott'; known: aggressive, balanced, ...`;
`config.unknown`), in the manner of lm-evaluation-harness's `Registry`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping
from contextlib import contextmanager
from typing import TypeVar, overload

from pillagerbench.config.compose import ConfigError, unknown

T = TypeVar("T")


class Registry(Mapping[str, T]):
    """Named items of one kind, in the order they were registered."""

    def __init__(self, kind: str, items: Mapping[str, T] | None = None, hint: str = "") -> None:
        self.kind, self.hint = kind, hint  # hint: what else a name may be, said after the known ones
        self._items: dict[str, T] = {}
        for name, item in (items or {}).items():
            self.register(name, item)

    @overload
    def register(self, name: str) -> Callable[[T], T]: ...

    @overload
    def register(self, name: str, item: T) -> T: ...

    def register(self, name: str, item: T | None = None) -> T | Callable[[T], T]:
        """Add an item under a name (or, without an item, a decorator that adds what it decorates).
        A name registered twice is a programming error: the first item is never silently replaced."""
        if item is None:
            return lambda it: self.register(name, it)
        if name in self._items and self._items[name] is not item:
            raise ValueError(f"two {self.kind}s are registered under the name {name!r}")
        self._items[name] = item
        return item

    @contextmanager
    def registered(self, name: str, item: T) -> Iterator[T]:
        """An item under a name for the length of a `with` block (a test's own team), then gone."""
        self.register(name, item)
        try:
            yield item
        finally:
            del self._items[name]

    def find(self, name: object, also: Iterable[str] = ()) -> T:
        """The item of that name; a ConfigError in the one form, naming every known name (with
        `also`: names found elsewhere, such as installed entry points), sorted, otherwise."""
        if isinstance(name, str) and name in self._items:
            return self._items[name]
        raise self.unknown(name, also)

    def unknown(self, name: object, also: Iterable[str] = ()) -> ConfigError:
        return unknown(self.kind, name, sorted({*self._items, *also}), self.hint)

    def names(self) -> list[str]:
        return list(self._items)

    def __getitem__(self, name: str) -> T:
        return self._items[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __repr__(self) -> str:
        return f"Registry({self.kind!r}, {self.names()})"
