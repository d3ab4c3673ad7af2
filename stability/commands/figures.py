"""``tippe figures``: run atlas recipes (atlases/*.toml): compute what is missing, then draw."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..errors import InputError

HELP = "compute and draw atlas recipes (atlases/*.toml)"
DESCRIPTION = (
    "Run atlas recipes: compute the datasets that are missing or out of date (netCDF beside each recipe) and "
    "draw their figures (PNG). A recipe's own outputs (<name>.png, <name>*.nc beside it) are replaced; a file "
    "there that no recipe wrote is refused unless --force. Each recipe names its models (default: sliding)."
)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe figures``."""
    p.add_argument("recipes", nargs="*", metavar="RECIPE", help="recipe files or directories (default: atlases/)")
    p.add_argument(
        "--force",
        action="store_true",
        help="recompute even when a matching dataset exists, and replace a file at a recipe's "
        "output path that was not written by a recipe (default: reuse, refuse)",
    )


def run(args: argparse.Namespace) -> int:
    """Run ``tippe figures``."""
    from .. import recipes as r
    from ..plotting import save_figure, style
    from ..plotting.recipe_figures import recipe_figure

    found = []
    for target in args.recipes or ["atlases"]:
        path = Path(target)
        if not path.exists():
            raise FileNotFoundError(f"recipe {target!r} does not exist (give recipe files or directories)")
        recipes = r.find_recipes(path) if path.is_dir() else [r.load_recipe(path)]
        if not recipes:
            raise InputError(f"no recipes (*.toml) in {str(path)!r}")
        found += recipes
    for recipe in found:  # every output writable before anything is computed
        r.check_outputs(recipe)
    for recipe in found:
        log: list = []
        datasets = r.compute(recipe, force=args.force, log=log)
        for path, action, seconds in log:
            why = "(recipe and code unchanged)" if action == "reused" else f"({seconds:.1f} s)"
            print(f"{recipe.name}: {action} {path} {why}")
        with style():
            fig, _ = recipe_figure(recipe, datasets)
            save_figure(fig, recipe.figure_path)
        print(f"{recipe.name}: wrote {recipe.figure_path}")
    return 0
