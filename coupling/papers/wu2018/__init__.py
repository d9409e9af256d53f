"""Paper A: Z.-H. Wu, Y.-Q. Xu, S.-E. Deng, "Analysis of dynamic characteristics of grease-lubricated tapered roller
bearings", *Shock and Vibration* 2018, 7183042.

- :mod:`.parameters`: its parameter tables as a case-file parameter set (``parameters = "Wu2018"``);
- :mod:`.claims`: its claims, figure by figure, checked against the project's studies
  (``studies/trb_*.toml``).
"""
