"""Linear stability of the upright spin: spectra of the linear models and what is built on them.

Layer 2 (docs/architecture.md): imports :mod:`stability.models`, :mod:`stability.parameters`
and the generic :mod:`continuation` engine, never the grids, the nonlinear runs, the figures or
the command line.

* :mod:`~stability.linear.roots` - structured polynomial roots and their error bounds, and the
  polynomial building blocks every engine shares (Horner, the quadratic formula, deflation);
* :mod:`~stability.linear.kernel` - the compiled default eigenvalue method;
* :mod:`~stability.linear.spectra` - :func:`~stability.linear.spectra.eigenvalues`,
  :func:`~stability.linear.spectra.spectrum` and the marginal decision;
* :mod:`~stability.linear.modes` - mode tracking along a path;
* :mod:`~stability.linear.neutrality` - the neutral condition ``p(i w) = 0``;
* :mod:`~stability.linear.critical` - thresholds and the critical spin of a real top;
* :mod:`~stability.linear.neutral_curves`, :mod:`~stability.linear.neutral_compiled` - neutral
  curves and folds by continuation (clients of :mod:`continuation`);
* :mod:`~stability.linear.control_forms` - python-control forms of the operators.
"""
