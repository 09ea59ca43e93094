"""libode 0.16 enum values, defined here because python3-pyode's are stale.

PyODE hard-codes the joint parameter and contact mode numbers of an older ODE.
libode 0.16 (/usr/include/ode/common.h, contact.h) inserted dParamLoVel and
dParamHiVel after dParamVel and renumbered the contact slip flags, so e.g.
``ode.ParamFMax`` (3) is read as dParamLoVel and a motor set up with it has no
force. Only use the names below with ``setParam`` / ``Contact.setMode``.
"""

# Joint parameters, first axis (enum D_ALL_PARAM_NAMES in ode/common.h).
PARAM_LO_STOP = 0
PARAM_HI_STOP = 1
PARAM_VEL = 2
PARAM_LO_VEL = 3
PARAM_HI_VEL = 4
PARAM_FMAX = 5
PARAM_FUDGE_FACTOR = 6
PARAM_BOUNCE = 7
PARAM_CFM = 8
PARAM_STOP_ERP = 9
PARAM_STOP_CFM = 10
PARAM_SUSPENSION_ERP = 11
PARAM_SUSPENSION_CFM = 12
PARAM_ERP = 13

# Add to a first-axis parameter to address axis 2 or 3 (dParamGroup).
PARAM_GROUP = 0x100
PARAM_GROUP2 = PARAM_GROUP
PARAM_GROUP3 = 2 * PARAM_GROUP

# Contact surface mode flags (ode/contact.h).
CONTACT_MU2 = 0x001
CONTACT_FDIR1 = 0x002
CONTACT_BOUNCE = 0x004
CONTACT_SOFT_ERP = 0x008
CONTACT_SOFT_CFM = 0x010
CONTACT_MOTION1 = 0x020
CONTACT_MOTION2 = 0x040
CONTACT_MOTION_N = 0x080
CONTACT_SLIP1 = 0x100
CONTACT_SLIP2 = 0x200
CONTACT_ROLLING = 0x400
CONTACT_APPROX1_1 = 0x1000
CONTACT_APPROX1_2 = 0x2000
CONTACT_APPROX1_N = 0x4000
CONTACT_APPROX1 = 0x7000
