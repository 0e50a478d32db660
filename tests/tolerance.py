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
TINY = float(np.finfo(float).tiny)  # the underflow threshold: below it results are subnormal


def roundoff(*magnitudes, operations: int = 64) -> float:
    """Absolute tolerance ``operations * (eps * max|magnitude| + tiny)`` (Higham sec. 3.1;
    the model of floating-point arithmetic with underflow, sec. 2.1: each operation errs by
    at most eps relative plus the underflow threshold absolute, so magnitudes that are zero
    still allow a subnormal result)."""
    scale = max(float(np.max(np.abs(m))) for m in magnitudes)
    return operations * (EPS * scale + TINY)
