"""One solver case: the hertz.edp options it sets, its label and its exact identifier.

A case names only the options it sets; hertz.edp supplies every other default,
so no default is copied here. Values travel at full precision (shortest exact
repr), and the identifier is built from the same text, so two different values
never share an id.
"""
from __future__ import annotations

import hashlib
import re
from dataclasses import dataclass, replace
from typing import Any

Value = int | float | str

# what a case id may hold as it is: every other character is %XX-escaped, so an
# id is one file name whatever the values (never a path, never . or ..)
_UNSAFE = re.compile(r"[^A-Za-z0-9._=+-]")


def exact(value: Value) -> str:
    """The shortest text that reads back as the same value."""
    if isinstance(value, bool):
        raise TypeError("booleans are not hertz.edp values")
    if isinstance(value, float):
        text = repr(value)
        return text[:-2] if text.endswith(".0") else text
    return str(value)


@dataclass(frozen=True)
class Case:
    """hertz.edp options (names without the dash) and the study's label for them."""

    params: tuple[tuple[str, Value], ...] = ()
    variant: str = ""            # the study's name for the series this case belongs to
    expect_converged: bool = True  # False for cases that probe where methods fail

    @classmethod
    def of(cls, **params: Value) -> Case:
        return cls(tuple(sorted(params.items())))

    def with_(self, **changes: Value) -> Case:
        """The same case with some options changed (or added)."""
        return replace(self, params=tuple(sorted((dict(self.params) | changes).items())))

    def labelled(self, variant: str, expect_converged: bool = True) -> Case:
        return replace(self, variant=variant, expect_converged=expect_converged)

    def get(self, name: str, default: Any = None) -> Any:
        return dict(self.params).get(name, default)

    def args(self) -> list[str]:
        """hertz.edp's command-line options for this case."""
        out: list[str] = []
        for name, value in self.params:
            out += [f"-{name}", exact(value)]
        return out

    @property
    def case_id(self) -> str:
        """Readable and exact: name=value pairs in name order ("defaults" for none).
        A safe file name: odd characters escaped; very long ids keep their start
        and a hash of the whole."""
        text = "_".join(f"{name}={exact(value)}" for name, value in self.params) or "defaults"
        text = _UNSAFE.sub(lambda m: "".join(f"%{b:02X}" for b in m.group().encode()), text)
        if len(text) > 150:
            text = text[:120] + "_" + hashlib.sha256(text.encode()).hexdigest()[:16]
        return text
