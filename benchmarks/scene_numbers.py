"""Print the numbers of the tumbling runs of Sec. 3(ii) beside the paper's.

Usage: python benchmarks/scene_numbers.py
"""

from __future__ import annotations

from stability.nonlinear.scene import PAPER_NUMBERS, friction_cases, scene_numbers


def main() -> None:
    for fr in (0.3, 0.1):
        n = scene_numbers(fr)
        print(
            f"fr_inv = {fr}: crossing after {n['crossing_periods']:.2f} spin periods "
            f"(paper {PAPER_NUMBERS['crossing_periods'][fr]:.0f}); run took {n['seconds']:.3f} s"
        )
        for k, v in n.items():
            print(f"    {k:34s} {v: .6g}")
    for scheme in ("adaptive", "fixed_step"):
        ds = friction_cases(0.3, scheme=scheme)
        print(f"Fig. 9(b) friction cases, scheme = {scheme}")
        print(ds.to_dataframe().to_string())


if __name__ == "__main__":
    main()
