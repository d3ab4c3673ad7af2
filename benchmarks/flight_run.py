"""A run that loses its contact, flies and lands (``on_contact_loss="continue"``): prints its
phases and draws ``atlases/flight_run.png`` (:func:`stability.plotting.plot_flight_run`).

The run: the issue's reproducer with omega = [4, 0, 1] and friction proportional to N
(``normal="actual"``, the only law with which the top can leave the floor smoothly;
docs/contact.md, "Flight and landing").

Usage: python benchmarks/flight_run.py [--out atlases/flight_run.png]
"""

from __future__ import annotations

import argparse

import numpy as np

import stability
from stability.plotting import plot_flight_run, save_figure


def main() -> None:
    """Run, print the take-offs, landings and impacts, and save the figure."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="atlases/flight_run.png")
    out = parser.parse_args().out
    k = np.array([0.3, 0.0, 1.0]) / np.hypot(0.3, 1.0)
    ds = stability.simulate(
        "sliding",
        t_end=30.0,
        dt=0.01,
        q=-0.1,
        fr_inv=0.05,
        sigma=1.0,
        alpha_v=0.5,
        omega=[4.0, 0.0, 1.0],
        k=k,
        velocity=[0.0, 0.0],
        normal="actual",
        on_contact_loss="continue",
    )
    a = ds.attrs
    print(f"flights {a['flights']}; impact law: {a['impact_law']}")
    for i, t0 in enumerate(a["takeoff_times"]):
        if i < len(a["landing_times"]):
            print(
                f"  take-off t = {t0:.9g}, landing t = {a['landing_times'][i]:.9g}, contact point's "
                f"vertical velocity {a['impact_contact_velocity_before'][i]:.6g} -> "
                f"{a['impact_contact_velocity_after'][i]:.2g}, impulse {a['impact_impulse_vertical'][i]:.6g}, "
                f"energy dissipated {a['impact_energy_loss'][i]:.6g}"
            )
        else:
            print(f"  take-off t = {t0:.9g}, still in the air at t_end")
    fig, _ = plot_flight_run(ds)
    save_figure(fig, out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
