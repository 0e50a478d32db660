"""How a prism's unit-step response is superposed over its exposure (``History``):
Duhamel's panels for a few segments, the tabulated sum over a long record, and a stored
record solve read at more times (``extension``, the limit search)."""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .duhamel import duhamel
from ..forcing.record import RECORD_SHARE, is_long_record
from ..planform.outline import outline_extent
from ..problem.results import DiffusionResult
from .tabulated import LongRecord, Same


def _kernel(fraction, scale: float):
    """K(tau) = 1 - u(tau*) for ``duhamel`` (rescaled s, any shape), tau* = scale tau."""
    def kernel(tau):
        tau = np.asarray(tau, float)
        u = np.asarray(fraction(tau.ravel() * scale), float)
        return 1.0 - u.reshape(tau.shape + u.shape[1:])
    return kernel


def _diffusion_times(geometry, d) -> tuple[float, float]:
    """(fastest, slowest) L^2 / D0 of a prism: the thickness and the planform extents."""
    sizes = (*outline_extent(geometry), geometry.thickness)
    times = [size ** 2 / d[i] for i, size in enumerate(sizes)]
    return min(times), max(times)


@dataclass(frozen=True)
class History:
    """How ``solve_plane`` superposes over the exposure: Duhamel's panels (``duhamel``) for
    a few segments; for a long record (``forcing.is_long_record``) the tabulated sum of
    ``tabulated``, cost linear in the rows, shared by the mean, the layer and the fields,
    within ``RECORD_SHARE`` of the accuracy (``plan`` designs the rest)."""

    diffusivity: object
    exposure: object
    times: np.ndarray
    geometry: object
    record: LongRecord | None

    @classmethod
    def of(cls, geometry, diffusivity, exposure, times, accuracy: float) -> "History":
        d = tuple(float(v) for v in diffusivity.pre_exponential)
        record = (LongRecord.of(diffusivity, exposure, times, _diffusion_times(geometry, d)[0],
                                RECORD_SHARE * accuracy) if is_long_record(exposure) else None)
        return cls(diffusivity, exposure, np.asarray(times, float), geometry, record)

    def at(self, times) -> "History":
        """The same history read at other ``times`` inside the outputs' span (a long record
        only: ``LongRecord.at``)."""
        return replace(self, times=np.asarray(times, float), record=self.record.at(times))

    def superpose(self, fraction, chunk: int = 64, fields: bool = False,
                  looser: float = 1.0, same: Same | None = None,
                  start: int = 0) -> tuple[np.ndarray, float, int]:
        """(c0 + Duhamel sum of the unit-step unsaturated fraction u(tau*), the error of the
        sum itself relative to the swing: 0 for the panels, whose quadrature is exact to
        ``calibration.ANALYTIC_ERROR``, the tables' points per decade: 0 for the panels).
        ``fields``: a wide kernel (``LongRecord.field``); ``looser``: a tolerance this many
        times the mean's (the contact layer); ``same``: which fraction this is
        (``tabulated.Same``), to reuse its tables across solves; ``start``: the points per
        decade an earlier solve of this fraction refined to (``LongRecord.superpose``)."""
        d = tuple(float(v) for v in self.diffusivity.pre_exponential)
        kernel = _kernel(fraction, d[2] / self.geometry.thickness ** 2)
        if self.record is None:
            return self.exposure.initial_moisture + duhamel(
                kernel, self.diffusivity, self.exposure, self.times,
                _diffusion_times(self.geometry, d), chunk=chunk), 0.0, 0
        if fields:
            return self.exposure.initial_moisture + self.record.field(kernel), 0.0, 0
        if same is not None:
            same = Same(same.key + (d[2] / self.geometry.thickness ** 2,), same.holds)
        values, error, level = self.record.superpose(kernel, looser=looser, same=same,
                                                     start=start)
        return self.exposure.initial_moisture + values, error, level


def extension(result: DiffusionResult, superposed):
    """``DiffusionResult.extend`` of a plane solve over a long record: the result at its
    times and ``at`` (inside their span) together, the new rows summed with the stored plan,
    planform response, forcing and tables (``History.at``), the stored rows as they are."""

    def extend(at) -> DiffusionResult:
        at = np.asarray(at, float)
        new = np.setdiff1d(at, result.times)
        mean, _, layer, _ = superposed(new)
        return result.merged(new, mean, layer)
    return extend
