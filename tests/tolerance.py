"""Tolerances for comparisons that hold exactly in exact arithmetic.

A result that equals its reference exactly in real arithmetic and is computed in a few
floating-point operations differs from it by at most about n u max|term|, with u the
unit round-off and n the number of operations (Higham, Accuracy and Stability of
Numerical Algorithms, 2nd ed., 2002, sec. 3.1, gamma_n). The tolerance therefore scales
with the magnitudes involved, not with one machine's last digits.
"""
from __future__ import annotations

import numpy as np

EPS = float(np.finfo(float).eps)


def roundoff(*magnitudes, operations: int = 64) -> float:
    """Absolute tolerance ``operations * eps * max|magnitude|`` (Higham sec. 3.1)."""
    scale = max(float(np.max(np.abs(m))) for m in magnitudes)
    return operations * EPS * scale
