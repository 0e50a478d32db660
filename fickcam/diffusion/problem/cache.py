"""The run's cache: what the solvers build once and read again (the rescaled clock of a
long record, planform meshes and step responses, Duhamel tables and their readings, a
two-phase planform's refinement), owned by whoever runs the solves and passed down.

``fickcam.simulation.simulate.run`` makes one per run (its plans, solves and the limit search share
it), a sweep worker one per worker process (its cases that share a part and material share
the solves); ``solve`` and ``plan`` make a fresh one when given none. Nothing is kept
between runs unless the caller hands the same cache on.

Every value stored is frozen: its arrays are made read-only (also inside the tuples,
lists, dicts and dataclasses it returns), so that no caller can change what a later one
reads and none needs a defensive copy. The cache holds at most ``budget`` bytes (the
arrays it can count), the least recently used entries dropped first (never the one just
stored). It is thread-safe: dask's threads may share it (two threads asking for one
missing entry may both build it; the first stored is kept and both get it).
"""
from __future__ import annotations

import dataclasses
import threading
import types
import weakref
from collections import OrderedDict
from typing import Any, Callable, Hashable

import numpy as np
from scipy import sparse

BUDGET = 2 ** 30   # bytes a run keeps at most (the arrays counted): 1 GiB
NOT_DATA = (type, types.FunctionType, types.MethodType, types.BuiltinFunctionType,
            types.ModuleType, str, bytes)


def freeze(value):
    """Make every array ``value`` holds read-only, in place, and return ``value``.

    Arrays, and the items of tuples, lists, dicts and dataclass fields, are visited
    recursively (each object once); other objects are left as they are.

    Parameters
    ----------
    value : object
        The value to freeze: an array or a container of arrays.

    Returns
    -------
    object
        ``value`` itself, its arrays no longer writeable.
    """
    _freeze(value, set())
    return value


def _freeze(value, seen: set) -> None:
    if id(value) in seen:
        return
    seen.add(id(value))
    if isinstance(value, np.ndarray):
        value.setflags(write=False)
    elif isinstance(value, (tuple, list)):
        for item in value:
            _freeze(item, seen)
    elif isinstance(value, dict):
        for item in value.values():
            _freeze(item, seen)
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        for item in dataclasses.fields(value):
            _freeze(getattr(value, item.name), seen)


def size_of(value) -> int:
    """Count the bytes of the arrays ``value`` holds.

    Arrays, sparse matrices and SuperLU factorisations are counted, and the items of
    tuples, lists, dicts, dataclass fields and plain objects' attributes are visited; each
    object is counted once, a view not at all (its base is).

    Parameters
    ----------
    value : object
        The value to measure.

    Returns
    -------
    int
        The bytes [B] of the arrays held.
    """
    return _size(value, set())


def _size(value, seen: set) -> int:
    if id(value) in seen or value is None or isinstance(value, (*NOT_DATA, RunCache)):
        return 0
    seen.add(id(value))
    if isinstance(value, np.ndarray):
        return value.nbytes if value.base is None else 0   # a view: its base is counted
    if sparse.issparse(value):
        return sum(_size(getattr(value, name, None), seen)
                   for name in ("data", "indices", "indptr", "row", "col", "offsets"))
    if hasattr(value, "nnz") and hasattr(value, "solve"):    # a SuperLU factorisation
        return 12 * int(value.nnz) + 8 * int(value.shape[0])
    if isinstance(value, (tuple, list, set, frozenset)):
        return sum(_size(item, seen) for item in value)
    if isinstance(value, dict):
        return sum(_size(item, seen) for item in value.values())
    if hasattr(value, "__dict__"):
        return sum(_size(item, seen) for item in vars(value).values())
    return 0


class RunCache:
    """Values built once per key and read again, frozen, at most ``budget`` bytes.

    Parameters
    ----------
    budget : int
        The bytes [B] of arrays kept at most; past it the least recently used entries are
        dropped.

    Examples
    --------
    >>> cache = RunCache()
    >>> table = cache.get(("squares", 4), lambda: np.arange(4.0) ** 2)
    >>> table.flags.writeable
    False
    """

    def __init__(self, budget: int = BUDGET):
        self.budget = int(budget)
        self._entries: OrderedDict = OrderedDict()   # key -> (value, holds, bytes)
        self._bytes = 0
        self._lock = threading.RLock()
        self.hits = self.misses = 0

    def __len__(self) -> int:
        return len(self._entries)

    def keys(self) -> list:
        """The keys kept, least recently used first."""
        with self._lock:
            return list(self._entries)

    @property
    def nbytes(self) -> int:
        """The bytes [B] of the arrays kept."""
        return self._bytes

    def get(self, key: Hashable, build: Callable[[], Any], holds: tuple = (),
            owner: object | None = None):
        """The value kept under ``key``, else ``build()`` frozen, kept and returned.

        Parameters
        ----------
        key : hashable
            Names the value: a tag for what it is, then everything it depends on.
        build : callable
            Makes the value when it is not kept.
        holds : tuple
            Objects kept alive with the entry (those whose ids ``key`` holds).
        owner : object, optional
            The entry belongs to this object: it is keyed by its id too and dropped when
            the owner is collected (values derived from an object without a value key).
        """
        if owner is not None:
            key = (id(owner), key)
        with self._lock:
            if key in self._entries:
                self._entries.move_to_end(key)
                self.hits += 1
                return self._entries[key][0]
        value = freeze(build())
        size = size_of(value)
        with self._lock:
            if key in self._entries:   # another thread built it meanwhile: keep the first
                return self._entries[key][0]
            self.misses += 1
            self._entries[key] = (value, holds, size)
            self._bytes += size
            if owner is not None:   # (a weak reference: the owner may hold the cache)
                weakref.finalize(owner, _forget, weakref.ref(self), key)
            self._evict()
        return value

    def forget(self, key) -> None:
        """Drop the entry ``key`` (an owner's key is (id(owner), key)), if kept."""
        with self._lock:
            entry = self._entries.pop(key, None)
            if entry is not None:
                self._bytes -= entry[2]

    def _evict(self) -> None:
        while self._bytes > self.budget and len(self._entries) > 1:
            _, (_, _, size) = self._entries.popitem(last=False)
            self._bytes -= size

    def clear(self) -> None:
        """Drop every entry."""
        with self._lock:
            self._entries.clear()
            self._bytes = 0


def _forget(reference: weakref.ref, key) -> None:
    """An owner was collected: its entry leaves the cache, if the cache still lives."""
    cache = reference()
    if cache is not None:
        cache.forget(key)


def run_cache(cache: RunCache | None) -> RunCache:
    """Return ``cache``, or a fresh ``RunCache`` when it is None (a solve or plan called alone).

    Parameters
    ----------
    cache : RunCache or None
        The run's cache, if the caller has one.

    Returns
    -------
    RunCache
        The cache to use.
    """
    return RunCache() if cache is None else cache
