"""Closed-form solutions: Crank's one-dimensional series, their products for the parts
whose shape separates, the Fickian modes of those parts, and the exact two-phase sheet."""
