"""The installed version of tippe-stability, read once.

Layer 0 (docs/architecture.md): imports nothing from the package. Every dataset's ``source``
attribute, the chunk store's identity and ``tippe --version`` take the version from here.
"""

from __future__ import annotations

import functools
from importlib.metadata import PackageNotFoundError, version

__all__ = ["DISTRIBUTION", "package_version"]

#: the distribution's name (PyPI); the import packages are ``stability`` and ``continuation``
DISTRIBUTION = "tippe-stability"


@functools.lru_cache(maxsize=1)
def package_version() -> str:
    """Installed version of tippe-stability (read once: importlib.metadata takes ~0.2 ms)."""
    try:
        return version(DISTRIBUTION)
    except PackageNotFoundError:  # pragma: no cover - source tree without install
        return "unknown"
