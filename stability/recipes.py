"""Atlas recipes: one small TOML file per atlas under ``atlases/``, read and run here.

Why TOML: a recipe is data (a model, a grid, what to draw, where to write), not a program; TOML
is in the standard library (``tomllib``), reads like the paper's parameter lists, and cannot run
code. A recipe looks like::

    title = "Fig. 4: growth rate against q for several alpha_v"
    kind = "lines"                  # lines | map | models | scene  (what is drawn)
    model = "sliding"
    x = "q"                         # abscissa (lines, maps)
    family = "alpha_v"              # one line per value (lines)
    y = "sigma"                     # ordinate (map, models)
    quantities = ["growth_rate"]    # lines: growth_rate and/or frequency panels
    mask_unphysical = true
    neutral = true                  # map, models: continue the neutral curves and draw them

    [grid]                          # numbers, lists, or "start:stop:num" strings
    q = "-0.45:0.45:361"
    fr_inv = 0.0
    sigma = 1.0
    alpha_v = [0.1, 0.2, 0.5, 1.0, 2.0, 5.0]

A ``kind = "critical_spin"`` recipe draws the critical spin rate (rpm) of a real top
(``preset = "table1"``, :class:`stability.Top`) against one nondimensional parameter of its
``[grid]`` (``q`` or ``sigma``), the others kept at the preset's values; see
:func:`stability.critical_spin`.

A real top instead of the nondimensional set (docs/your_top.md): a ``[top]`` table of SI values
(``mass``, ``radius``, ``com_offset``, ``inertia_transverse``, ``inertia_axial``, optional ``g``,
``mu_v``, ``mu_k``; or ``preset = "table1"``, :meth:`stability.Top.from_mapping`) gives ``q``,
``sigma`` and ``mu`` (eq. 3), and ``spin`` (a number or a grid) with ``unit`` (default
``"rad/s"``) gives ``fr_inv`` (eq. 3) and, with ``mu_v``, ``alpha_v`` (eq. 7); a ``[grid]``
value of a parameter the top gives is refused. A grid of spins is a grid of ``fr_inv`` with
the spin a coordinate along it::

    title = "My top: growth rate against its spin"
    kind = "lines"
    x = "fr_inv"
    spin = "5:20:31"
    unit = "rev/s"
    [grid]
    alpha_v = 0.5
    [top]
    mass = 0.015
    radius = 0.015
    com_offset = -0.003
    inertia_transverse = 1.3e-6
    inertia_axial = 1.5e-6

A ``kind = "scene"`` recipe names instead one of the paper's nonlinear figures,
``figure = "fig5"`` ... ``"fig9"``, drawn from the runs of Sec. 3(ii) (:mod:`stability.nonlinear.scene`);
it has no grid.

Steady states (:mod:`stability.steady`, docs/steady_states.md):

* ``kind = "bifurcation"``: the bifurcation diagram of a preset top (``preset = "table1"``) or
  of a ``[top]``: the tilt of every steady state against the equivalent upright spin in
  ``unit`` (default rpm), with the end points of nonlinear runs launched upright (tilt 1
  degree) at the spins ``runs`` (in ``unit``; ``runs_rpm`` in rpm, kept for the older recipes;
  :attr:`Recipe.runs_rpm` holds them converted to ``unit``); ``[grid]`` holds ``alpha_v`` (a
  number; not with a ``mu_v`` in ``[top]``);
* ``kind = "classes"``: the high-spin class map over ``[grid]`` ``q`` and ``sigma`` (1-D) at a
  scalar ``mu`` (:func:`stability.class_atlas`);
* ``kind = "settle"``: the paper's run of Sec. 3(ii) at ``[grid] fr_inv`` (0.3 or 0.1)
  continued to ``t_end`` with the final tilt :func:`stability.final_state` predicts.

The outputs are ``<name>.nc`` (regenerated, not committed) and ``<name>.png`` (committed when the
README shows it) beside the recipe, ``<name>`` being the recipe's file stem. A dataset already on
disk is reused when its ``recipe_digest`` attribute matches the digest of the recipe's contents
and of the package's source code (:func:`code_fingerprint`): a dataset computed by another
version of the code is recomputed, never reused.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import importlib.util
import time
import tomllib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from .errors import AtlasFileError, RecipeError
from .grids.atlases import atlas
from .grids.netcdf import check_output_path, open_atlas, write_dataset
from .grids.ranges import parse_values
from .models import MODELS, get_model
from .parameters import PARAMETERS, parameter_attrs
from .products import PRODUCT_ATTR
from .top import PRESETS, SI_UNITS, SPIN_UNITS, Top

__all__ = ["KINDS", "Recipe", "check_outputs", "compute", "find_recipes", "load_recipe", "output_paths"]

#: what a recipe can draw
KINDS = ("lines", "map", "models", "scene", "critical_spin", "bifurcation", "classes", "settle")
#: the steady-state kinds (their own loader and makers below)
STEADY_KINDS = ("bifurcation", "classes", "settle")
#: the paper's nonlinear figures a scene recipe can draw
SCENE_FIGURES = ("fig5", "fig6", "fig7", "fig8", "fig9")
QUANTITIES = ("growth_rate", "frequency")


@dataclass(frozen=True)
class Recipe:
    """A parsed atlas recipe (see the module docstring for the file format)."""

    path: Path
    title: str
    kind: str
    model: str
    grid: dict[str, Any]
    x: str = "q"
    y: str | None = None
    family: str | None = None
    quantities: tuple[str, ...] = ("growth_rate",)
    mask_unphysical: bool = True
    caption: str = ""
    figure: str | None = None
    neutral: bool = False
    runs_rpm: tuple[float, ...] = ()
    t_end: float = 0.0
    top: Any = None
    spin: Any = None
    unit: str = "rad/s"
    digest: str = field(default="", compare=False)

    @property
    def name(self) -> str:
        """The recipe's file stem, used for its outputs."""
        return self.path.stem

    @property
    def dataset_path(self) -> Path:
        """Where the computed dataset is written."""
        return self.path.with_suffix(".nc")

    @property
    def figure_path(self) -> Path:
        """Where the figure is written."""
        return self.path.with_suffix(".png")

    def models(self) -> tuple[str, ...]:
        """The models the recipe computes (all three for kind "models")."""
        return tuple(MODELS) if self.kind == "models" else (self.model,)


#: the keys a recipe file may hold: the fields of :class:`Recipe` it gives (``figure`` holds a
#: scene's figure or a preset), ``preset``, and ``runs`` (a bifurcation's launch spins)
_KEYS = {f.name for f in fields(Recipe)} - {"path", "digest"} | {"preset", "runs"}


@functools.cache
def code_fingerprint() -> str:
    """SHA-256 of the source of the ``stability`` and ``continuation`` packages.

    Part of every recipe's digest, so that a cached dataset made by other code (an older
    version, a local edit) is recomputed rather than drawn. Reading and hashing the ~80 source
    files takes a few milliseconds, once per process.
    """
    h = hashlib.sha256()
    for pkg in ("stability", "continuation"):
        root = Path(importlib.util.find_spec(pkg).origin).parent  # located, not imported
        for f in sorted(root.rglob("*.py")):
            h.update(f.relative_to(root.parent).as_posix().encode())
            h.update(f.read_bytes())
    return h.hexdigest()


def _check(ok: Any, message: str) -> None:
    """A :class:`RecipeError` with ``message`` (it names the file and the key) unless ``ok``."""
    if not ok:
        raise RecipeError(message)


def _grid_value(path: Path, key: str, value: Any) -> float | np.ndarray:
    if isinstance(value, str):
        try:
            return parse_values(value, name=f"grid.{key}")
        except ValueError as exc:
            raise RecipeError(f"{path}: {exc}") from None
    if isinstance(value, list):
        try:
            return np.array([float(v) for v in value])
        except (TypeError, ValueError):
            raise RecipeError(f"{path}: grid.{key} = {value!r} is not a list of numbers") from None
    _check(
        isinstance(value, (int, float)) and not isinstance(value, bool),
        f"{path}: grid.{key} = {value!r} is not a number, a list or 'start:stop:num'",
    )
    return float(value)


def _one_of(p: Path, raw: dict[str, Any], key: str, default: Any, choices: Sequence[str]) -> Any:
    """The recipe's ``key`` (``default`` if absent), or a :class:`RecipeError` naming the choices."""
    value = raw.get(key, default)
    _check(value in choices, f"{p}: {key} = {value!r} is not one of {', '.join(choices)}")
    return value


def _grid(p: Path, raw: dict[str, Any], allowed: Sequence[str], refusal: str) -> dict[str, Any]:
    """The ``[grid]`` table read (:func:`_grid_value`); a key outside ``allowed`` is refused with
    ``refusal`` (formatted with the allowed and the refused keys)."""
    grid_raw = raw.get("grid", {})
    _check(isinstance(grid_raw, dict), f"{p}: [grid] must be a table of parameter values")
    bad = ", ".join(sorted(set(grid_raw) - set(allowed)))
    _check(not bad, f"{p}: " + refusal.format(allowed=", ".join(allowed), bad=bad))
    return {k: _grid_value(p, k, v) for k, v in grid_raw.items()}


def load_recipe(path: str | Path) -> Recipe:
    """Read and check a recipe file.

    Raises
    ------
    RecipeError
        Missing file, bad TOML, unknown keys, or values outside their choices; the message
        names the file and the key.
    """
    p = Path(path)
    _check(p.is_file(), f"recipe {str(p)!r} does not exist")
    raw_bytes = p.read_bytes()
    try:
        raw = tomllib.loads(raw_bytes.decode())
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise RecipeError(f"{p}: not valid TOML ({exc})") from None
    unknown = ", ".join(sorted(set(raw) - _KEYS))
    _check(not unknown, f"{p}: unknown keys {unknown} (allowed: {', '.join(sorted(_KEYS))})")
    for key in ("title", "kind"):
        _check(key in raw, f"{p}: the key {key!r} is required")
    kind = _one_of(p, raw, "kind", None, KINDS)
    digest = hashlib.sha256(raw_bytes + code_fingerprint().encode()).hexdigest()[:16]
    top = _load_top(p, raw, kind)
    common = dict(path=p, title=str(raw["title"]), kind=kind, caption=str(raw.get("caption", "")), digest=digest)
    if kind == "scene":
        figure = _one_of(p, raw, "figure", None, SCENE_FIGURES)
        _check("grid" not in raw, f"{p}: a scene recipe has no [grid] (its runs are those of Sec. 3(ii))")
        return Recipe(**common, model="sliding", grid={}, figure=figure)
    if kind in STEADY_KINDS:
        return _load_steady(p, raw, kind, common, top)
    _check("grid" in raw, f"{p}: the key 'grid' is required")
    model = raw.get("model", "sliding")
    try:  # a recipe's model is a public lookup: "rolling" warns once, a deprecated name is mapped
        model = get_model(model).name
    except ValueError:
        raise RecipeError(f"{p}: model = {model!r} is not one of {', '.join(MODELS)}") from None
    x = raw.get("x", "q")
    common.update(model=model, x=x, top=top)
    if kind == "critical_spin":
        preset = None if top is not None else _one_of(p, raw, "preset", "table1", PRESETS)
        _check(
            x in ("q", "sigma") and set(raw["grid"]) == {x},
            f"{p}: a critical_spin recipe varies one of q, sigma: [grid] must hold only x = {x!r}",
        )
        grid = {x: _grid_value(p, x, raw["grid"][x])}
        _check(np.ndim(grid[x]) == 1, f"{p}: {x!r} must be a 1-D grid (a list or 'start:stop:num')")
        return Recipe(**common, grid=grid, figure=preset)
    grid = _grid(p, raw, PARAMETERS, "grid has unknown parameters {bad} (allowed: {allowed})")
    spin, unit = _top_grid(p, raw, top, grid)
    quantities = tuple(raw.get("quantities", ["growth_rate"]))
    for qn in quantities:
        _check(qn in QUANTITIES, f"{p}: quantities has {qn!r}, not one of {', '.join(QUANTITIES)}")
    arrays = [k for k, v in grid.items() if np.ndim(v) == 1]
    y, family = raw.get("y"), raw.get("family")
    wanted = {"lines": [x] + ([family] if family else []), "map": [x, y], "models": [x, y]}[kind]
    for name in wanted:
        _check(name is not None, f"{p}: kind = {kind!r} needs the key 'y'")
        _check(name in arrays, f"{p}: {name!r} must be a 1-D grid (a list or 'start:stop:num') for kind = {kind!r}")
    _check(
        sorted(arrays) == sorted(wanted),
        f"{p}: grid dimensions {', '.join(arrays)} do not match what kind = {kind!r} draws ({', '.join(wanted)})",
    )
    flags = {k: bool(raw.get(k, k == "mask_unphysical")) for k in ("mask_unphysical", "neutral")}
    return Recipe(**common, **flags, grid=grid, y=y, family=family, quantities=quantities, spin=spin, unit=unit)


def _load_top(p: Path, raw: dict[str, Any], kind: str) -> Any:
    """The recipe's ``[top]`` table as a :class:`stability.Top` (None without one); a ``[top]``
    beside ``preset``, or on a kind that takes no top, is refused; so are ``spin`` and ``unit``
    without a ``[top]``."""
    if "top" not in raw:
        _check("spin" not in raw, f"{p}: spin = {raw.get('spin')!r} needs a [top] table (the top's SI data)")
        return None
    _check(kind in (*KINDS[:3], "critical_spin", "bifurcation"), f"{p}: a {kind} recipe takes no [top] table")
    _check(
        "preset" not in raw,
        f"{p}: preset = {raw.get('preset')!r} and [top] conflict: give a preset or a [top] table "
        "(which may hold preset = ... itself), not both",
    )
    try:
        return Top.from_mapping(raw["top"], source=f"{p} [top]")
    except RecipeError:
        raise
    except ValueError as exc:  # InputError, DomainError: the top's own message, naming the file
        raise RecipeError(str(exc) if str(p) in str(exc) else f"{p} [top]: {exc}") from None


def _top_grid(p: Path, raw: dict[str, Any], top: Any, grid: dict[str, Any]) -> tuple[Any, str]:
    """Fold a ``[top]`` and its ``spin`` (in ``unit``) into the grid of a lines/map/models
    recipe: q, sigma, mu from the top (eq. 3), fr_inv and (with ``mu_v``) alpha_v from the spin
    (eqs. 3, 7). A grid value of a parameter the top gives is refused, naming both. A 1-D spin
    is a 1-D grid of fr_inv (the spin is recorded as a coordinate along it)."""
    unit = _one_of(p, raw, "unit", "rad/s", SPIN_UNITS)
    if top is None:
        _check("unit" not in raw, f"{p}: unit = {unit!r} needs a [top] table and a spin")
        return None, unit
    given = [k for k in ("q", "sigma", "mu") if k in grid]
    if "spin" in raw:
        given += [k for k in ("fr_inv",) if k in grid] + ["alpha_v"] * (top.mu_v is not None and "alpha_v" in grid)
    if given:
        raise RecipeError(
            f"{p}: [top] and grid.{given[0]} conflict: the top gives {given[0]} (eqs. 3, 7); "
            "give the top or the nondimensional value, not both"
        )
    grid.update(q=top.q, sigma=top.sigma, mu=top.mu)
    if "spin" not in raw:
        return None, unit
    spin = _grid_value(p, "spin", raw["spin"])
    _check(np.ndim(spin) <= 1, f"{p}: spin must be a number or a 1-D grid")
    try:
        nd = top.nondimensional(spin, unit, alpha_v=grid.get("alpha_v"))
    except (ValueError, TypeError) as exc:
        raise RecipeError(f"{p}: spin = {raw['spin']!r} {unit}: {exc}") from None
    _check(
        np.ndim(nd.get("alpha_v", 0.0)) != 1 or np.ndim(nd["fr_inv"]) != 1,
        f"{p}: a grid of spins and mu_v = {top.mu_v or 0:g}: alpha_v = mu mu_v g / Omega would "
        "change along the spin grid, and an atlas holds one dimension per parameter; give "
        "grid.alpha_v (held fixed) instead of mu_v, or one spin",
    )
    grid.update({k: v for k, v in nd.items() if k in ("fr_inv", "alpha_v")})
    return spin, unit


def _recipe_top(recipe: Recipe) -> Any:
    """The recipe's top: its ``[top]`` table, or its preset (default Table 1)."""
    return recipe.top if recipe.top is not None else getattr(Top, recipe.figure or "table1")()


def spin_coordinate(ds: xr.Dataset, spin: Any, unit: str) -> xr.Dataset:
    """The spin of a top (in ``unit``) on an atlas over its ``fr_inv`` (eq. 3): a coordinate along
    ``fr_inv`` for a grid of spins, the attributes ``spin`` and ``spin_unit`` for one (what
    ``tippe atlas --spin`` and a recipe with a ``[top]`` write)."""
    attrs = {"long_name": "spin rate Omega of the top", "units": unit, "comment": "fr_inv = g / (Omega^2 R) (eq. 3)"}
    if np.ndim(spin) == 1 and "fr_inv" in ds.dims:
        return ds.assign_coords(spin=("fr_inv", np.asarray(spin, dtype=float), attrs))
    ds.attrs.update(spin=float(np.asarray(spin).ravel()[0]), spin_unit=unit)
    return ds


def find_recipes(directory: str | Path) -> list[Recipe]:
    """All recipes (``*.toml``) in ``directory``, sorted by name."""
    return [load_recipe(p) for p in sorted(Path(directory).glob("*.toml"))]


def _grid_for(model: str, grid: dict[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in grid.items() if k in MODELS[model].parameters}


def _datasets(recipe: Recipe) -> dict[str, tuple[Path, Callable[[], xr.Dataset], Callable[[Path], xr.Dataset]]]:
    """Every dataset of ``recipe``: its key (in :func:`compute`'s result) -> its path, the call
    that makes it and the call that reads it back; the one list of what a recipe writes."""

    read = xr.load_dataset  # each dataset but the atlases (open_atlas checks what it reads)

    def beside(key: str) -> Path:
        return recipe.path.with_name(f"{recipe.name}_{key}.nc")

    if recipe.kind in STEADY_KINDS:  # one call makes every part
        parts, maker = _STEADY[recipe.kind]
        made = functools.cache(lambda: maker(recipe))
        return {k: (recipe.dataset_path if k == parts[0] else beside(k), lambda k=k: made()[k], read) for k in parts}
    if recipe.kind == "critical_spin":
        return {recipe.model: (recipe.dataset_path, lambda: critical_spin_dataset(recipe), read)}
    if recipe.kind == "scene":  # the run's label in its attributes (what the figure's legend shows)
        runs = scene_runs(recipe.figure or "").items()
        return {k: (beside(k), lambda m=make, t=label: m().assign_attrs(label=t), read) for k, (label, make) in runs}
    out = {}
    for model in recipe.models():
        path = recipe.dataset_path if recipe.kind != "models" else beside(model)
        out[model] = (path, functools.partial(_atlas, recipe, model), open_atlas)
        if recipe.neutral:
            neutral = path.with_name(path.stem + "_neutral.nc")
            out[f"{model}_neutral"] = (neutral, functools.partial(_neutral, recipe, model), read)
    return out


def output_paths(recipe: Recipe) -> list[Path]:
    """Every file :func:`compute` and ``tippe figures`` may write for ``recipe``."""
    return [recipe.figure_path, *(path for path, _, _ in _datasets(recipe).values())]


def check_outputs(recipe: Recipe) -> None:
    """Fail before computing if an output of ``recipe`` cannot be written (its own files may be
    replaced; see the module docstring).

    Raises
    ------
    OSError
        The directory is missing or not writable, or an output path is a directory.
    """
    for path in output_paths(recipe):
        check_output_path(path, overwrite=True)


def scene_runs(figure: str) -> dict[str, tuple[str, Callable[[], xr.Dataset]]]:
    """The runs a scene figure needs: key -> (label, function making the run)."""
    from .nonlinear import scene

    paper = dict(method="rk4", step=0.1, friction="componentwise", slip_scale=1e-12)
    runs: dict[str, tuple[str, Callable[[], xr.Dataset]]] = {"fr_inv_0.3": ("Fr$^{-1}$ = 0.3", lambda: scene.run(0.3))}
    if figure == "fig5":
        runs["fr_inv_0.1"] = ("Fr$^{-1}$ = 0.1", lambda: scene.run(0.1))
    if figure == "fig9":
        runs["rolling"] = ("rolling", lambda: scene.run(0.3, model="rolling"))
        for j, (ak, av) in enumerate(scene.FRICTION_CASES, start=1):
            label = f"({j}) $\\alpha_K$ = {ak:g}, $\\alpha_v$ = {av:g}"
            for key, scheme in ((f"case{j}", {}), (f"case{j}_paper_scheme", paper)):
                runs[key] = (
                    label,
                    lambda ak=ak, av=av, s=scheme: scene.run(0.3, alpha_k=ak, alpha_v=av, t_end=1500.0, dt=0.5, **s),
                )
    return runs


def compute(
    recipe: Recipe, *, force: bool = False, log: list[tuple[Path, str, float]] | None = None
) -> dict[str, xr.Dataset]:
    """Compute (or reuse from disk) the recipe's datasets.

    A dataset on disk is reused when its ``recipe_digest`` attribute equals the recipe's;
    otherwise it is recomputed and written atomically.

    Parameters
    ----------
    recipe : Recipe
        The recipe.
    force : bool
        Recompute even when a matching dataset exists.
    log : list, optional
        If given, one ``(path, action, seconds)`` is appended per dataset, ``action`` being
        ``"reused"`` or ``"computed"`` (what ``tippe figures`` prints).

    Returns
    -------
    dict
        model name -> atlas dataset, or (scene recipes) run key -> simulate() dataset with the
        run's label in its ``label`` attribute.
    """
    out, log = {}, [] if log is None else log
    for key, (path, make, reader) in _datasets(recipe).items():
        if path.exists() and not force:  # reused if it holds this recipe version's dataset
            try:
                out[key] = ds = reader(path)
            except (AtlasFileError, OSError, ValueError) as exc:
                raise RecipeError(
                    f"{path} exists and was not written by a recipe ({exc}); remove it or pass force=True to replace it"
                ) from None
            if ds.attrs.get("recipe_digest") == recipe.digest:
                log.append((path, "reused", 0.0))
                continue
            _check(
                "recipe_digest" in ds.attrs,
                f"{path} exists and was not written by a recipe (it has no recipe_digest "
                "attribute); remove it or pass force=True to replace it",
            )
        start = time.perf_counter()
        out[key] = ds = make()
        ds.attrs["recipe_digest"] = recipe.digest
        write_dataset(ds, path, overwrite=True)
        log.append((path, "computed", time.perf_counter() - start))
    return out


def _atlas(recipe: Recipe, model: str) -> xr.Dataset:
    """The atlas of ``model`` over the recipe's grid; with a ``[top]``, the top's SI data in the
    attributes and its spin (in the recipe's unit) on it (:func:`spin_coordinate`)."""
    ds = atlas(MODELS[model], mask_unphysical=recipe.mask_unphysical, **_grid_for(model, recipe.grid))
    if (t := recipe.top) is not None:
        si = {f"{k}_{u.replace(' ', '_').replace('^', '')}": getattr(t, k) for k, u in SI_UNITS.items()}
        ds.attrs.update(si, g=t.g)
        ds = ds if recipe.spin is None else spin_coordinate(ds, recipe.spin, recipe.unit)
    ds.attrs["recipe"] = recipe.path.name
    return ds


def critical_spin_dataset(recipe: Recipe) -> xr.Dataset:
    """Critical spin rates (rpm) of the preset top against the recipe's grid parameter.

    For every value, a :class:`stability.Top` with the preset's mass and radius and the
    nondimensional set changed in that one parameter (:meth:`stability.Top.from_nondimensional`)
    is handed to :func:`stability.critical_spin`, upright and inverted; NaN where there is no
    transition in the range searched.
    """
    from .linear.critical import critical_spin

    base, x = _recipe_top(recipe), recipe.x
    values = np.asarray(recipe.grid[x], dtype=float)
    out = {"upright": np.full(values.size, np.nan), "inverted": np.full(values.size, np.nan)}
    for j, v in enumerate(values):
        nd = {"q": base.q, "mu": base.mu, "sigma": base.sigma, x: float(v)}
        top = Top.from_nondimensional(mass=base.mass, radius=base.radius, **nd)
        for orientation in out:
            with contextlib.suppress(ValueError):
                out[orientation][j] = critical_spin(top, recipe.model, orientation).rpm
    becomes = {"upright": "unstable", "inverted": "stable"}
    var = {o: {"long_name": f"{o} critical spin", "units": "min-1"} for o in out}
    var = {o: dict(a, comment=f"spin rate above which the {o} top is {becomes[o]}") for o, a in var.items()}
    attrs = {"Conventions": "CF-1.10", "title": recipe.title, PRODUCT_ATTR: "critical_spin", "model": recipe.model}
    attrs.update(
        preset=recipe.figure or "", mass_kg=base.mass, radius_m=base.radius, q=base.q, mu=base.mu, sigma=base.sigma
    )
    data = {f"critical_spin_{o}": (x, v, var[o]) for o, v in out.items()}
    return xr.Dataset(data, coords={x: (x, values, parameter_attrs(x))}, attrs=attrs)


def _neutral(recipe: Recipe, model: str) -> xr.Dataset:
    """Continued neutral curves of ``model`` over the recipe's (x, y) ranges."""
    from .linear.neutral_curves import neutral_curve

    grid = _grid_for(model, recipe.grid)
    fixed = {k: float(v) for k, v in grid.items() if np.ndim(v) == 0}
    xs, ys = np.asarray(grid[recipe.x]), np.asarray(grid[recipe.y or ""])
    ranges = {"x_range": (float(xs.min()), float(xs.max())), "y_range": (float(ys.min()), float(ys.max()))}
    ds = neutral_curve(MODELS[model], recipe.x, recipe.y, fixed=fixed, **ranges)
    for name in ("kind", "detail"):
        if name in ds:
            ds[name] = ds[name].astype(str)
    return ds


# ------------------------------------------------------------------------------------------
# steady states: the bifurcation diagram, the class map, a run settling (stability.steady)
# ------------------------------------------------------------------------------------------
def _load_steady(p: Path, raw: dict[str, Any], kind: str, common: dict[str, Any], top: Any = None) -> Recipe:
    """The steady kinds' keys (module docstring); ``common``: the keywords of every kind."""
    allowed = {"bifurcation": ("alpha_v",), "classes": ("mu", "q", "sigma"), "settle": ("fr_inv",)}[kind]
    grid = _grid(p, raw, allowed, f"a {kind} recipe's grid takes {{allowed}}, not {{bad}}")
    common = dict(common, model="sliding", grid=grid)
    if kind == "bifurcation":
        preset = None if top is not None else _one_of(p, raw, "preset", "table1", PRESETS)
        unit = _one_of(p, raw, "unit", "rpm", SPIN_UNITS)
        _check(
            "runs_rpm" not in raw or "runs" not in raw,
            f"{p}: runs_rpm and runs conflict: give the launch spins once (runs, in unit)",
        )
        key = "runs" if "runs" in raw else "runs_rpm"
        runs = raw.get(key, [])
        _check(
            isinstance(runs, list)
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) and v > 0 for v in runs),
            f"{p}: {key} = {runs!r} must be a list of spin rates > 0 ({'rpm' if key == 'runs_rpm' else unit})",
        )
        runs = [float(v) * (SPIN_UNITS["rpm"] / SPIN_UNITS[unit] if key == "runs_rpm" else 1.0) for v in runs]
        _check(
            "alpha_v" not in grid or top is None or top.mu_v is None,
            f"{p}: [top] mu_v and grid.alpha_v conflict: alpha_v follows from mu_v (eq. 7)",
        )
        alpha_v = grid.get("alpha_v", 0.5)
        _check(np.ndim(alpha_v) == 0 and float(alpha_v) > 0, f"{p}: grid.alpha_v must be one number > 0")
        return Recipe(**common, figure=preset, runs_rpm=tuple(runs), top=top, unit=unit)
    _check("spin" not in raw and "unit" not in raw, f"{p}: a {kind} recipe takes no spin or unit")
    if kind == "classes":
        for k in ("q", "sigma"):
            _check(
                np.ndim(grid.get(k)) == 1,
                f"{p}: a classes recipe needs grid.{k} as a 1-D grid (a list or 'start:stop:num')",
            )
        _check(np.ndim(grid.get("mu", 2.28)) == 0, f"{p}: grid.mu must be one number")
        return Recipe(**common)
    from .nonlinear.scene import INITIAL_CONDITIONS

    fr, t_end = grid.get("fr_inv", 0.3), raw.get("t_end", 15000.0)
    _check(
        np.ndim(fr) == 0 and float(fr) in INITIAL_CONDITIONS,
        f"{p}: grid.fr_inv = {fr!r} must be one of {', '.join(map(str, INITIAL_CONDITIONS))} "
        "(the paper's runs of Sec. 3(ii))",
    )
    _check(
        isinstance(t_end, (int, float)) and not isinstance(t_end, bool) and t_end > 0,
        f"{p}: t_end = {t_end!r} must be a number > 0",
    )
    return Recipe(**common, t_end=float(t_end))


def bifurcation_datasets(recipe: Recipe) -> dict[str, xr.Dataset]:
    """The bifurcation diagram of the recipe's top (``kind = "bifurcation"``):
    :func:`stability.steady.diagram.bifurcation_diagram` in the recipe's ``unit`` (default rpm)
    with the runs launched upright at ``runs`` (``runs_rpm`` of the older recipes), and for the
    Table 1 preset also the paper's Fr^-1 = 0.3 run of Sec. 3(ii).

    Returns
    -------
    dict
        ``"branch"``, ``"vertical"``, ``"runs"``, sharing the abscissa ``spin`` (the equivalent
        upright spin, in ``unit``).
    """
    from .steady.diagram import bifurcation_diagram

    top = _recipe_top(recipe)
    alpha_v = recipe.grid.get("alpha_v")
    out = bifurcation_diagram(
        top,
        unit=recipe.unit,
        alpha_v=None if alpha_v is None and top.mu_v is not None else float(0.5 if alpha_v is None else alpha_v),
        runs=recipe.runs_rpm,
        paper_run=recipe.top is None and recipe.figure == "table1",
    )
    for ds in out.values():
        ds.attrs.update(title=recipe.title, preset=recipe.figure or "")
    return out


def classes_dataset(recipe: Recipe) -> dict[str, xr.Dataset]:
    """The class map (``kind = "classes"``): :func:`stability.class_atlas` over the grid."""
    from .steady.classes import class_atlas

    ds = class_atlas(q=recipe.grid["q"], sigma=recipe.grid["sigma"], mu=float(recipe.grid.get("mu", 2.28)))
    ds.attrs["recipe"] = recipe.path.name
    return {"classes": ds}


def settle_dataset(recipe: Recipe) -> dict[str, xr.Dataset]:
    """The paper's run continued to ``t_end`` (``kind = "settle"``), with the final state
    :func:`stability.final_state` predicts from its initial state in the attributes."""
    from .nonlinear import scene
    from .steady.final import final_state
    from .steady.states import steady_states

    fr = float(recipe.grid.get("fr_inv", 0.3))
    run = scene.run(fr, t_end=recipe.t_end, dt=max(0.5, recipe.t_end / 20000.0))
    end = final_state(fr_inv=fr, alpha_v=0.5, **scene.PAPER, **scene.INITIAL_CONDITIONS[fr])
    states = steady_states(fr_inv=fr, alpha_v=0.5, **scene.PAPER, jellett=end.jellett)
    rate = float(states.growth_rate[np.argmin(np.abs(states.tilt.values - end.tilt))])
    run.attrs.update({f"predicted_{k}": getattr(end, k) for k in ("tilt", "kind", "method", "axial_spin")})
    run.attrs.update(predicted_growth_rate=rate, jellett=end.jellett, label=f"Fr$^{{-1}}$ = {fr:g}")
    return {"run": run}


#: each steady kind: the datasets it writes (the first is <name>.nc, the others <name>_<key>.nc)
#: and the call that makes them all
_STEADY: dict[str, tuple[tuple[str, ...], Callable[[Recipe], dict[str, xr.Dataset]]]] = {
    "bifurcation": (("branch", "vertical", "runs"), bifurcation_datasets),
    "classes": (("classes",), classes_dataset),
    "settle": (("run",), settle_dataset),
}
