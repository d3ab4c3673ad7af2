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

A ``kind = "scene"`` recipe names instead one of the paper's nonlinear figures,
``figure = "fig5"`` ... ``"fig9"``, drawn from the runs of Sec. 3(ii) (:mod:`stability.nonlinear.scene`);
it has no grid.

The outputs are ``<name>.nc`` (regenerated, not committed) and ``<name>.png`` (committed when the
README shows it) beside the recipe, ``<name>`` being the recipe's file stem. A dataset already on
disk is reused when its ``recipe_digest`` attribute matches the digest of the recipe's contents
and of the package's source code (:func:`code_fingerprint`): a dataset computed by another
version of the code is recomputed, never reused.
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import tomllib
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from .grids.atlases import atlas
from .errors import AtlasFileError, RecipeError
from .grids.netcdf import check_output_path, open_atlas, write_dataset
from .grids.ranges import parse_values
from .models import MODELS
from .parameters import LONG_NAMES, PARAMETERS
from .products import PRODUCT_ATTR

__all__ = ["Recipe", "load_recipe", "find_recipes", "compute", "check_outputs", "output_paths",
           "KINDS"]

#: what a recipe can draw
KINDS = ("lines", "map", "models", "scene", "critical_spin")
#: the paper's nonlinear figures a scene recipe can draw
SCENE_FIGURES = ("fig5", "fig6", "fig7", "fig8", "fig9")
QUANTITIES = ("growth_rate", "frequency")
_KEYS = {"title", "kind", "model", "x", "y", "family", "quantities", "mask_unphysical", "grid", "caption",
         "figure", "neutral", "preset"}


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


def _grid_value(path: Path, key: str, value: Any) -> float | np.ndarray:
    if isinstance(value, bool):
        raise RecipeError(f"{path}: grid.{key} = {value!r} is not a number, a list or 'start:stop:num'")
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, list):
        try:
            return np.array([float(v) for v in value])
        except (TypeError, ValueError):
            raise RecipeError(f"{path}: grid.{key} = {value!r} is not a list of numbers") from None
    if isinstance(value, str):
        try:
            return parse_values(value, name=f"grid.{key}")
        except ValueError as exc:
            raise RecipeError(f"{path}: {exc}") from None
    raise RecipeError(f"{path}: grid.{key} = {value!r} is not a number, a list or 'start:stop:num'")


def load_recipe(path: str | Path) -> Recipe:
    """Read and check a recipe file.

    Raises
    ------
    RecipeError
        Missing file, bad TOML, unknown keys, or values outside their choices; the message
        names the file and the key.
    """
    p = Path(path)
    if not p.is_file():
        raise RecipeError(f"recipe {str(p)!r} does not exist")
    raw_bytes = p.read_bytes()
    try:
        raw = tomllib.loads(raw_bytes.decode())
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise RecipeError(f"{p}: not valid TOML ({exc})") from None
    unknown = set(raw) - _KEYS
    if unknown:
        raise RecipeError(f"{p}: unknown keys {', '.join(sorted(unknown))} (allowed: {', '.join(sorted(_KEYS))})")
    for key in ("title", "kind"):
        if key not in raw:
            raise RecipeError(f"{p}: the key {key!r} is required")
    kind = raw["kind"]
    if kind not in KINDS:
        raise RecipeError(f"{p}: kind = {kind!r} is not one of {', '.join(KINDS)}")
    digest = hashlib.sha256(raw_bytes + code_fingerprint().encode()).hexdigest()[:16]
    if kind == "scene":
        figure = raw.get("figure")
        if figure not in SCENE_FIGURES:
            raise RecipeError(f"{p}: figure = {figure!r} is not one of {', '.join(SCENE_FIGURES)}")
        if "grid" in raw:
            raise RecipeError(f"{p}: a scene recipe has no [grid] (its runs are those of Sec. 3(ii))")
        return Recipe(path=p, title=str(raw["title"]), kind=kind, model="sliding", grid={},
                      caption=str(raw.get("caption", "")), figure=figure, digest=digest)
    if "grid" not in raw:
        raise RecipeError(f"{p}: the key 'grid' is required")
    model = raw.get("model", "sliding")
    if model not in MODELS:
        raise RecipeError(f"{p}: model = {model!r} is not one of {', '.join(MODELS)}")
    if kind == "critical_spin":
        preset = raw.get("preset", "table1")
        if preset not in PRESETS:
            raise RecipeError(f"{p}: preset = {preset!r} is not one of {', '.join(PRESETS)}")
        x = raw.get("x", "q")
        if x not in ("q", "sigma") or set(raw["grid"]) != {x}:
            raise RecipeError(f"{p}: a critical_spin recipe varies one of q, sigma: [grid] must hold only x = {x!r}")
        grid = {x: _grid_value(p, x, raw["grid"][x])}
        if np.ndim(grid[x]) != 1:
            raise RecipeError(f"{p}: {x!r} must be a 1-D grid (a list or 'start:stop:num')")
        return Recipe(path=p, title=str(raw["title"]), kind=kind, model=model, grid=grid, x=x,
                      caption=str(raw.get("caption", "")), figure=preset, digest=digest)
    grid_raw = raw["grid"]
    if not isinstance(grid_raw, dict):
        raise RecipeError(f"{p}: [grid] must be a table of parameter values")
    bad = set(grid_raw) - set(PARAMETERS)
    if bad:
        raise RecipeError(f"{p}: grid has unknown parameters {', '.join(sorted(bad))} (allowed: {', '.join(PARAMETERS)})")
    grid = {k: _grid_value(p, k, v) for k, v in grid_raw.items()}
    quantities = tuple(raw.get("quantities", ["growth_rate"]))
    for qn in quantities:
        if qn not in QUANTITIES:
            raise RecipeError(f"{p}: quantities has {qn!r}, not one of {', '.join(QUANTITIES)}")
    arrays = [k for k, v in grid.items() if np.ndim(v) == 1]
    x, y, family = raw.get("x", "q"), raw.get("y"), raw.get("family")
    wanted = {"lines": [x] + ([family] if family else []), "map": [x, y], "models": [x, y]}[kind]
    for name in wanted:
        if name is None:
            raise RecipeError(f"{p}: kind = {kind!r} needs the key 'y'")
        if name not in arrays:
            raise RecipeError(f"{p}: {name!r} must be a 1-D grid (a list or 'start:stop:num') for kind = {kind!r}")
    if sorted(arrays) != sorted(wanted):
        raise RecipeError(f"{p}: grid dimensions {', '.join(arrays)} do not match what kind = {kind!r} draws "
                          f"({', '.join(wanted)})")
    return Recipe(path=p, title=str(raw["title"]), kind=kind, model=model, grid=grid, x=x, y=y, family=family,
                  quantities=quantities, mask_unphysical=bool(raw.get("mask_unphysical", True)),
                  caption=str(raw.get("caption", "")), neutral=bool(raw.get("neutral", False)), digest=digest)


def find_recipes(directory: str | Path) -> list[Recipe]:
    """All recipes (``*.toml``) in ``directory``, sorted by name."""
    return [load_recipe(p) for p in sorted(Path(directory).glob("*.toml"))]


def _grid_for(model: str, grid: dict[str, Any]) -> dict[str, Any]:
    takes = MODELS[model].parameters
    return {k: v for k, v in grid.items() if k in takes}


def _cached(path: Path, digest: str, make: Callable[[], xr.Dataset], *, force: bool,
            reader: Callable[[Path], xr.Dataset]) -> xr.Dataset:
    """Reuse ``path`` if it holds the dataset of this recipe version, else make and write it.

    A file at ``path`` that is not a recipe's dataset is refused unless ``force`` (module
    docstring)."""
    if path.exists() and not force:
        try:
            ds = reader(path)
        except (AtlasFileError, OSError, ValueError) as exc:
            raise RecipeError(f"{path} exists and was not written by a recipe ({exc}); remove it or "
                              "pass force=True to replace it") from None
        if ds.attrs.get("recipe_digest") == digest:
            return ds
        if "recipe_digest" not in ds.attrs:
            raise RecipeError(f"{path} exists and was not written by a recipe (it has no recipe_digest "
                              "attribute); remove it or pass force=True to replace it")
    ds = make()
    ds.attrs["recipe_digest"] = digest
    write_dataset(ds, path, overwrite=True)
    return ds


def output_paths(recipe: Recipe) -> list[Path]:
    """Every file :func:`compute` and ``tippe figures`` may write for ``recipe``."""
    paths = [recipe.figure_path]
    if recipe.kind == "scene":
        return paths + [recipe.path.with_name(f"{recipe.name}_{k}.nc") for k in scene_runs(recipe.figure or "")]
    if recipe.kind == "critical_spin":
        return paths + [recipe.dataset_path]
    for model in recipe.models():
        path = recipe.dataset_path if recipe.kind != "models" else recipe.path.with_name(f"{recipe.name}_{model}.nc")
        paths.append(path)
        if recipe.neutral:
            paths.append(path.with_name(path.stem + "_neutral.nc"))
    return paths


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


def _read(path: Path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def scene_runs(figure: str) -> dict[str, tuple[str, Callable[[], xr.Dataset]]]:
    """The runs a scene figure needs: key -> (label, function making the run)."""
    from .nonlinear import scene

    paper = dict(method="rk4", step=0.1, friction="componentwise", slip_scale=1e-12)
    runs: dict[str, tuple[str, Callable[[], xr.Dataset]]] = {
        "fr_inv_0.3": ("Fr$^{-1}$ = 0.3", lambda: scene.run(0.3)),
    }
    if figure == "fig5":
        runs["fr_inv_0.1"] = ("Fr$^{-1}$ = 0.1", lambda: scene.run(0.1))
    if figure == "fig9":
        runs["rolling"] = ("rolling", lambda: scene.run(0.3, model="rolling"))
        for j, (ak, av) in enumerate(scene.FRICTION_CASES, start=1):
            label = f"({j}) $\\alpha_K$ = {ak:g}, $\\alpha_v$ = {av:g}"
            runs[f"case{j}"] = (label, lambda ak=ak, av=av: scene.run(0.3, alpha_k=ak, alpha_v=av,
                                                                      t_end=1500.0, dt=0.5))
            runs[f"case{j}_paper_scheme"] = (label, lambda ak=ak, av=av: scene.run(
                0.3, alpha_k=ak, alpha_v=av, t_end=1500.0, dt=0.5, **paper))
    return runs


def compute(recipe: Recipe, *, force: bool = False) -> dict[str, xr.Dataset]:
    """Compute (or reuse from disk) the recipe's datasets.

    A dataset on disk is reused when its ``recipe_digest`` attribute equals the recipe's;
    otherwise it is recomputed and written atomically.

    Returns
    -------
    dict
        model name -> atlas dataset, or (scene recipes) run key -> simulate() dataset with the
        run's label in its ``label`` attribute.
    """
    out: dict[str, xr.Dataset] = {}
    if recipe.kind == "critical_spin":
        out[recipe.model] = _cached(recipe.dataset_path, recipe.digest, lambda: critical_spin_dataset(recipe),
                                    force=force, reader=_read)
        return out
    if recipe.kind == "scene":
        for key, (label, make) in scene_runs(recipe.figure or "").items():
            def made(make=make, label=label) -> xr.Dataset:
                ds = make()
                ds.attrs["label"] = label
                return ds
            out[key] = _cached(recipe.path.with_name(f"{recipe.name}_{key}.nc"), recipe.digest, made,
                               force=force, reader=_read)
        return out
    for model in recipe.models():
        path = recipe.dataset_path if recipe.kind != "models" else recipe.path.with_name(f"{recipe.name}_{model}.nc")

        def make(model=model) -> xr.Dataset:
            ds = atlas(model, mask_unphysical=recipe.mask_unphysical, **_grid_for(model, recipe.grid))
            ds.attrs["recipe"] = recipe.path.name
            return ds
        out[model] = _cached(path, recipe.digest, make, force=force, reader=open_atlas)
        if recipe.neutral:
            out[f"{model}_neutral"] = _cached(path.with_name(path.stem + "_neutral.nc"), recipe.digest,
                                              lambda model=model: _neutral(recipe, model), force=force, reader=_read)
    return out


#: real tops a critical_spin recipe can name
PRESETS = ("table1", "table1_measured")


def critical_spin_dataset(recipe: Recipe) -> xr.Dataset:
    """Critical spin rates (rpm) of the preset top against the recipe's grid parameter.

    For every value, a :class:`stability.Top` with the preset's mass and radius and the
    nondimensional set changed in that one parameter (:meth:`stability.Top.from_nondimensional`)
    is handed to :func:`stability.critical_spin`, upright and inverted; NaN where there is no
    transition in the range searched.
    """
    from .linear.critical import critical_spin
    from .top import Top

    base = getattr(Top, recipe.figure or "table1")()
    x = recipe.x
    values = np.asarray(recipe.grid[x], dtype=float)
    out = {"upright": np.full(values.size, np.nan), "inverted": np.full(values.size, np.nan)}
    for j, v in enumerate(values):
        nd = {"q": base.q, "mu": base.mu, "sigma": base.sigma, x: float(v)}
        top = Top.from_nondimensional(mass=base.mass, radius=base.radius, **nd)
        for orientation in out:
            try:
                out[orientation][j] = critical_spin(top, recipe.model, orientation).rpm
            except ValueError:
                pass
    unit = {"units": "min-1"}
    return xr.Dataset(
        {"critical_spin_upright": (x, out["upright"], {"long_name": "spin rate above which the upright top is unstable", **unit}),
         "critical_spin_inverted": (x, out["inverted"], {"long_name": "spin rate above which the inverted top is stable", **unit})},
        coords={x: (x, values, {"long_name": LONG_NAMES[x], "units": "1"})},
        attrs={"Conventions": "CF-1.10", "title": recipe.title, PRODUCT_ATTR: "critical_spin",
               "model": recipe.model, "preset": recipe.figure,
               "mass_kg": base.mass, "radius_m": base.radius, "q": base.q, "mu": base.mu, "sigma": base.sigma})


def _neutral(recipe: Recipe, model: str) -> xr.Dataset:
    """Continued neutral curves of ``model`` over the recipe's (x, y) ranges."""
    from .linear.neutral_curves import neutral_curve

    grid = _grid_for(model, recipe.grid)
    fixed = {k: float(v) for k, v in grid.items() if np.ndim(v) == 0}
    xs, ys = np.asarray(grid[recipe.x]), np.asarray(grid[recipe.y or ""])
    ds = neutral_curve(model, recipe.x, recipe.y, fixed=fixed,
                       x_range=(float(xs.min()), float(xs.max())), y_range=(float(ys.min()), float(ys.max())))
    for name in ("kind", "detail"):
        if name in ds:
            ds[name] = ds[name].astype(str)
    return ds
