"""Spin units and plausible units of a real top (issue 23, items 1-2).

References: the definitions of the units (1 rev = 2 pi rad, 1 min = 60 s, 1 Hz = 1 rev/s
for a spin rate), and the issue's own example of a top given in grams and millimetres.
"""

import math
import warnings

import pytest

from stability.errors import DomainError
from stability.top import SPIN_UNITS, ImplausibleTopWarning, Top, check_launch_spin, from_rad_per_s, to_rad_per_s


@pytest.mark.parametrize(
    "unit,rad_per_unit", [("rad/s", 1.0), ("rev/s", 2 * math.pi), ("Hz", 2 * math.pi), ("rpm", 2 * math.pi / 60)]
)
def test_spin_units_by_definition(unit, rad_per_unit):
    # reference: the unit's definition; exact to rounding of one product (1 ulp)
    assert to_rad_per_s(3.0, unit) == pytest.approx(3.0 * rad_per_unit, rel=2e-16)
    assert from_rad_per_s(3.0 * rad_per_unit, unit) == pytest.approx(3.0, rel=4e-16)
    top = Top.table1()
    assert top.fr_inv(7.15, unit) == pytest.approx(top.g / ((7.15 * rad_per_unit) ** 2 * top.radius), rel=1e-15)


def test_one_table_of_units():
    assert set(SPIN_UNITS) == {"rad/s", "rev/s", "rpm", "Hz"}
    with pytest.raises(ValueError, match="unit = 'kHz' is not known"):
        to_rad_per_s(1.0, "kHz")


def test_grams_and_millimetres_refused():
    # the top (15 g, 15 mm, G 3 mm below O, A_G = 1.3e-6, C = 1.5e-6 kg m^2) given in g and mm
    with pytest.raises(DomainError, match=r"radius looks like millimetres.*sigma = 1.11e-08.*mass looks like grams"):
        Top(mass=15, radius=15, com_offset=-3, inertia_transverse=1.3e-6, inertia_axial=1.5e-6)


def test_inertias_in_g_mm2_refused():
    # 1 g mm^2 = 1e-9 kg m^2: inertias 1e9 too large make mu ~ 1e-9
    with pytest.raises(DomainError, match=r"mu = 2.6e-09 \(the inertias look too large.*1 g mm\^2"):
        Top(mass=0.015, radius=0.015, com_offset=-0.003, inertia_transverse=1300.0, inertia_axial=1500.0)


def test_grey_zone_warns_with_the_derived_values():
    with pytest.warns(ImplausibleTopWarning, match=r"mass looks like grams.*q = -0.2, mu = 24.8"):
        Top(mass=15, radius=0.015, com_offset=-0.003, inertia_transverse=1.3e-6, inertia_axial=1.5e-6)


def test_real_tops_pass_silently():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Top(mass=0.015, radius=0.015, com_offset=-0.003, inertia_transverse=1.3e-6, inertia_axial=1.5e-6)
        Top.table1()
        Top.table1_measured()
        Top(
            mass=0.02,
            radius=0.02,
            com_offset=-0.006,
            inertia_transverse=0.376 * 0.02 * 0.02**2,
            inertia_axial=0.4 * 0.02 * 0.02**2,
        )


@pytest.mark.parametrize("spin,unit", [(0.05, "rev/s"), (2e4, "Hz"), (3.0, "rpm"), (1e5, "rad/s")])
def test_launch_spin_range(spin, unit):
    with pytest.raises(
        DomainError, match=rf"spin = {spin:g} {unit} .* is outside the allowed range: 0.1 to 10000 rev/s"
    ):
        check_launch_spin(spin, unit)
    assert check_launch_spin(7.15, "rev/s") == pytest.approx(7.15 * 2 * math.pi, rel=1e-16)
