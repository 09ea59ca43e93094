"""Contacts found in a step: watches that report them, and the ODE contact joints made from them."""
from __future__ import annotations

from typing import Callable, Iterable, List, NamedTuple, Optional, Sequence, Tuple

import ode

from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics.surfaces import PairContact

# Where every component of normal x fdir1 is below this, Gazebo's ODE falls back to its own friction directions
# (gazebo-classic deps/opende/src/joints/contact.cpp, dxJointContact::getInfo2: _dequal(t2, 0)).
PARALLEL_FDIR1_TOLERANCE = 1e-6


class WatchedContact(NamedTuple):
    """One contact point touching a watched geom: ``normal`` points from ``other`` towards
    ``geom`` (moving ``geom`` along it by ``depth`` separates them)."""

    geom: ode.GeomObject
    other: ode.GeomObject
    position: Tuple[float, float, float]
    normal: Tuple[float, float, float]
    depth: float


class ContactWatch:
    """Contacts touching ``geoms`` during the last step (see ``PhysicsWorld.watch_contacts``).

    ``contacts`` is a new list after every step (the ODE contact points as found, before
    contact joints are made from them); ground contacts are included (``other`` is
    ``PhysicsWorld.ground``).
    """

    def __init__(self, geoms: Iterable[ode.GeomObject]) -> None:
        self.geoms = frozenset(geoms)
        self._contacts: List[WatchedContact] = []
        # Set when the step's contacts are still in the contact kernel: read on demand, since most steps'
        # contacts are never asked for (sensors read at their own rates).
        self._fill: Optional[Callable[[], None]] = None

    @property
    def contacts(self) -> List[WatchedContact]:
        if self._fill is not None:
            self._fill()
        return self._contacts


ContactGeom = Tuple[Tuple[float, float, float], Tuple[float, float, float], float]


def merge_line_contact(contacts: Sequence[ode.Contact]) -> Tuple[Sequence[ode.Contact], Optional[ContactGeom]]:
    """Replace the two end points of a line contact by its centre of pressure (returned with its point).

    A cylinder lying on a surface touches it along a line, but ODE reports only the
    line's two ends. Their friction scrubs against each other when the cylinder pivots:
    a wheel pair turning in place then turns 6.5 % slower than commanded, because the
    robot settles where one end point sticks. One contact at the centre of pressure of
    the (linear, as for a spring foundation) pressure profile pivots freely.
    """
    first, second = contacts
    (x1, y1, z1), normal, depth1, _, _ = first.getContactGeomParams()
    (x2, y2, z2), (nx2, ny2, nz2), depth2, _, _ = second.getContactGeomParams()
    if normal[0] * nx2 + normal[1] * ny2 + normal[2] * nz2 < 0.999:
        return contacts, None  # not one flat line contact
    total = depth1 + depth2
    # Centroid of a trapezoid of heights depth1, depth2, as a fraction from pos1.
    t = (depth1 + 2.0 * depth2) / (3.0 * total) if total > 0 else 0.5
    # Set without its geoms (PyODE then leaves them null): a contact joint never reads them, and PyODE takes
    # four times as long to set them (every wheel, every step).
    merged = ((x1 + t * (x2 - x1), y1 + t * (y2 - y1), z1 + t * (z2 - z1)), normal, depth1 + t * (depth2 - depth1))
    first.setContactGeomParams(*merged)
    return (first,), merged  # its geoms are null now: PyODE could not read it back


def friction_direction(
    rotation: Sequence[float], fdir1: Tuple[float, float, float], normal: Sequence[float]
) -> Optional[Tuple[float, float, float]]:
    """``fdir1`` (in a geom's frame; ``rotation`` its world rotation, row-major) turned into the world and handed to
    ODE as it is, neither projected onto the contact plane nor normalised, as gazebo-classic's ODEPhysics::Collide
    does. ODE's contact joint then takes it as the first friction direction and normal x fdir1 as the second: a
    wheel's fdir1 "1 0 0" turns with the wheel, so its friction rows tilt and shrink as it rolls, in Gazebo and here.
    None where normal x fdir1 vanishes: Gazebo's ODE then falls back to dPlaneSpace, as stock ODE does without
    dContactFDir1. contact_kernel.c's friction_direction, op for op."""
    x, y, z = fdir1
    wx = rotation[0] * x + rotation[1] * y + rotation[2] * z
    wy = rotation[3] * x + rotation[4] * y + rotation[5] * z
    wz = rotation[6] * x + rotation[7] * y + rotation[8] * z
    cross = (normal[1] * wz - normal[2] * wy, normal[2] * wx - normal[0] * wz, normal[0] * wy - normal[1] * wx)
    if all(abs(c) <= PARALLEL_FDIR1_TOLERANCE for c in cross):
        return None
    return (wx, wy, wz)


def add_contact_joints(
    world: ode.World,
    keep: List[ode.ContactJoint],
    max_contacts: int,
    contacts: Sequence[ode.Contact],
    body1: Optional[ode.Body],
    body2: Optional[ode.Body],
    pair: PairContact,
    geom1: ode.GeomObject,
    geom2: ode.GeomObject,
) -> None:
    """One contact joint per point of ``contacts`` in ``world`` with ``pair``'s surface, kept alive in ``keep``
    until the next step (as contact_kernel.c's add_contacts, step for step)."""
    surface, merge_line = pair
    mode, side, adjust, mu, mu2, erp, cfm, slip1, slip2, min_depth, depth_cap, layer, fx, fy, fz = surface
    merged: Optional[ContactGeom] = None
    if merge_line and len(contacts) == 2:
        contacts, merged = merge_line_contact(contacts)
    elif len(contacts) > max_contacts:
        contacts = contacts[:max_contacts]
    for contact in contacts:
        contact_mode = mode
        if adjust or side:
            position, normal, depth = merged if merged is not None else contact.getContactGeomParams()[:3]
            if adjust:
                depth = depth - min_depth
                if depth > depth_cap:
                    depth = depth_cap
                contact.setContactGeomParams(position, normal, depth + layer)
            if side:
                direction = friction_direction((geom1 if side == 1 else geom2).getRotation(), (fx, fy, fz), normal)
                if direction is not None:
                    contact_mode |= oc.CONTACT_FDIR1
                    contact.setFDir1(direction)
        contact.setMode(contact_mode)
        contact.setMu(mu)
        contact.setMu2(mu2)
        contact.setSoftERP(erp)
        contact.setSoftCFM(cfm)
        contact.setSlip1(slip1)
        contact.setSlip2(slip2)
        joint = ode.ContactJoint(world, None, getattr(contact, "ode_contact", contact))
        joint.attach(body1, body2)
        keep.append(joint)
