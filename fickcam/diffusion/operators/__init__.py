"""Discrete operators M dc/dt + K c = g f of every mesh model (``Discretisation``): the
one FiPy backend (``fipy_backend``), the finite-volume grids and prisms it assembles,
the hand-written P1 elements of the plane model, and how many cells each needs."""
