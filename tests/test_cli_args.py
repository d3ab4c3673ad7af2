"""The shared helpers of the command modules (stability/commands/_args.py): the table a command
prints and the keywords it passes to the library."""

from __future__ import annotations

import argparse

from stability.commands._args import keywords, table


def test_table_aligns_the_header_as_the_columns():
    """Reference: the header and row of ``tippe steady``'s table written out by hand as
    f-strings (the form the command printed before the shared helper): left-aligned text,
    right-aligned numbers and names, a last column without width."""
    row = ("upright", 0.0, 1.0, 0.9, 1.1, -0.25, "unstable", "note")
    lines = table("{:<9} {:12.6f} {:12.6g} {:12.6g} {:12.8g} {:12.4g} {:>10}  {}", [*"abcdefgh"], [row])
    assert lines[0] == f"{'a':<9} {'b':>12} {'c':>12} {'d':>12} {'e':>12} {'f':>12} {'g':>10}  h"
    assert lines[1] == f"upright   {0.0:12.6f} {1.0:12.6g} {0.9:12.6g} {1.1:12.8g} {-0.25:12.4g} {'unstable':>10}  note"


def test_keywords_are_the_options_the_call_takes():
    """Only the call's own keywords are taken from the options (a flag's dest is the library's
    keyword); ``given`` overrides them. Reference: the signature written here."""

    def call(q, *, fr_inv, mu=2.28, engine=None):
        return q, fr_inv, mu, engine

    args = argparse.Namespace(q=0.1, fr_inv=0.3, mu=None, output="x.nc", overwrite=False)
    assert keywords(call, args, mu=1.0) == {"q": 0.1, "fr_inv": 0.3, "mu": 1.0}
