"""Continuous joints' turns counted in C after every step (src/contact_kernel.c's tso_count_turns), as
models.built.JointHandle.track_turns counts them in Python, double for double: a 1000-link chain spent 12 % of its
step counting turns in Python (issue #33)."""
from __future__ import annotations

import ctypes
from typing import Any, Sequence

Doubles = ctypes.Array  # of ctypes.c_double


class TurnCounter:
    """Slot i: the last [-pi, pi] angle read of hinge ``ids[i]`` (``last``) and its angle counted across turns
    (``unwrapped``); ``count()`` after each step moves every slot on, ``count_one(i)`` one."""

    def __init__(self, lib: Any, ids: Sequence[int], hinges: Sequence[Any]) -> None:
        """``hinges``: the PyODE joints of ``ids``, kept alive here (PyODE destroys a joint with its last wrapper)."""
        size = max(1, len(ids))
        self._hinges = list(hinges)
        self._size = len(ids)
        self._ids = (ctypes.c_void_p * size)(*ids)
        self.last: Doubles = (ctypes.c_double * size)()
        self.unwrapped: Doubles = (ctypes.c_double * size)()
        self._count_turns = lib.tso_count_turns

    def count(self) -> None:
        self._count_turns(self._size, self._ids, self.last, self.unwrapped)

    def count_one(self, slot: int) -> None:
        self._count_turns(1, _at(self._ids, slot), _at(self.last, slot), _at(self.unwrapped, slot))


def _at(array: ctypes.Array, index: int) -> Any:
    """A pointer to ``array[index]``, typed as the array's elements."""
    kind = array._type_  # type: ignore[attr-defined]
    return ctypes.cast(ctypes.addressof(array) + index * ctypes.sizeof(kind), ctypes.POINTER(kind))
