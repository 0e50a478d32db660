"""Time stepping of an operator: the geometric step plans, the theta-scheme marcher,
the unit-step response of an operator, and dense output between recorded steps."""
