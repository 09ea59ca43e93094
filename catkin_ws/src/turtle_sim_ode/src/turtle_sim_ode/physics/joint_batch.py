"""Per-joint work after every step done in C for all joints of a model at once (src/contact_kernel.c), double for
double as models.built does it joint by joint in Python: continuous joints' turns counted (tso_count_turns; a
1000-link chain spent 12 % of its step counting turns in Python, issue #33) and viscous damping (tso_damp_joints)."""
from __future__ import annotations

import ctypes
from typing import Any, Sequence, Tuple

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


class JointDamper:
    """``apply()`` after each step: -coefficient x rate on each joint, a torque on a hinge, a force on a slider."""

    def __init__(self, lib: Any, entries: Sequence[Tuple[int, bool, float]], joints: Sequence[Any]) -> None:
        """``entries``: (joint id, is a slider, coefficient); ``joints``: their PyODE joints, kept alive here."""
        size = max(1, len(entries))
        self._joints = list(joints)
        self._size = len(entries)
        self._ids = (ctypes.c_void_p * size)(*(joint for joint, _, _ in entries))
        self._sliders = (ctypes.c_ubyte * size)(*(int(slider) for _, slider, _ in entries))
        self._coefficients = (ctypes.c_double * size)(*(coefficient for _, _, coefficient in entries))
        self._damp = lib.tso_damp_joints

    def apply(self) -> None:
        self._damp(self._size, self._ids, self._sliders, self._coefficients)
