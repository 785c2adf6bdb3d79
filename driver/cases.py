"""One solver case: its parameters, its command line and its stable identifier."""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace


@dataclass(frozen=True)
class Case:
    """Every hertz.edp option; the defaults are hertz.edp's own."""

    model: str = "axi"
    method: str = "newton"
    order: int = 2
    n: int = 16
    L: float = 5000.0
    kpen: float = 1e5
    omega: float = 1.0
    E: float = 10.0
    nu: float = 0.3
    R: float = 0.5
    d: float = 0.02
    cont: int = 0
    maxit: int | None = None  # hertz.edp picks 50 (newton) or 2000 (fixedpoint)
    tol: float = 1e-8

    def args(self) -> list[str]:
        """Command-line options for hertz.edp, every one explicit."""
        out = []
        for f in fields(self):
            value = getattr(self, f.name)
            if value is None:
                continue
            out += [f"-{f.name}", _fmt(value)]
        return out

    @property
    def case_id(self) -> str:
        """Readable and unique: names the values that define the case."""
        parts = [self.model, self.method, f"P{self.order}", f"n{self.n}", f"L{_fmt(self.L)}",
                 f"k{_fmt(self.kpen)}", f"w{_fmt(self.omega)}", f"E{_fmt(self.E)}",
                 f"nu{_fmt(self.nu)}", f"R{_fmt(self.R)}", f"d{_fmt(self.d)}", f"c{self.cont}",
                 f"tol{_fmt(self.tol)}"]
        if self.maxit is not None:
            parts.append(f"it{self.maxit}")
        return "_".join(parts)

    def with_(self, **changes) -> "Case":
        return replace(self, **changes)

    def as_dict(self) -> dict:
        return asdict(self)

    @property
    def estar(self) -> float:
        return self.E / (1 - self.nu**2)

    @property
    def contact_scale(self) -> float:
        """The length hertz.edp sizes the mesh with: Hertz a for the sphere, the
        estimate of edp/lib/hertz.idp (planeHalfWidthEstimate) in plane strain."""
        if self.model == "axi":
            return math.sqrt(self.R * self.d)
        return math.sqrt(2 * self.R * self.d / (math.log(2 * self.L) - 0.1))

    def scaled_kpen(self, gamma: float) -> float:
        """kpen = gamma E*/h with h = a/n, the mesh-consistent penalty."""
        return gamma * self.estar * self.n / self.contact_scale


def _fmt(value) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)
