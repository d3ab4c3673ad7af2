"""Shared argument parsing for the ``tippe`` subcommands: the parameter flags and their help
(their values are read by :func:`stability.grids.ranges.parse_values`, which recipes use too),
and the help of ``--model``."""

from __future__ import annotations

import argparse
from collections.abc import Iterable

from ..grids.ranges import parse_values
from ..parameters import DEFAULT_MU, DOMAIN

__all__ = [
    "FLAGS",
    "PARAMETER_HELP",
    "TOP_FLAGS",
    "add_float_flags",
    "add_model_flag",
    "add_output_flags",
    "add_parameter_flags",
    "add_state_flags",
    "add_top_arguments",
    "apply_top",
    "comma_floats",
    "flag_of",
    "lo_hi",
    "output_path",
    "parameter_help",
    "parameter_values",
    "required_top",
    "top_from_args",
    "top_parameters",
    "write_output",
]


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


def flag_of(name: str) -> str:
    """The flag of a parameter or option: ``fr_inv`` -> ``--fr-inv``; ``g`` (``gravity``) -> ``--g``,
    ``top_file`` -> ``--top``."""
    return {"gravity": "--g", "top_file": "--top"}.get(name) or "--" + name.replace("_", "-")


_VALUES = {"values": "a number, a comma list, or start:stop:num", "value": "a number"}


def parameter_help(name: str, *, kind: str = "value", extra: str = "") -> str:
    """The help of a parameter flag: what it is, its unit, its physical domain (``DOMAIN``)."""
    domain = " and ".join(b.text for b in DOMAIN if b.parameter == name)
    text = f"{PARAMETER_HELP[name]}; {domain}" if domain else PARAMETER_HELP[name]
    return f"{text}{extra}: {_VALUES[kind]}".replace("%", "%%")


def add_parameter_flags(
    p: argparse.ArgumentParser | argparse._ArgumentGroup,
    names: Iterable[str],
    *,
    kind: str = "values",
    unless_top: Iterable[str] = (),
    extra: dict[str, str] | None = None,
) -> None:
    """Add ``--q``, ``--fr-inv``, ... with their help (what, unit, domain, default).

    A flag not given is None: ``mu`` then takes :data:`stability.parameters.DEFAULT_MU`
    (:func:`apply_top`, which also fills the parameters a top gives), as its help says.

    Parameters
    ----------
    p : argparse parser or group
    names : iterable of str
        Parameter names (keys of :data:`PARAMETER_HELP`).
    kind : {"values", "value"}
        ``"values"``: a number, a comma list or a range (read later by :func:`parameter_values`);
        ``"value"``: one float.
    unless_top : iterable of str
        The names whose flag is required unless a top is given (said in their help).
    extra : dict, optional
        Text added to a name's help (e.g. which model needs it), instead of the default.
    """
    required = " (required unless a top is given)"
    extra = {"mu": f" (default {DEFAULT_MU})", **dict.fromkeys(unless_top, required), **(extra or {})}
    for name in names:
        p.add_argument(
            flag_of(name),
            dest=name,
            metavar="VALUES" if kind == "values" else "VALUE",
            type=float if kind == "value" else None,
            default=None,
            help=parameter_help(name, kind=kind, extra=extra.get(name, "")),
        )


def add_model_flag(
    p: argparse.ArgumentParser,
    models: Iterable[str],
    default: str = "sliding",
    *,
    what: str = "linear model",
    deprecated: dict[str, str] | None = None,
) -> None:
    """``--model`` with its choices and default listed in the help; ``deprecated`` (old name ->
    new name) are accepted too (the library warns) and named as such."""
    models = list(models)
    deprecated = deprecated or {}
    old = "; ".join(f"{o}: deprecated name of {n}" for o, n in deprecated.items())
    p.add_argument(
        "--model",
        choices=[*models, *deprecated],
        default=default,
        metavar="MODEL",
        help=f"{what}: {', '.join(models)}" + (f" ({old})" if old else ""),
    )


def output_path(args: argparse.Namespace):  # -> Path | None
    """``--output`` checked before anything is computed (:func:`stability.files.check_output_path`),
    or None when not given."""
    from ..files import check_output_path

    return check_output_path(args.output, overwrite=args.overwrite) if args.output else None


def write_output(dataset, out, args: argparse.Namespace) -> None:
    """Write ``dataset`` (or what a callable returns: built only when written) to the checked
    path ``out`` of :func:`output_path` and say so; nothing when ``out`` is None."""
    from ..grids.netcdf import write_dataset

    if out is not None:
        write_dataset(dataset() if callable(dataset) else dataset, out, overwrite=args.overwrite)
        print(f"wrote {out}")


def add_output_flags(
    p: argparse.ArgumentParser,
    help: str,
    *,
    required: bool = False,
    overwrite: str = "replace an existing output file (default: refuse)",
) -> None:
    """``-o/--output FILE.nc`` (``help`` says what is written) and ``--overwrite``."""
    p.add_argument("-o", "--output", required=required, default=None, metavar="FILE.nc", help=help)
    p.add_argument("--overwrite", action="store_true", help=overwrite)


def add_float_flags(p: argparse.ArgumentParser | argparse._ArgumentGroup, *rows: tuple) -> None:
    """Options that take one number: each row ``(flag, default, metavar, help)``."""
    for flag, default, metavar, text in rows:
        p.add_argument(flag, type=float, default=default, metavar=metavar, help=text)


def comma_floats(text: str) -> list[float]:
    """A comma list of numbers (``--omega 0,0,1``), or an argparse error naming the text."""
    try:
        return [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a comma list of numbers") from None


def add_state_flags(p: argparse.ArgumentParser, *, omega: str, k: str, velocity: str) -> None:
    """The initial state as comma lists: ``--omega`` and ``--k`` (required), ``--velocity``."""
    for flag, metavar, text, required in (
        ("--omega", "W1,W2,W3", omega + "; required", True),
        ("--k", "K1,K2,K3", k + "; required", True),
        ("--velocity", "V1,V2", velocity, False),
    ):
        p.add_argument(flag, type=comma_floats, required=required, default=None, metavar=metavar, help=text)


def parameter_values(args: argparse.Namespace, names: tuple[str, ...]) -> dict[str, object]:
    """Parsed values of the parameter flags that were given."""
    out: dict[str, object] = {}
    for name in names:
        v = getattr(args, name, None)
        if v is None:
            continue
        out[name] = parse_values(v, name=FLAGS[name]) if isinstance(v, str) else v
    return out


# ------------------------------------------------------------------------------------------
# a real top in SI units instead of the nondimensional parameters (docs/your_top.md)
# ------------------------------------------------------------------------------------------
#: the SI data of a top: Top's constructor keywords, in its order
TOP_FLAGS = ("mass", "radius", "com_offset", "inertia_transverse", "inertia_axial")
TOP_HELP = {
    "mass": "mass M, kg",
    "radius": "radius R of the sphere, m",
    "com_offset": "offset d of G from the sphere's centre along the axis, m (d < 0: G below)",
    "inertia_transverse": "transverse moment of inertia about G, A_G, kg m^2",
    "inertia_axial": "axial moment of inertia C, kg m^2",
}
#: the parameters a top gives whatever the spin (eq. 3)
TOP_PARAMETERS = ("q", "sigma", "mu")


def add_top_arguments(p: argparse.ArgumentParser, spin: bool = True, *, grid: bool = False) -> None:
    """The options of a real top in SI units: ``--preset``, ``--top FILE.toml``, ``--mass``,
    ``--radius``, ``--com-offset``, ``--inertia-transverse``, ``--inertia-axial``, ``--g``,
    ``--mu-v``, ``--mu-k``, and (``spin``) ``--spin`` with ``--unit``.

    Parameters
    ----------
    p : argparse.ArgumentParser
    spin : bool
        Add ``--spin`` and ``--unit`` (the command needs fr_inv, and alpha_v for the sliding model).
    grid : bool
        ``--spin`` takes a range or list (an atlas, a validation) instead of one number.
    """
    from ..top import PRESETS, SPIN_UNITS

    g = p.add_argument_group(
        "a real top in SI units (instead of --q, --sigma, --mu"
        + (", --fr-inv and, with --mu-v, --alpha-v)" if spin else ")")
    )
    g.add_argument(
        "--preset",
        choices=list(PRESETS),
        help="the paper's toy top: table1 (q = -0.1, mu = 2.28, sigma = 1, as its simulations) or "
        "table1_measured (Table 1 taken literally)",
    )
    g.add_argument(
        "--top",
        dest="top_file",
        metavar="FILE.toml",
        help="a TOML file with a [top] table: mass, radius, com_offset, inertia_transverse, "
        'inertia_axial (SI), optional g, mu_v, mu_k, or preset = "table1"',
    )
    for name in TOP_FLAGS:
        g.add_argument(flag_of(name), dest=name, type=float, metavar="VALUE", help=TOP_HELP[name])
    g.add_argument("--g", dest="gravity", type=float, default=None, metavar="M/S2", help="gravity (default 9.80665)")
    g.add_argument(
        "--mu-v",
        type=float,
        metavar="S/M",
        help="viscous friction coefficient mu_v, s/m: alpha_v = mu mu_v g / Omega (eq. 7) "
        "(default: none, --alpha-v given)",
    )
    g.add_argument(
        "--mu-k",
        type=float,
        metavar="MU_K",
        help="Coulomb friction coefficient mu_K: alpha_k = mu Fr^-1 mu_K (eq. 7) (default: none)",
    )
    if spin:
        g.add_argument(
            "--spin",
            metavar="VALUES" if grid else "VALUE",
            help="spin rate Omega of the top, in --unit: " + (_VALUES["values"] if grid else _VALUES["value"]),
        )
        g.add_argument("--unit", choices=list(SPIN_UNITS), default=None, help="unit of --spin (default rad/s)")
    p.set_defaults(_top_spin=spin, _top_grid=grid)


def _top_source(args: argparse.Namespace) -> str:
    """How the command line gave its top, for messages: ``--preset table1``, ``--top F``, ``--mass``."""
    if getattr(args, "preset", None):
        return f"--preset {args.preset}"
    if getattr(args, "top_file", None):
        return f"--top {args.top_file}"
    given = [n for n in TOP_FLAGS if getattr(args, n, None) is not None]
    return flag_of(given[0]) if given else "the top"


def top_from_args(args: argparse.Namespace):  # -> Top | None
    """The :class:`stability.Top` of :func:`add_top_arguments`' options, or None if none was given.

    Raises
    ------
    InputError
        Two ways of giving the top at once, missing SI data, or ``--g``/``--mu-v``/``--mu-k``
        without a top (one line, naming the options).
    """
    from dataclasses import replace

    from ..errors import InputError
    from ..top import Top

    preset, path = getattr(args, "preset", None), getattr(args, "top_file", None)
    si = [n for n in TOP_FLAGS if getattr(args, n, None) is not None]
    extra = {
        k: getattr(args, a)
        for k, a in (("g", "gravity"), ("mu_v", "mu_v"), ("mu_k", "mu_k"))
        if getattr(args, a, None) is not None
    }
    ways = (
        ([f"--preset {preset}"] if preset else [])
        + ([f"--top {path}"] if path else [])
        + ([", ".join(map(flag_of, si))] if si else [])
    )
    if len(ways) > 1:
        raise InputError(f"{' and '.join(ways)} conflict: give the top one way (--preset, --top FILE or its SI data)")
    if preset:
        return getattr(Top, preset)(**extra)
    if path:
        top = Top.from_toml(path)
        clash = [flag_of(k) for k in extra if getattr(top, k) is not None and k != "g"]
        if clash or "g" in extra:
            raise InputError(f"--top {path} and {', '.join(clash or ['--g'])} conflict: give g, mu_v, mu_k in the file")
        return replace(top, **extra) if extra else top
    if si:
        missing = [n for n in TOP_FLAGS if n not in si]
        if missing:
            raise InputError(
                f"{', '.join(map(flag_of, si))} given without {', '.join(map(flag_of, missing))}: a top in SI "
                "units needs all "
                "five (or --top FILE, or --preset)"
            )
        return Top(*(getattr(args, n) for n in TOP_FLAGS), **extra)
    if extra:
        raise InputError(
            f"{', '.join(map(flag_of, extra))} describe a real top: give it too (--mass ..., --top FILE or --preset)"
        )
    return None


def required_top(args: argparse.Namespace, command: str):  # -> Top
    """The top of :func:`top_from_args`, or an :class:`InputError` saying that ``command`` needs one."""
    from ..errors import InputError

    top = top_from_args(args)
    if top is None:
        raise InputError(f"{command} needs a top: --preset, --top FILE.toml or {', '.join(map(flag_of, TOP_FLAGS))}")
    return top


def lo_hi(text: str, flag: str) -> tuple[float, float]:
    """``LO:HI`` of a range flag (``--bracket``, ``--x-range``) as two floats."""
    from ..errors import InputError

    try:
        lo, hi = (float(v) for v in text.split(":"))
    except ValueError:
        raise InputError(f"{flag} = {text!r} must be lo:hi (two numbers)") from None
    return lo, hi


def top_parameters(
    top, spin=None, unit: str = "rad/s", alpha_v=None, *, names: Iterable[str] = (*TOP_PARAMETERS, "fr_inv", "alpha_v")
) -> dict[str, object]:
    """The nondimensional keywords of a top at a spin: ``q, sigma, mu`` (eq. 3) and, with a spin,
    ``fr_inv`` (eq. 3) and ``alpha_v`` (eq. 7, from the top's ``mu_v`` or the ``alpha_v`` given),
    ``alpha_k`` (eq. 7, with ``mu_k``); only those in ``names``.

    The formulas are :meth:`stability.Top.nondimensional`'s; this selects and, without a spin,
    keeps the spin-independent ones.
    """
    names = tuple(names)
    if spin is None:
        out = {"q": top.q, "sigma": top.sigma, "mu": top.mu}
    else:
        out = top.nondimensional(spin, unit, alpha_v=alpha_v if "alpha_v" in names else None)
    return {k: v for k, v in out.items() if k in names}


def apply_top(
    args: argparse.Namespace,
    names: Iterable[str],
    *,
    spin_needed: bool = True,
    skip: Iterable[str] = (),
    required: Iterable[str] = (),
):  # -> Top | None
    """Fill ``args``' nondimensional parameters from the top of :func:`add_top_arguments`.

    With a top, ``q``, ``sigma``, ``mu`` come from it and, when ``spin_needed``, ``fr_inv`` (and
    ``alpha_v`` with ``--mu-v``, ``alpha_k`` with ``--mu-k``) from ``--spin`` in ``--unit``; a
    nondimensional flag given beside the value the top gives is refused, naming both. Without a
    top, ``--spin`` is refused and an unset ``mu`` takes :data:`stability.parameters.DEFAULT_MU`.

    Parameters
    ----------
    args : argparse.Namespace
    names : iterable of str
        The nondimensional parameters the command takes (keys of :data:`FLAGS`, and ``alpha_k``).
    spin_needed : bool
        The command needs the spin-dependent parameters (False: e.g. ``fr_inv`` is traced).
    skip : iterable of str
        Parameters the command does not fix (traced ones), left alone.
    required : iterable of str
        Parameters that must have a value in the end (from their flag or the top); a missing
        one is an error naming its flag and the top's options.

    Returns
    -------
    Top or None
    """
    from ..errors import InputError

    names = [n for n in names if n not in tuple(skip)]
    top = top_from_args(args)
    spin = getattr(args, "spin", None)
    if spin is None and getattr(args, "unit", None) is not None:
        raise InputError(f"--unit {args.unit} is the unit of --spin: give --spin too (with a top)")
    if top is None:
        if spin is not None:
            raise InputError(f"--spin {spin} needs a top: give --mass ... (SI), --top FILE.toml or --preset")
        if "mu" in names and getattr(args, "mu", None) is None:
            args.mu = DEFAULT_MU
        _require(args, required)
        return None
    source = _top_source(args)
    given = [n for n in names if n in TOP_PARAMETERS and getattr(args, n, None) is not None]
    if spin_needed:
        given += [
            n
            for n in ("fr_inv", "alpha_k")
            if n in names and getattr(args, n, None) is not None and (n == "fr_inv" or top.mu_k is not None)
        ]
        if top.mu_v is not None and "alpha_v" in names and getattr(args, "alpha_v", None) is not None:
            raise InputError(
                f"--mu-v {top.mu_v:g} and --alpha-v {args.alpha_v} conflict: alpha_v = mu mu_v g / "
                "Omega follows from mu_v and the spin (eq. 7); give one of them"
            )
    if given:
        n = given[0]
        flag = flag_of(n)
        raise InputError(
            f"{source} and {flag} {getattr(args, n)} conflict: the top gives {n} "
            f"(eqs. 3, 7); give the top or {flag}, not both"
        )
    if spin_needed:
        if spin is None:
            raise InputError(
                f"{source} needs --spin VALUE (with --unit): the spin rate gives fr_inv "
                "= g / (Omega^2 R) and alpha_v = mu mu_v g / Omega"
            )
        value = parse_values(spin, name="--spin") if isinstance(spin, str) else spin
        if not getattr(args, "_top_grid", False) and not isinstance(value, float):
            raise InputError(f"--spin = {spin!r} must be one number here")
        unit = getattr(args, "unit", None) or "rad/s"  # one of SPIN_UNITS: argparse's choices
        alpha_v = getattr(args, "alpha_v", None)
        if isinstance(alpha_v, str):
            alpha_v = parse_values(alpha_v, name=FLAGS["alpha_v"])
        nd = top_parameters(top, value, unit, alpha_v, names=names)
    else:
        if spin is not None:
            raise InputError(f"--spin {spin} is not used here (no spin-dependent parameter is fixed)")
        nd = top_parameters(top, names=names)
    for k, v in nd.items():
        setattr(args, k, v)
    _require(args, required)
    return top


def _require(args: argparse.Namespace, required: Iterable[str]) -> None:
    from ..errors import InputError

    missing = [flag_of(n) for n in required if getattr(args, n, None) is None]
    if missing:
        spin = getattr(args, "_top_spin", False)
        raise InputError(
            f"{', '.join(missing)} required (or a top in SI units: --mass ... / --top FILE.toml / "
            f"--preset{' with --spin' if spin else ''})"
        )
