"""Parameter values written as text: ``start:stop:num``, a comma list, or one number.

The one reader of such text, for the command line's flags (``--q -0.6:0.6:241``) and for the
``[grid]`` tables of atlas recipes (``q = "-0.45:0.45:361"``).
"""

from __future__ import annotations

import numpy as np

__all__ = ["parse_values"]


def parse_values(text: str, *, name: str = "value") -> float | np.ndarray:
    """Parse ``start:stop:num`` (``numpy.linspace``), a comma list, or one number.

    Raises
    ------
    ValueError
        With the flag name, the offending text and the accepted forms.
    """
    forms = "a number, a comma list (0,0.1,0.3) or start:stop:num (-0.6:0.6:241, num >= 1)"
    t = str(text).strip()
    if not t:
        raise ValueError(f"{name} = {text!r} is empty; give {forms}")

    def number(part: str) -> float:
        try:
            return float(part)
        except ValueError:
            raise ValueError(f"{name} = {text!r}: {part.strip()!r} is not a number; give {forms}") from None

    if ":" in t:
        parts = t.split(":")
        if len(parts) != 3:
            raise ValueError(f"{name} = {text!r} has {len(parts)} fields; give {forms}")
        start, stop = number(parts[0]), number(parts[1])
        try:
            num = int(parts[2])
        except ValueError:
            raise ValueError(f"{name} = {text!r}: the number of points {parts[2].strip()!r} is not an "
                             "integer; give start:stop:num with num >= 1") from None
        if num < 1:
            raise ValueError(f"{name} = {text!r}: the number of points is {num}; the allowed range is num >= 1")
        if num > 10**9:
            raise ValueError(f"{name} = {text!r}: the number of points is {num}; the allowed range is num <= 1e9")
        return np.linspace(start, stop, num)
    if "," in t:
        vals = [number(v) for v in t.split(",") if v.strip()]
        if not vals:
            raise ValueError(f"{name} = {text!r} is empty; give {forms}")
        return np.array(vals)
    return number(t)
