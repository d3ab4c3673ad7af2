"""Shared argument parsing for the ``tippe`` subcommands: the parameter flags and their help
(their values are read by :func:`stability.grids.ranges.parse_values`, which recipes use too),
the help of ``--model``, a real top in SI units, the output file, and the tables commands print."""

from __future__ import annotations

import argparse
import re
from collections.abc import Callable, Iterable

from ..errors import InputError
from ..grids.ranges import parse_values
from ..parameters import DEFAULT_MU, DOMAIN

#: what each parameter is, with its unit (docs/conventions.md); the physical domain is added
#: from :data:`stability.parameters.DOMAIN` by :func:`add_parameter_flags`
PARAMETER_HELP: dict[str, str] = {
    "q": "centre-of-mass offset q, units of R (G = O + q R k; q < 0: G below the centre O)",
    "fr_inv": "inverse Froude number g / (Omega^2 R), ~ 1/spin^2",
    "sigma": "inertia ratio sigma = C / A0 (axial / transverse about O)",
    "alpha_v": "viscous friction alpha_v = mu mu_v g / Omega (eq. 7)",
    "alpha_k": "Coulomb friction alpha_k = mu Fr^-1 mu_K (eq. 7)",
    "mu": "scaled mass mu = M R^2 / A0",
}
_VALUES = {"values": "a number, a comma list, or start:stop:num", "value": "a number"}


def flag_of(name: str) -> str:
    """The flag of a parameter or option (its argparse ``dest``): ``fr_inv`` -> ``--fr-inv``."""
    return "--" + name.replace("_", "-")


def add_parameter_flags(
    p: argparse.ArgumentParser, names: Iterable[str], kind: str = "values", unless_top=(), extra: dict | None = None
) -> None:
    """Add ``--q``, ``--fr-inv``, ... with their help (what, unit, physical domain, default).

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
        domain = " and ".join(b.text for b in DOMAIN if b.parameter == name)
        text = f"{PARAMETER_HELP[name]}; {domain}" if domain else PARAMETER_HELP[name]
        text = f"{text}{extra.get(name, '')}: {_VALUES[kind]}".replace("%", "%%")
        p.add_argument(flag_of(name), dest=name, metavar=kind.upper(), type={"value": float}.get(kind), help=text)


def add_model_flag(p: argparse.ArgumentParser, nonlinear: str | None = None) -> None:
    """``--model`` (default sliding) with its choices listed in the help: the linear models and
    their deprecated names (the library warns), or with ``nonlinear`` (what the help calls them)
    the nonlinear ones."""
    from ..models import DEPRECATED_NAMES, MODELS
    from ..nonlinear import NONLINEAR_MODELS

    models, deprecated = (list(NONLINEAR_MODELS), {}) if nonlinear else (list(MODELS), DEPRECATED_NAMES)
    old = "; ".join(f"{o}: deprecated name of {n}" for o, n in deprecated.items())
    text = f"{nonlinear or 'linear model'}: {', '.join(models)}" + (f" ({old})" if old else "")
    p.add_argument("--model", choices=[*models, *deprecated], default="sliding", metavar="MODEL", help=text)


def add_output_flags(
    p: argparse.ArgumentParser, help: str, required=False, overwrite="replace an existing output file (default: refuse)"
) -> None:
    """``-o/--output FILE.nc`` (``help`` says what is written) and ``--overwrite``."""
    p.add_argument("-o", "--output", required=required, metavar="FILE.nc", help=help)
    p.add_argument("--overwrite", action="store_true", help=overwrite)


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


def add_float_flags(p: argparse.ArgumentParser, *rows: tuple) -> None:
    """Options that take one number: each row ``(flag, default, metavar, help)``."""
    for flag, default, metavar, text in rows:
        p.add_argument(flag, type=float, default=default, metavar=metavar, help=text)


def add_switches(p: argparse.ArgumentParser, *rows: tuple[str, str]) -> None:
    """Options that are on when given: each row ``(flag, help)``."""
    for flag, text in rows:
        p.add_argument(flag, action="store_true", help=text)


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
        p.add_argument(flag, type=comma_floats, required=required, metavar=metavar, help=text)


def parameter_values(args: argparse.Namespace, names: Iterable[str]) -> dict[str, object]:
    """Parsed values of the parameter flags that were given."""
    values = {name: getattr(args, name, None) for name in names}
    return {
        n: parse_values(v, name=flag_of(n)) if isinstance(v, str) else v for n, v in values.items() if v is not None
    }


def keywords(call: Callable, args: argparse.Namespace, **given) -> dict[str, object]:
    """The keywords of ``call`` that are options of the command (a flag's ``dest`` is the
    library's keyword, :data:`stability.cli.KEYWORD_FLAGS`), and ``given``."""
    import inspect

    return {n: getattr(args, n) for n in inspect.signature(call).parameters if hasattr(args, n)} | given


def table(row: str, header: Iterable[str], rows: Iterable[Iterable]) -> list[str]:
    """Lines of a table: the ``header`` aligned as the columns of the format ``row`` (``{:<9}``
    left, any other right), then each of ``rows`` formatted by ``row``."""
    head = re.sub(r"\{:([<>]?)(\d*)[^}]*\}", lambda m: "{:" + (m[1] or ">") + m[2] + "}", row)
    return [head.format(*header), *(row.format(*r) for r in rows)]


# ------------------------------------------------------------------------------------------
# a real top in SI units instead of the nondimensional parameters (docs/your_top.md)
# ------------------------------------------------------------------------------------------
#: the options of a real top: its SI data (Top's constructor keywords, in its order), then
#: gravity and the friction coefficients; each with its help (and metavar, VALUE unless said)
TOP_OPTIONS = {
    "mass": "mass M, kg",
    "radius": "radius R of the sphere, m",
    "com_offset": "offset d of G from the sphere's centre along the axis, m (d < 0: G below)",
    "inertia_transverse": "transverse moment of inertia about G, A_G, kg m^2",
    "inertia_axial": "axial moment of inertia C, kg m^2",
    "g": "gravity (default 9.80665)",
    "mu_v": "viscous friction coefficient mu_v, s/m: alpha_v = mu mu_v g / Omega (eq. 7) "
    "(default: none, --alpha-v given)",
    "mu_k": "Coulomb friction coefficient mu_K: alpha_k = mu Fr^-1 mu_K (eq. 7) (default: none)",
}
_METAVARS = {"g": "M/S2", "mu_v": "S/M", "mu_k": "MU_K"}
TOP_FLAGS, _TOP_EXTRA = tuple(TOP_OPTIONS)[:5], tuple(TOP_OPTIONS)[5:]
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
        metavar="FILE.toml",
        help="a TOML file with a [top] table: mass, radius, com_offset, inertia_transverse, "
        'inertia_axial (SI), optional g, mu_v, mu_k, or preset = "table1"',
    )
    add_float_flags(g, *((flag_of(n), None, _METAVARS.get(n, "VALUE"), text) for n, text in TOP_OPTIONS.items()))
    if spin:
        g.add_argument(
            "--spin",
            metavar="VALUES" if grid else "VALUE",
            help="spin rate Omega of the top, in --unit: " + _VALUES["values" if grid else "value"],
        )
        g.add_argument("--unit", choices=list(SPIN_UNITS), default=None, help="unit of --spin (default rad/s)")
    p.set_defaults(_top_grid=grid)


def top_from_args(args: argparse.Namespace):  # -> Top | None
    """The :class:`stability.Top` of :func:`add_top_arguments`' options, or None if none was given.

    Raises
    ------
    InputError
        Two ways of giving the top at once, missing SI data, or ``--g``/``--mu-v``/``--mu-k``
        without a top (one line, naming the options).
    """
    from dataclasses import replace

    from ..top import Top

    si = [n for n in TOP_FLAGS if getattr(args, n) is not None]
    extra = {k: getattr(args, k) for k in _TOP_EXTRA if getattr(args, k) is not None}
    ways = [f"--preset {args.preset}"] * bool(args.preset) + [f"--top {args.top}"] * bool(args.top)
    ways += [", ".join(map(flag_of, si))] * bool(si)
    if len(ways) > 1:
        raise InputError(f"{' and '.join(ways)} conflict: give the top one way (--preset, --top FILE or its SI data)")
    if args.preset:
        return getattr(Top, args.preset)(**extra)
    if args.top:
        top = Top.from_toml(args.top)
        clash = [flag_of(k) for k in extra if getattr(top, k) is not None and k != "g"]
        if clash or "g" in extra:
            raise InputError(
                f"--top {args.top} and {', '.join(clash or ['--g'])} conflict: give g, mu_v, mu_k in the file"
            )
        return replace(top, **extra)
    if si:
        missing = ", ".join(flag_of(n) for n in TOP_FLAGS if n not in si)
        if missing:
            raise InputError(
                f"{', '.join(map(flag_of, si))} given without {missing}: a top in SI units needs all "
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
    top = top_from_args(args)
    if top is None:
        raise InputError(f"{command} needs a top: --preset, --top FILE.toml or {', '.join(map(flag_of, TOP_FLAGS))}")
    return top


def lo_hi(text: str | None, flag: str) -> tuple[float, float] | None:
    """``LO:HI`` of a range flag (``--bracket``, ``--x-range``) as two floats; None if not given."""
    if text is None:
        return None
    try:
        lo, hi = (float(v) for v in text.split(":"))
    except ValueError:
        raise InputError(f"{flag} = {text!r} must be lo:hi (two numbers)") from None
    return lo, hi


def apply_top(
    args: argparse.Namespace, names: Iterable[str], *, spin_needed: bool = True, skip=(), required=()
):  # -> Top | None
    """Fill ``args``' nondimensional parameters from the top of :func:`add_top_arguments`.

    With a top, ``q``, ``sigma``, ``mu`` come from it (eq. 3) and, when ``spin_needed``,
    ``fr_inv`` (eq. 3; and ``alpha_v`` with ``--mu-v``, ``alpha_k`` with ``--mu-k``, eq. 7) from
    ``--spin`` in ``--unit`` (:meth:`stability.Top.nondimensional`); a nondimensional flag
    given beside the value the top gives is refused, naming both. Without a top, ``--spin`` is
    refused and an unset ``mu`` takes :data:`stability.parameters.DEFAULT_MU`.

    Parameters
    ----------
    args : argparse.Namespace
    names : iterable of str
        The nondimensional parameters the command takes (keys of :data:`PARAMETER_HELP`).
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
    names = [n for n in names if n not in skip]
    top, spin = top_from_args(args), args.spin
    if spin is None and args.unit is not None:
        raise InputError(f"--unit {args.unit} is the unit of --spin: give --spin too (with a top)")
    if top is None and spin is not None:
        raise InputError(f"--spin {spin} needs a top: give --mass ... (SI), --top FILE.toml or --preset")
    if top is None and "mu" in names and args.mu is None:
        args.mu = DEFAULT_MU
    if top is not None:
        si = next((flag_of(n) for n in TOP_FLAGS if getattr(args, n) is not None), None)
        source = f"--preset {args.preset}" if args.preset else f"--top {args.top}" if args.top else si
        given = [n for n in names if n in TOP_PARAMETERS and getattr(args, n) is not None]
        if spin_needed:
            spun = ("fr_inv",) + ("alpha_k",) * (top.mu_k is not None)
            given += [n for n in spun if n in names and getattr(args, n) is not None]
            if top.mu_v is not None and "alpha_v" in names and args.alpha_v is not None:
                raise InputError(
                    f"--mu-v {top.mu_v:g} and --alpha-v {args.alpha_v} conflict: alpha_v = mu mu_v g / "
                    "Omega follows from mu_v and the spin (eq. 7); give one of them"
                )
        if given:
            flag = flag_of(given[0])
            raise InputError(
                f"{source} and {flag} {getattr(args, given[0])} conflict: the top gives {given[0]} "
                f"(eqs. 3, 7); give the top or {flag}, not both"
            )
        nd = {"q": top.q, "sigma": top.sigma, "mu": top.mu}
        if spin_needed and spin is None:
            raise InputError(
                f"{source} needs --spin VALUE (with --unit): the spin rate gives fr_inv "
                "= g / (Omega^2 R) and alpha_v = mu mu_v g / Omega"
            )
        if spin_needed:
            value = parse_values(spin, name="--spin")
            if not args._top_grid and not isinstance(value, float):
                raise InputError(f"--spin = {spin!r} must be one number here")
            alpha_v = parameter_values(args, [n for n in names if n == "alpha_v"]).get("alpha_v")
            nd = top.nondimensional(value, args.unit or "rad/s", alpha_v=alpha_v)
        elif spin is not None:
            raise InputError(f"--spin {spin} is not used here (no spin-dependent parameter is fixed)")
        for k in nd.keys() & names:
            setattr(args, k, nd[k])
    missing = [flag_of(n) for n in required if getattr(args, n) is None]
    if missing:
        raise InputError(
            f"{', '.join(missing)} required (or a top in SI units: --mass ... / --top FILE.toml / --preset with --spin)"
        )
    return top
