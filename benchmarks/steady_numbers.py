"""Print the validation numbers of the steady states (docs/steady_states.md, sec. 9).

Usage: python benchmarks/steady_numbers.py   (about a minute; the long runs are in
tests/test_steady_final.py and the timings in benchmarks/bench_steady.py)

Each number is measured against an independent reference: the compiled right-hand sides of the
nonlinear models, eq. (11) (stability.spectrum, stability.thresholds, stability.critical_spin),
the energy criterion, the closed forms of stability.steady.family, the literature's conditions.
"""

from __future__ import annotations

import math

import numpy as np

import stability
from stability.nonlinear import rolling, sliding
from stability.nonlinear.parameters import pack
from stability.nonlinear.scene import INITIAL_CONDITIONS
from stability.steady import family
from stability.steady.branch import branch_points
from stability.steady.linearisation import ROTATION, modes_verdict, reduced_spectrum

MU = 2.28


def random_tops(n, seed):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        mu = MU if rng.random() < 0.7 else rng.uniform(0.5, 5.0)
        qm = min(0.45, 0.95 / math.sqrt(mu))
        q = rng.uniform(-qm, qm)
        out.append(
            dict(
                q=q,
                sigma=rng.uniform(0.05, 2 * (1 - mu * q * q)),
                fr_inv=rng.uniform(0.01, 2.0),
                alpha_v=math.exp(rng.uniform(math.log(0.05), math.log(5.0))),
                mu=mu,
            )
        )
    return out, rng


def residuals() -> None:
    tops, rng = random_tops(3000, 1)
    worst = {"sliding": 0.0, "rolling": 0.0}
    n = 0
    for t in tops:
        c = rng.uniform(-1, 1)
        lam = family.precession_rate(
            c, q=t["q"], sigma=t["sigma"], fr_inv=t["fr_inv"], mu=t["mu"], sign=rng.choice([-1.0, 1.0])
        )
        if not math.isfinite(lam):
            continue
        y = family.state_vector(math.acos(c), lam, t["q"], phi=rng.uniform(0, 2 * np.pi))
        p = pack(q=t["q"], fr_inv=t["fr_inv"], sigma=t["sigma"], mu=t["mu"], alpha_v=t["alpha_v"])
        g = ROTATION @ y
        f = sliding.rhs(0.0, np.concatenate([y, [0.0, 0.0]]), p)[:8] - lam * g
        worst["sliding"] = max(worst["sliding"], np.max(np.abs(f)) / max(1.0, lam * lam))
        f = rolling.rhs(0.0, np.concatenate([y[:6], [0.0, 0.0]]), p)[:6] - lam * g[:6]
        worst["rolling"] = max(worst["rolling"], np.max(np.abs(f)) / max(1.0, lam * lam))
        n += 1
    print(
        f"A. {n} closed-form steady states, residual of the compiled rhs in the precessing frame / max(1, lam^2): "
        f"sliding {worst['sliding']:.1e}, rolling {worst['rolling']:.1e}"
    )


def vertical_and_tilted() -> None:
    tops, rng = random_tops(300, 3)
    worst = 0.0
    agree = total = 0
    for t in tops:
        ds = stability.steady_states(jellett=rng.uniform(0.2, 3.0) * rng.choice([-1, 1]), **t)
        for i in np.nonzero(ds.kind.values != "tilted")[0]:
            s = ds.isel(state=i)
            ref = stability.spectrum(
                "sliding",
                q=float(s.equivalent_q),
                fr_inv=float(s.equivalent_fr_inv),
                sigma=t["sigma"],
                alpha_v=float(s.equivalent_alpha_v),
                mu=t["mu"],
            )
            lin = ref.eigenvalues * abs(float(s.omega_vertical))
            both = np.sort_complex(np.concatenate([lin, lin.conj()]))
            got = np.sort_complex(s.mode_growth_rate.values + 1j * s.mode_frequency.values)
            worst = max(worst, np.max(np.abs(got - both)) / max(1.0, np.max(np.abs(both))))
            agree += int(s.stability) == int(ref.stability)
            total += 1
    print(
        f"B. vertical states: 6 eigenvalues vs eq. (11) at the equivalent spin (x |n|, and conjugates): "
        f"max diff / max(1, |s|) {worst:.1e}; verdicts equal {agree}/{total}"
    )
    tops, rng = random_tops(2000, 4)
    agree = total = 0
    max_complex = -np.inf
    for t in tops:
        cs = rng.uniform(-0.995, 0.995, 8)
        lam = family.precession_rate(cs, q=t["q"], sigma=t["sigma"], fr_inv=t["fr_inv"], mu=t["mu"])
        ok = np.isfinite(lam)
        if not ok.any():
            continue
        cs, lam = cs[ok], lam[ok]
        p = pack(q=t["q"], fr_inv=t["fr_inv"], sigma=t["sigma"], mu=t["mu"], alpha_v=t["alpha_v"])
        y = family.state_vector(np.arccos(cs), lam, t["q"])
        ev, scale = reduced_spectrum(y, lam, np.zeros(len(cs), bool), p, q=t["q"], sigma=t["sigma"], mu=t["mu"])
        _, _, verdict = modes_verdict(ev, scale)
        for i, c in enumerate(cs):
            J = lam[i] * family.d_of_c(c, t["q"], t["sigma"], t["mu"])
            test, size = family.energy_test("tilted", c, J, q=t["q"], sigma=t["sigma"], fr_inv=t["fr_inv"], mu=t["mu"])
            if abs(test) < 1e-9 * size:
                continue
            total += 1
            agree += (verdict[i] == 0) == (test > 0) and (verdict[i] == 2) == (test < 0)
            if test > 0:
                cplx = ev[i][np.abs(ev[i].imag) > 1e-9]
                if cplx.size:
                    max_complex = max(max_complex, cplx.real.max() / scale[i])
    print(
        f"C. tilted states: reduced-Jacobian verdict = energy criterion (sign of U_J'') in {agree}/{total}; "
        f"largest Re of a complex mode at an energetically stable state / ||A||: {max_complex:.1e} (no Hopf)"
    )


def branches() -> None:
    cases = [
        (-0.1, 1.0, 0.3),
        (-0.3, 0.5, 0.1),
        (0.2, 0.7, 0.3),
        (-0.2, 1.3, 0.5),
        (-0.15, 1.12, 0.3),
        (-0.295, 1.107, 1 / MU),
    ]
    worst = fold = 0.0
    for q, sigma, fr in cases:
        ds = stability.steady_branch(q=q, sigma=sigma, fr_inv=fr, alpha_v=0.5)
        c = np.cos(np.radians(ds.tilt.values))
        inner = ds.kind.values != "branch_point"
        lam = family.precession_rate(c, q=q, sigma=sigma, fr_inv=fr, mu=MU)
        worst = max(
            worst,
            np.max(np.abs(ds.precession_rate.values[inner] - lam[inner]) / lam[inner]),
            np.max(
                np.abs(ds.jellett.values[inner] - lam[inner] * family.d_of_c(c[inner], q, sigma, MU))
                / ds.jellett.values[inner]
            ),
        )
        f = np.cos(np.radians(ds.tilt.values[ds.kind.values == "fold"]))
        ref = [x for x in family.fold_cosines(q, sigma, MU) if -1 < x < 1]
        for x in f:
            fold = max(fold, min(abs(x - r) for r in ref))
        kinds = [f"{k} {float(t):.4f}" for k, t in zip(ds.kind.values, ds.tilt.values) if k]
        print(f"   q={q:+.3f} sigma={sigma} fr_inv={fr:.4g}: {ds.sizes['point']} points, {', '.join(kinds)}")
    print(
        f"D. traced branches vs the closed form (lam, J): max relative difference {worst:.1e}; folds vs "
        f"c0 -+ sqrt(D(c0)/(3a)): {fold:.1e} in cos(tilt)"
    )
    rng = np.random.default_rng(7)
    worst = 0.0
    n = 0
    for _ in range(40):
        q = rng.uniform(-0.4, 0.4)
        sigma = rng.uniform(0.1, 1.9 * (1 - MU * q * q))
        fr = rng.uniform(0.05, 1.5)
        bp = branch_points(q=q, sigma=sigma, fr_inv=fr, alpha_v=0.5)
        for orient, sgn in (("upright", 1.0), ("inverted", -1.0)):
            if not math.isfinite(bp[orient]):
                continue
            spin = bp[orient] / (sigma * (1 + sgn * q))
            th = min(
                stability.thresholds("fr_inv", q=sgn * q, sigma=sigma, alpha_v=0.5), key=lambda v: abs(v - fr / spin**2)
            )
            worst = max(worst, abs(th - fr / spin**2) / th)
            n += 1
    top = stability.Top.table1()
    out = []
    for orient, sgn in (("upright", 1.0), ("inverted", -1.0)):
        cs = stability.critical_spin(top, orientation=orient)
        j = branch_points(q=top.q, sigma=top.sigma, fr_inv=cs.fr_inv, mu=top.mu)[orient]
        out.append(
            f"{orient} {cs.rpm:.4f} rpm: J_b / (sigma (1 {'+' if sgn > 0 else '-'} q)) = "
            f"{j / (top.sigma * (1 + sgn * top.q)):.15f}"
        )
    print(f"E. {n} branch points (nonlinear rhs) vs stability.thresholds (eq. 11): max relative difference {worst:.1e}")
    print(f"   Table 1 top at its critical spins: {'; '.join(out)}")
    fr = float(top.fr_inv(1.0, unit="rpm"))
    bp = branch_points(q=top.q, sigma=top.sigma, fr_inv=fr, mu=top.mu)
    rpm = {k: v / (top.sigma * (1 + top.q)) for k, v in bp.items()}
    print(
        f"   launch spins of the branch points (upright launch, J = sigma (1 + q) Omega): upright "
        f"{rpm['upright']:.4f} rpm, inverted {rpm['inverted']:.4f} rpm; between them the top hangs"
    )


def classes_and_paper() -> None:
    rng = np.random.default_rng(1)
    q = rng.uniform(-0.66, 0.66, 1_000_000)
    sigma = rng.uniform(0.0, 2.0, 1_000_000)
    names = stability.top_class(q=q, sigma=sigma, mask_unphysical=True)
    inside = names != "outside_domain"
    gamma = (1 - MU * q * q) / sigma
    hug = (q < 0) & (1 + q < gamma) & (gamma < 1 - q)
    counts = {str(k): int(v) for k, v in zip(*np.unique(names[inside], return_counts=True))}
    print(
        f"F. 1e6 random tops: {counts}; 'inverts' vs Hugenholtz 1 - alpha < A_G/C < 1 + alpha: "
        f"{int(np.sum((names == 'inverts')[inside] != hug[inside]))} mismatches"
    )
    for fr in (0.3, 0.1):
        end = stability.final_state(q=-0.1, sigma=1.0, fr_inv=fr, alpha_v=0.5, **INITIAL_CONDITIONS[fr])
        jinv = family.branch_point_jellett("inverted", q=-0.1, sigma=1.0, fr_inv=fr, mu=MU)
        cands = ", ".join(
            f"{c.kind} {c.tilt:.6f} E={c.energy:.7f} {('stable', 'marginal', 'unstable')[c.stability]}"
            for c in end.candidates
        )
        print(
            f"G. paper run Fr^-1 = {fr}: J0 = {end.jellett:.7f}, |J_inv| = {jinv:.7f}; ends {end.kind} at "
            f"{end.tilt:.6f} deg ({end.method}), axial spin {end.axial_spin:.5f}, energy {end.energy:.7f}; "
            f"candidates: {cands}"
        )


def main() -> None:
    residuals()
    vertical_and_tilted()
    branches()
    classes_and_paper()


if __name__ == "__main__":
    main()
