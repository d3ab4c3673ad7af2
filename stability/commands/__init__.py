"""Subcommands of the ``tippe`` command line, one module each (see :mod:`stability.cli`)."""
