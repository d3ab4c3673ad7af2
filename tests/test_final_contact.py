"""final_state says whether the sphere stays on the floor (``FinalState.contact``).

References: the normal force at the start against the independent vertical equation of
tests/test_contact_loss.py (Newton for G, Euler about G), to 1e-12 (round-off of two 6 x 6
solves); a start with N < 0 reports no end state; the Jellett path says the transient is not
checked.
"""

import numpy as np
import pytest
from test_contact_loss import MU, _accelerations

import stability
from stability.nonlinear.scene import INITIAL_CONDITIONS


def _unit(v):
    return np.asarray(v, float) / np.linalg.norm(v)


@pytest.mark.parametrize("omega", [[2.0, 0.0, 0.0], [0.0, 2.0, 0.5]])
def test_a_start_without_normal_force_has_no_end_state(omega):
    k = _unit([0.3, 0, -1])
    n_ref = _accelerations(np.concatenate([omega, k, [0.0, 0.0]]), -0.1, 0.05, 1.0, 0.5, MU)[5]
    assert n_ref < 0
    for simulation in (False, True):
        end = stability.final_state(
            q=-0.1, sigma=1.0, fr_inv=0.05, alpha_v=0.5, omega=omega, k=k, velocity=[0, 0], simulation=simulation
        )
        assert end.kind == "contact_lost" and end.contact == "lost" and end.state is None
        assert end.event == "contact_lost" and end.event_time == 0.0
        assert f"N = {n_ref:.6g}" in end.reason
        assert end.to_dataset().attrs["contact"] == "lost"


def test_jellett_answer_says_contact_was_not_checked():
    end = stability.final_state(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, **INITIAL_CONDITIONS[0.3])
    assert end.method == "jellett" and end.kind == "tilted"
    assert end.contact == "not checked"
    assert "contact not checked on the way" in end.reason
    ic = INITIAL_CONDITIONS[0.3]
    y = np.concatenate([ic["omega"], _unit(ic["k"]), np.asarray(ic.get("velocity", [0.0, 0.0]))[:2]])
    n_ref = _accelerations(y, -0.1, 0.3, 1.0, 0.5, MU)[5]
    assert f"N = {n_ref:.6g} at the start" in end.reason
