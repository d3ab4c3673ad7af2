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
    from ..plotting import save_figure, style
    from ..plotting.recipe_figures import recipe_figure
    from ..recipes import check_outputs, compute, find_recipes, load_recipe

    targets = args.recipes or ["atlases"]
    recipes = []
    for t in targets:
        path = Path(t)
        if not path.exists():
            raise FileNotFoundError(f"recipe {t!r} does not exist (give recipe files or directories)")
        if path.is_dir():
            found = find_recipes(path)
            if not found:
                raise InputError(f"no recipes (*.toml) in {str(path)!r}")
            recipes.extend(found)
        else:
            recipes.append(load_recipe(path))
    for recipe in recipes:  # every output writable before anything is computed
        check_outputs(recipe)
    for recipe in recipes:
        log: list = []
        datasets = compute(recipe, force=args.force, log=log)
        for path, action, seconds in log:
            if action == "reused":
                print(f"{recipe.name}: reused {path} (recipe and code unchanged)")
            else:
                print(f"{recipe.name}: computed {path} ({seconds:.1f} s)")
        with style():
            fig, _ = recipe_figure(recipe, datasets)
            save_figure(fig, recipe.figure_path)
        print(f"{recipe.name}: wrote {recipe.figure_path}")
    return 0
