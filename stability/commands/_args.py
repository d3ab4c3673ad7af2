"""Shared argument parsing for the ``tippe`` subcommands: the parameter flags and their help
(their values are read by :func:`stability.grids.ranges.parse_values`, which recipes use too),
and the help of ``--model``."""

from __future__ import annotations

import argparse
from collections.abc import Iterable

from ..grids.ranges import parse_values
from ..parameters import DEFAULT_MU, DOMAIN

__all__ = ["add_parameter_flags", "parameter_values", "parameter_help", "add_model_flag", "FLAGS",
           "PARAMETER_HELP"]


#: parameter name -> CLI flag
FLAGS = {"q": "--q", "fr_inv": "--fr-inv", "sigma": "--sigma", "alpha_v": "--alpha-v", "mu": "--mu"}

#: what each parameter is, with its unit (docs/conventions.md); the physical domain is added
#: from :data:`stability.parameters.DOMAIN` by :func:`parameter_help`
PARAMETER_HELP: dict[str, str] = {
    "q": "centre-of-mass offset q, units of R (G = O + q R k; q < 0: G below the centre O)",
    "fr_inv": "inverse Froude number g / (Omega^2 R), ~ 1/spin^2",
    "sigma": "inertia ratio sigma = C / A0 (axial / transverse about O)",
    "alpha_v": "viscous friction alpha_v = mu mu_v g / Omega (eq. 7)",
    "alpha_k": "Coulomb friction alpha_k = mu Fr^-1 mu_K (eq. 7)",
    "mu": "scaled mass mu = M R^2 / A0",
}

_VALUES = {"values": "a number, a comma list, or start:stop:num", "value": "a number"}


def parameter_help(name: str, *, kind: str = "value", extra: str = "") -> str:
    """The help of a parameter flag: what it is, its unit, its physical domain (``DOMAIN``)."""
    domain = " and ".join(b.text for b in DOMAIN if b.parameter == name)
    text = f"{PARAMETER_HELP[name]}; {domain}" if domain else PARAMETER_HELP[name]
    return f"{text}{extra}: {_VALUES[kind]}".replace("%", "%%")


def add_parameter_flags(p: argparse.ArgumentParser | argparse._ArgumentGroup, names: Iterable[str], *,
                        required: Iterable[str] = (), kind: str = "values",
                        defaults: dict[str, object] | None = None,
                        extra: dict[str, str] | None = None) -> None:
    """Add ``--q``, ``--fr-inv``, ... with their help (what, unit, domain, default).

    Parameters
    ----------
    p : argparse parser or group
    names : iterable of str
        Parameter names (keys of :data:`PARAMETER_HELP`).
    required : iterable of str
        The names whose flag is required.
    kind : {"values", "value"}
        ``"values"``: a number, a comma list or a range (read later by :func:`parameter_values`);
        ``"value"``: one float.
    defaults : dict, optional
        Default per name (``mu`` defaults to :data:`stability.parameters.DEFAULT_MU`, the
        others to None: not given).
    extra : dict, optional
        Text added to a name's help (e.g. which model needs it).
    """
    required = tuple(required)
    defaults = {"mu": DEFAULT_MU, **(defaults or {})}
    for name in names:
        flag = FLAGS.get(name, "--" + name.replace("_", "-"))
        p.add_argument(flag, dest=name, metavar="VALUES" if kind == "values" else "VALUE",
                       type=float if kind == "value" else None, required=name in required,
                       default=defaults.get(name),
                       help=parameter_help(name, kind=kind, extra=(extra or {}).get(name, ""))
                       + ("; required" if name in required else ""))


def add_model_flag(p: argparse.ArgumentParser, models: Iterable[str], default: str = "sliding", *,
                   what: str = "linear model", deprecated: dict[str, str] | None = None) -> None:
    """``--model`` with its choices and default listed in the help; ``deprecated`` (old name ->
    new name) are accepted too (the library warns) and named as such."""
    models = list(models)
    deprecated = deprecated or {}
    old = "; ".join(f"{o}: deprecated name of {n}" for o, n in deprecated.items())
    p.add_argument("--model", choices=[*models, *deprecated], default=default, metavar="MODEL",
                   help=f"{what}: {', '.join(models)}" + (f" ({old})" if old else ""))


def parameter_values(args: argparse.Namespace, names: tuple[str, ...]) -> dict[str, object]:
    """Parsed values of the parameter flags that were given."""
    out: dict[str, object] = {}
    for name in names:
        v = getattr(args, name, None)
        if v is None:
            continue
        out[name] = parse_values(v, name=FLAGS[name]) if isinstance(v, str) else v
    return out


# --- a real top in SI units (issue 23; a minimal form, to be unified with the other commands') ---
TOP_FIELDS = ("mass", "radius", "com_offset", "inertia_transverse", "inertia_axial")
_TOP_FIELD_HELP = {"mass": "mass M, kg", "radius": "radius R of the sphere, m",
                   "com_offset": "offset d of G from the sphere's centre along the axis, m (d < 0: G below O)",
                   "inertia_transverse": "transverse moment of inertia about G, kg m^2",
                   "inertia_axial": "axial moment of inertia C, kg m^2"}


def add_top_arguments(parser: argparse.ArgumentParser) -> None:
    """``--preset`` or ``--mass --radius --com-offset --inertia-transverse --inertia-axial``
    ``[--g --mu-v --mu-k]``: a top in SI units (:func:`top_from_args`)."""
    g = parser.add_argument_group("the top, SI units (or --preset)")
    g.add_argument("--preset", choices=["table1", "table1_measured"],
                   help="the paper's toy top: table1 (q = -0.1, mu = 2.28, sigma = 1) or table1_measured")
    for name in TOP_FIELDS:
        g.add_argument("--" + name.replace("_", "-"), dest=name, type=float, metavar="VALUE",
                       help=_TOP_FIELD_HELP[name])
    g.add_argument("--g", dest="gravity", type=float, metavar="M/S2", help="gravity (default 9.80665)")
    g.add_argument("--mu-v", dest="mu_v", type=float, metavar="S/M",
                   help="viscous friction coefficient mu_v, s/m (alpha_v = mu mu_v g / Omega, eq. 7)")
    g.add_argument("--mu-k", dest="mu_k", type=float, metavar="COEFF", help="Coulomb friction coefficient mu_K")


def top_from_args(args: argparse.Namespace, command: str):
    """The :class:`stability.Top` of :func:`add_top_arguments`' flags."""
    from ..top import Top

    given = [n for n in (*TOP_FIELDS, "gravity") if getattr(args, n) is not None]
    if args.preset:
        if given:
            raise ValueError(f"--preset {args.preset} and {', '.join('--' + n.replace('_', '-') for n in given)} "
                             "conflict: give a preset or the top's SI data, not both")
        return getattr(Top, args.preset)(mu_v=args.mu_v, mu_k=args.mu_k)
    missing = [n for n in TOP_FIELDS if getattr(args, n) is None]
    if missing:
        raise ValueError(f"{command} needs --preset or " + ", ".join("--" + n.replace("_", "-") for n in missing))
    return Top(*(getattr(args, n) for n in TOP_FIELDS), g=9.80665 if args.gravity is None else args.gravity,
               mu_v=args.mu_v, mu_k=args.mu_k)
