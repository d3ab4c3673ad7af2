"""``python -m stability`` runs the ``tippe`` command line."""

import sys

from .cli import main

sys.exit(main())
