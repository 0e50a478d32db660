"""The climate as the solvers see it: the rescaled clock that absorbs the temperature
history, and a long record as a surface value piecewise linear in that clock."""
