"""The Fickian models ``solve`` chooses between: the exact series superposed
(``analytic``), the finite-volume meshes (``finite_volume``: slab, axisymmetric, solid)
and the plane model of prismatic parts (``plane``)."""
