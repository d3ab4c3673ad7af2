"""Parameter values written as text: ``start:stop:num``, a comma list, or one number.

The one reader of such text, for the command line's flags (``--q -0.6:0.6:241``) and for the
``[grid]`` tables of atlas recipes (``q = "-0.45:0.45:361"``).
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..resources import check_memory

__all__ = ["parse_values"]


def parse_values(text: str, *, name: str = "value") -> float | np.ndarray:
    """Parse ``start:stop:num`` (``numpy.linspace``), a comma list, or one number.

    Raises
    ------
    ValueError
        With the flag name, the offending text and the accepted forms; also for a value that is
        not finite (``inf``, ``nan``, ``1e999``) in a range or a list (one number is left to the
        parameter checks, which name the parameter) and for ``start:stop:num`` whose points are not
        all finite doubles (``-1e308:1e308:3``: the step overflows), checked before numpy is
        asked, so no numpy warning is printed.
    """
    forms = "a number, a comma list (0,0.1,0.3) or start:stop:num (-0.6:0.6:241, num >= 1)"
    t = str(text).strip()
    if not t:
        raise InputError(f"{name} = {text!r} is empty; give {forms}")

    def number(part: str, finite: bool = True) -> float:
        try:
            v = float(part)
        except ValueError:
            raise InputError(f"{name} = {text!r}: {part.strip()!r} is not a number; give {forms}") from None
        if finite and not np.isfinite(v):
            raise InputError(
                f"{name} = {text!r}: {part.strip()!r} is not finite (it reads as {v}); {name} must be a finite number"
            )
        return v

    if ":" in t:
        parts = t.split(":")
        if len(parts) != 3:
            raise InputError(f"{name} = {text!r} has {len(parts)} fields; give {forms}")
        start, stop = number(parts[0]), number(parts[1])
        try:
            num = int(parts[2])
        except ValueError:
            raise InputError(
                f"{name} = {text!r}: the number of points {parts[2].strip()!r} is not an "
                "integer; give start:stop:num with num >= 1"
            ) from None
        if num < 1:
            raise InputError(f"{name} = {text!r}: the number of points is {num}; the allowed range is num >= 1")
        if num > 10**9:
            raise InputError(f"{name} = {text!r}: the number of points is {num}; the allowed range is num <= 1e9")
        if num > 1 and not np.isfinite((stop - start) / (num - 1)):
            raise InputError(
                f"{name} = {text!r}: the step (stop - start)/(num - 1) overflows a double; "
                f"{name} must have |stop - start| <= 1.7e308"
            )
        check_memory(8.0 * num, what=f"{name} = {text!r} ({num} values)", parameter=name, way_out="give fewer points")
        return np.linspace(start, stop, num)
    if "," in t:
        vals = [number(v) for v in t.split(",") if v.strip()]
        if not vals:
            raise InputError(f"{name} = {text!r} is empty; give {forms}")
        return np.array(vals)
    return number(t, finite=False)  # one number: the parameter check names it ("q = inf is not finite")
