"""Paper B: J. Zhang, Y. Wang, L. Guan, Y. Zhang, S. Yang, *Symmetry* 16 (2024) 741: a cage-less 6206 ball
bearing with a functional slot, whose neighbouring balls collide through an oil film.

- :mod:`.parameters`: its parameter tables as a case-file parameter set (``parameters = "Zhang2024"``);
- :mod:`.figures`: its figures (settling, Poincare sections, angular displacement, spectra, quadrants)
  drawn from a run of :mod:`lubedyn.scenes.dynamics`.
"""
