"""Compensation: the dry dimensions at the reference temperature to make so that
the mechanism has its design geometry at an ageing time, or stays closest to it over a
window (minimax); `fickcam compensate` and :func:`fickcam.compensate`.

Public API: :func:`~fickcam.compensation.solve.compensate` -> :class:`~fickcam.compensation.core.Compensation`, :func:`~fickcam.compensation.report.write_scene`,
:func:`~fickcam.compensation.report.dimension_table`; the printed report is
:func:`fickcam.compensation.report.report`.
"""
from .core import Compensation, Target
from .report import dimension_table, write_scene
from .solve import compensate

__all__ = ["Compensation", "Target", "compensate", "dimension_table", "write_scene"]
