/* Collision and contact-joint creation of PhysicsWorld.step in C (issue #8), called through ctypes
 * (turtle_sim_ode/contact_kernel.py). It does what the Python path in physics.py does, in the same order and with
 * the same floating-point operations, so both step a world bitwise alike (test_contact_kernel.py); it only saves
 * Python's per-contact cost (about a third of a TurtleBot's step).
 *
 * The tables are set from Python whenever geoms, surfaces, watches or exclusions change; geoms and bodies are ODE
 * ids taken from PyODE. Nothing here owns a geom or a body. */
#ifndef TURTLE_SIM_ODE_CONTACT_KERNEL_H
#define TURTLE_SIM_ODE_CONTACT_KERNEL_H

#include <ode/ode.h>

#ifdef __cplusplus
extern "C"
{
#endif

  /* One combined surface of a geom pair, as set on each of its contacts (physics.world.ContactSurface).
   * fdir_side: whose fdir1 (in that geom's frame) is the first friction direction: 0 none, 1 the pair's first geom,
   * 2 its second. adjust_depth: each contact's depth becomes min(depth - min_depth, depth_cap) + surface_layer, so
   * that ODE acts with the pair's min_depth and max_vel instead of the world's. */
  typedef struct
  {
    int mode, fdir_side, adjust_depth;
    double mu, mu2, soft_erp, soft_cfm, slip1, slip2, min_depth, depth_cap, surface_layer;
    double fdir1[3];
  } TsoPairSurface;

  /* A contact point touching a watched geom, before contact joints are made; the normal points from other to geom. */
  typedef struct
  {
    dGeomID geom, other;
    double position[3], normal[3], depth;
  } TsoWatchedContact;

  typedef struct TsoContactKernel TsoContactKernel;

  TsoContactKernel* tso_kernel_create(void);
  void tso_kernel_destroy(TsoContactKernel* kernel);

  /* Geoms with a surface (index into the pair table; unlisted geoms use index 0) and whether contacts touching them
   * are recorded. Returns 0, or -1 when out of memory (the old table is kept). */
  int tso_kernel_set_geoms(TsoContactKernel* kernel, int count, const dGeomID* geoms, const int* surfaces,
                           const unsigned char* watched);
  /* surfaces x surfaces table: entry [i * surfaces + j] for a pair of geoms with surface indices i and j. */
  int tso_kernel_set_pair_surfaces(TsoContactKernel* kernel, int surfaces, const TsoPairSurface* table);
  /* Body pairs (two ids each) that never collide. */
  int tso_kernel_set_excluded(TsoContactKernel* kernel, int count, const dBodyID* pairs);
  /* The ground plane (in no space) and the geoms tested against it, in order. */
  int tso_kernel_set_ground_tests(TsoContactKernel* kernel, dGeomID ground, int count, const dGeomID* geoms);

  /* The spaces collided after the ground tests: the top space, then each self-colliding model space; and the
   * most contact joints a geom pair gets (a two-point line contact merged to one aside). */
  int tso_kernel_set_spaces(TsoContactKernel* kernel, dSpaceID top, int self_colliding_count,
                            const dSpaceID* self_colliding, int max_contacts);

  /* Destroy the last step's contact joints, then collide: ground tests, the top space, each self-colliding space.
   * Returns the number of contact joints made. */
  int tso_kernel_collide(TsoContactKernel* kernel);
  /* What tso_kernel_step steps: ``world`` by ``step_size`` with dWorldQuickStep if ``quick``, else dWorldStep. */
  void tso_kernel_set_step(TsoContactKernel* kernel, dWorldID world, double step_size, int quick);
  /* tso_kernel_collide, then the step set by tso_kernel_set_step (none before): a whole physics step in one call,
   * which ctypes makes without holding Python's GIL (PyODE's World.step holds it). Returns the number of contact
   * joints made. */
  int tso_kernel_step(TsoContactKernel* kernel);
  /* The contacts touching watched geoms found by the last collide; *count is set to their number. */
  const TsoWatchedContact* tso_kernel_watched(const TsoContactKernel* kernel, int* count);
  /* The one joint of ODE type ``type`` (dJointTypeHinge, dJointTypeSlider, ...) between bodies a and b (either may
   * be 0, the world; in either order), or 0 when there is none or more than one. */
  dJointID tso_joint_between(dBodyID a, dBodyID b, int type);
  /* Turn counting of continuous joints after a step (models.built.JointHandle.track_turns for each): the change of
   * each hinge's [-pi, pi] angle since last[i], taken across the wrap, is added to unwrapped[i]; last[i] becomes the
   * angle. */
  void tso_count_turns(int count, const dJointID* hinges, double* last, double* unwrapped);
  /* Viscous joint damping after a step, for the next (models.built's after-step hook for each): -coefficients[i]
   * times the joint's rate, as a torque on a hinge, a force on a slider (sliders[i] != 0). */
  void tso_damp_joints(int count, const dJointID* joints, const unsigned char* sliders, const double* coefficients);

#ifdef __cplusplus
}
#endif

#endif
