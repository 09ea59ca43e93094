/* See include/turtle_sim_ode/contact_kernel.h. Each step mirrors PhysicsWorld.step / _near / _record_contacts in
 * physics/world.py and add_contact_joints / merge_line_contact in physics/contacts.py: keep them in step. */
#include "turtle_sim_ode/contact_kernel.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* PyODE's ode.collide asks ODE for at most this many points; fewer could change which points a pair gives. */
enum
{
  kMaxPointsPerPair = 150
};

/* physics.contacts.PARALLEL_FDIR1_TOLERANCE */
static const double kParallelFdir1Tolerance = 1e-6;

typedef struct
{
  uintptr_t id;
  int surface;
  unsigned char watched;
} GeomEntry;

typedef struct
{
  uintptr_t low, high;
} BodyPair;

struct TsoContactKernel
{
  dJointGroupID joints; /* this step's contact joints */
  GeomEntry* geoms;     /* sorted by id */
  int geom_count;
  TsoPairSurface* pairs;
  int surface_count;
  BodyPair* excluded; /* sorted */
  int excluded_count;
  dGeomID ground;
  dGeomID* ground_tests;
  int ground_test_count;
  dSpaceID top;
  dSpaceID* self_colliding;
  int self_colliding_count;
  int max_contacts;
  int any_watched;
  int joint_count;
  TsoWatchedContact* watched;
  int watched_count, watched_capacity;
  dWorldID world; /* what tso_kernel_step steps, and how */
  double step_size;
  int quick;
};

static int compare_geoms(const void* a, const void* b)
{
  uintptr_t x = ((const GeomEntry*)a)->id, y = ((const GeomEntry*)b)->id;
  return (x > y) - (x < y);
}

static int compare_pairs(const void* a, const void* b)
{
  const BodyPair *x = (const BodyPair*)a, *y = (const BodyPair*)b;
  if (x->low != y->low)
    return (x->low > y->low) - (x->low < y->low);
  return (x->high > y->high) - (x->high < y->high);
}

static BodyPair body_pair(dBodyID a, dBodyID b)
{
  BodyPair pair;
  uintptr_t x = (uintptr_t)a, y = (uintptr_t)b;
  pair.low = x < y ? x : y;
  pair.high = x < y ? y : x;
  return pair;
}

static const GeomEntry* find_geom(const TsoContactKernel* kernel, dGeomID geom)
{
  GeomEntry key;
  key.id = (uintptr_t)geom;
  return (const GeomEntry*)bsearch(&key, kernel->geoms, (size_t)kernel->geom_count, sizeof(GeomEntry), compare_geoms);
}

static int is_watched(const TsoContactKernel* kernel, dGeomID geom)
{
  const GeomEntry* entry = find_geom(kernel, geom);
  return entry != NULL && entry->watched;
}

static const TsoPairSurface* pair_surface(const TsoContactKernel* kernel, dGeomID a, dGeomID b)
{
  const GeomEntry* entry_a = find_geom(kernel, a);
  const GeomEntry* entry_b = find_geom(kernel, b);
  int i = entry_a != NULL ? entry_a->surface : 0;
  int j = entry_b != NULL ? entry_b->surface : 0;
  return &kernel->pairs[i * kernel->surface_count + j];
}

/* Replace *target by a copy of count items of size bytes (count 0 gives NULL). */
static int replace(void** target, const void* items, int count, size_t size)
{
  void* copy = NULL;
  if (count < 0)
    return -1;
  if (count > 0)
  {
    copy = malloc((size_t)count * size);
    if (copy == NULL)
      return -1;
    memcpy(copy, items, (size_t)count * size);
  }
  free(*target);
  *target = copy;
  return 0;
}

TsoContactKernel* tso_kernel_create(void)
{
  TsoContactKernel* kernel = (TsoContactKernel*)calloc(1, sizeof(TsoContactKernel));
  static const TsoPairSurface kNoFriction; /* all zero */
  if (kernel == NULL)
    return NULL;
  kernel->joints = dJointGroupCreate(0);
  /* Until set: one surface, so that lookups stay in bounds. */
  if (replace((void**)&kernel->pairs, &kNoFriction, 1, sizeof(TsoPairSurface)) != 0)
  {
    tso_kernel_destroy(kernel);
    return NULL;
  }
  kernel->surface_count = 1;
  return kernel;
}

void tso_kernel_destroy(TsoContactKernel* kernel)
{
  if (kernel == NULL)
    return;
  if (kernel->joints != NULL)
    dJointGroupDestroy(kernel->joints);
  free(kernel->geoms);
  free(kernel->pairs);
  free(kernel->excluded);
  free(kernel->ground_tests);
  free(kernel->self_colliding);
  free(kernel->watched);
  free(kernel);
}

int tso_kernel_set_geoms(TsoContactKernel* kernel, int count, const dGeomID* geoms, const int* surfaces,
                         const unsigned char* watched)
{
  GeomEntry* entries;
  int i;
  if (count < 0)
    return -1;
  entries = (GeomEntry*)malloc((size_t)(count > 0 ? count : 1) * sizeof(GeomEntry));
  if (entries == NULL)
    return -1;
  kernel->any_watched = 0;
  for (i = 0; i < count; ++i)
  {
    entries[i].id = (uintptr_t)geoms[i];
    entries[i].surface = surfaces[i];
    entries[i].watched = watched[i];
    kernel->any_watched |= watched[i] != 0;
  }
  qsort(entries, (size_t)count, sizeof(GeomEntry), compare_geoms);
  free(kernel->geoms);
  kernel->geoms = entries;
  kernel->geom_count = count;
  return 0;
}

int tso_kernel_set_pair_surfaces(TsoContactKernel* kernel, int surfaces, const TsoPairSurface* table)
{
  if (surfaces < 1 || replace((void**)&kernel->pairs, table, surfaces * surfaces, sizeof(TsoPairSurface)) != 0)
  {
    return -1;
  }
  kernel->surface_count = surfaces;
  return 0;
}

int tso_kernel_set_excluded(TsoContactKernel* kernel, int count, const dBodyID* pairs)
{
  BodyPair* sorted;
  int i;
  if (count < 0)
    return -1;
  sorted = (BodyPair*)malloc((size_t)(count > 0 ? count : 1) * sizeof(BodyPair));
  if (sorted == NULL)
    return -1;
  for (i = 0; i < count; ++i)
    sorted[i] = body_pair(pairs[2 * i], pairs[2 * i + 1]);
  qsort(sorted, (size_t)count, sizeof(BodyPair), compare_pairs);
  free(kernel->excluded);
  kernel->excluded = sorted;
  kernel->excluded_count = count;
  return 0;
}

int tso_kernel_set_ground_tests(TsoContactKernel* kernel, dGeomID ground, int count, const dGeomID* geoms)
{
  if (replace((void**)&kernel->ground_tests, geoms, count, sizeof(dGeomID)) != 0)
    return -1;
  kernel->ground = ground;
  kernel->ground_test_count = count;
  return 0;
}

int tso_kernel_set_spaces(TsoContactKernel* kernel, dSpaceID top, int self_colliding_count,
                          const dSpaceID* self_colliding, int max_contacts)
{
  if (replace((void**)&kernel->self_colliding, self_colliding, self_colliding_count, sizeof(dSpaceID)) != 0)
  {
    return -1;
  }
  kernel->top = top;
  kernel->self_colliding_count = self_colliding_count;
  kernel->max_contacts = max_contacts;
  return 0;
}

static int record(TsoContactKernel* kernel, dGeomID geom, dGeomID other, const dContactGeom* point, double sign)
{
  TsoWatchedContact* slot;
  if (kernel->watched_count == kernel->watched_capacity)
  {
    int capacity = kernel->watched_capacity > 0 ? 2 * kernel->watched_capacity : 64;
    TsoWatchedContact* grown =
        (TsoWatchedContact*)realloc(kernel->watched, (size_t)capacity * sizeof(TsoWatchedContact));
    if (grown == NULL)
      return -1;
    kernel->watched = grown;
    kernel->watched_capacity = capacity;
  }
  slot = &kernel->watched[kernel->watched_count++];
  slot->geom = geom;
  slot->other = other;
  slot->position[0] = point->pos[0];
  slot->position[1] = point->pos[1];
  slot->position[2] = point->pos[2];
  slot->normal[0] = sign * point->normal[0];
  slot->normal[1] = sign * point->normal[1];
  slot->normal[2] = sign * point->normal[2];
  slot->depth = point->depth;
  return 0;
}

/* As physics.world's _record_contacts: for each watched side of the pair, every point. */
static void record_contacts(TsoContactKernel* kernel, const dContactGeom* points, int count, dGeomID a, dGeomID b)
{
  int i;
  if (is_watched(kernel, a))
  {
    for (i = 0; i < count; ++i)
      record(kernel, a, b, &points[i], 1.0);
  }
  if (is_watched(kernel, b))
  {
    for (i = 0; i < count; ++i)
      record(kernel, b, a, &points[i], -1.0);
  }
}

/* As physics.contacts.merge_line_contact: a flat two-point line contact becomes one point at its centre of pressure.
 * Returns the number of points left. */
static int merge_line_contact(dContactGeom* points)
{
  dContactGeom* first = &points[0];
  const dContactGeom* second = &points[1];
  double total, t;
  if (first->normal[0] * second->normal[0] + first->normal[1] * second->normal[1] +
          first->normal[2] * second->normal[2] <
      0.999)
  {
    return 2;
  }
  total = first->depth + second->depth;
  t = total > 0 ? (first->depth + 2.0 * second->depth) / (3.0 * total) : 0.5;
  first->pos[0] = first->pos[0] + t * (second->pos[0] - first->pos[0]);
  first->pos[1] = first->pos[1] + t * (second->pos[1] - first->pos[1]);
  first->pos[2] = first->pos[2] + t * (second->pos[2] - first->pos[2]);
  first->depth = first->depth + t * (second->depth - first->depth);
  return 1;
}

/* As physics.contacts.friction_direction: fdir1 turned by the geom's rotation into out, unprojected and
 * unnormalised as gazebo-classic's ODEPhysics::Collide hands it to ODE; 0 where normal x fdir1 vanishes (Gazebo's
 * ODE then uses dPlaneSpace, as stock ODE does without dContactFDir1). */
static int friction_direction(dGeomID geom, const double* fdir1, const dReal* normal, dReal* out)
{
  const dReal* r = dGeomGetRotation(geom); /* rows of 4 */
  double x = fdir1[0], y = fdir1[1], z = fdir1[2];
  double wx = r[0] * x + r[1] * y + r[2] * z;
  double wy = r[4] * x + r[5] * y + r[6] * z;
  double wz = r[8] * x + r[9] * y + r[10] * z;
  double cx = normal[1] * wz - normal[2] * wy;
  double cy = normal[2] * wx - normal[0] * wz;
  double cz = normal[0] * wy - normal[1] * wx;
  if (fabs(cx) <= kParallelFdir1Tolerance && fabs(cy) <= kParallelFdir1Tolerance && fabs(cz) <= kParallelFdir1Tolerance)
    return 0;
  out[0] = wx;
  out[1] = wy;
  out[2] = wz;
  return 1;
}

/* As physics.contacts.add_contact_joints: one contact joint per point, between body1 and body2 (either may be 0);
 * geom1 and geom2 are the pair in the order its surface was looked up. */
static void add_contacts(TsoContactKernel* kernel, dContactGeom* points, int count, dBodyID body1, dBodyID body2,
                         const TsoPairSurface* surface, int merge_line, dGeomID geom1, dGeomID geom2)
{
  dWorldID world = dBodyGetWorld(body1 != NULL ? body1 : body2);
  int i;
  if (merge_line && count == 2)
  {
    count = merge_line_contact(points);
  }
  else if (count > kernel->max_contacts)
  {
    count = kernel->max_contacts;
  }
  for (i = 0; i < count; ++i)
  {
    dContact contact;
    dJointID joint;
    memset(&contact, 0, sizeof(contact));
    contact.geom = points[i];
    contact.surface.mode = surface->mode;
    if (surface->adjust_depth)
    {
      double depth = contact.geom.depth - surface->min_depth;
      if (depth > surface->depth_cap)
        depth = surface->depth_cap;
      contact.geom.depth = depth + surface->surface_layer;
    }
    if (surface->fdir_side != 0 &&
        friction_direction(surface->fdir_side == 1 ? geom1 : geom2, surface->fdir1, contact.geom.normal, contact.fdir1))
    {
      contact.surface.mode |= dContactFDir1;
    }
    contact.surface.mu = surface->mu;
    contact.surface.mu2 = surface->mu2;
    contact.surface.bounce = 0.1; /* PyODE's Contact default (no effect without dContactBounce) */
    contact.surface.soft_erp = surface->soft_erp;
    contact.surface.soft_cfm = surface->soft_cfm;
    contact.surface.slip1 = surface->slip1;
    contact.surface.slip2 = surface->slip2;
    joint = dJointCreateContact(world, kernel->joints, &contact);
    dJointAttach(joint, body1, body2);
    ++kernel->joint_count;
  }
}

static int is_cylinder(dGeomID geom)
{
  return dGeomGetClass(geom) == dCylinderClass;
}

static void near_callback(void* data, dGeomID a, dGeomID b)
{
  TsoContactKernel* kernel = (TsoContactKernel*)data;
  dContactGeom points[kMaxPointsPerPair];
  dBodyID body_a, body_b;
  int count;
  if (dGeomIsSpace(a) || dGeomIsSpace(b))
  {
    dSpaceCollide2(a, b, data, near_callback);
    return;
  }
  body_a = dGeomGetBody(a);
  body_b = dGeomGetBody(b);
  if (body_a == body_b)
    return;
  if (kernel->excluded_count > 0)
  {
    BodyPair key = body_pair(body_a, body_b);
    if (bsearch(&key, kernel->excluded, (size_t)kernel->excluded_count, sizeof(BodyPair), compare_pairs))
      return;
  }
  count = dCollide(a, b, kMaxPointsPerPair, points, sizeof(dContactGeom));
  if (count > 0)
  {
    if (kernel->any_watched)
      record_contacts(kernel, points, count, a, b);
    add_contacts(kernel, points, count, body_a, body_b, pair_surface(kernel, a, b), is_cylinder(a) || is_cylinder(b), a,
                 b);
  }
}

int tso_kernel_collide(TsoContactKernel* kernel)
{
  dContactGeom points[kMaxPointsPerPair];
  int i;
  dJointGroupEmpty(kernel->joints);
  kernel->joint_count = 0;
  kernel->watched_count = 0;
  for (i = 0; i < kernel->ground_test_count; ++i)
  {
    dGeomID geom = kernel->ground_tests[i];
    int count = dCollide(kernel->ground, geom, kMaxPointsPerPair, points, sizeof(dContactGeom));
    if (count > 0)
    {
      if (kernel->any_watched)
        record_contacts(kernel, points, count, kernel->ground, geom);
      add_contacts(kernel, points, count, NULL, dGeomGetBody(geom), pair_surface(kernel, kernel->ground, geom),
                   is_cylinder(geom), kernel->ground, geom);
    }
  }
  if (kernel->top != NULL && dSpaceGetNumGeoms(kernel->top) > 1)
    dSpaceCollide(kernel->top, kernel, near_callback);
  for (i = 0; i < kernel->self_colliding_count; ++i)
    dSpaceCollide(kernel->self_colliding[i], kernel, near_callback);
  return kernel->joint_count;
}

void tso_kernel_set_step(TsoContactKernel* kernel, dWorldID world, double step_size, int quick)
{
  kernel->world = world;
  kernel->step_size = step_size;
  kernel->quick = quick;
}

int tso_kernel_step(TsoContactKernel* kernel)
{
  int joints = tso_kernel_collide(kernel);
  if (kernel->world == NULL)
    return joints;
  if (kernel->quick)
    dWorldQuickStep(kernel->world, kernel->step_size);
  else
    dWorldStep(kernel->world, kernel->step_size);
  return joints;
}

const TsoWatchedContact* tso_kernel_watched(const TsoContactKernel* kernel, int* count)
{
  *count = kernel->watched_count;
  return kernel->watched;
}

dJointID tso_joint_between(dBodyID a, dBodyID b, int type)
{
  dBodyID from = a != NULL ? a : b;
  dJointID found = NULL;
  int i, joints;
  if (from == NULL)
    return NULL;
  joints = dBodyGetNumJoints(from);
  for (i = 0; i < joints; ++i)
  {
    dJointID joint = dBodyGetJoint(from, i);
    dBodyID first = dJointGetBody(joint, 0), second = dJointGetBody(joint, 1);
    if ((int)dJointGetType(joint) != type || !((first == a && second == b) || (first == b && second == a)))
      continue;
    if (found != NULL)
      return NULL; /* two such joints between the same bodies: which is which cannot be told from here */
    found = joint;
  }
  return found;
}

/* The same doubles as math.pi and 2 * math.pi in models/built.py. */
static const double kPi = 3.14159265358979323846;
static const double kTwoPi = 2.0 * 3.14159265358979323846;

void tso_count_turns(int count, const dJointID* hinges, double* last, double* unwrapped)
{
  int i;
  for (i = 0; i < count; ++i)
  {
    double wrapped = dJointGetHingeAngle(hinges[i]);
    double delta = wrapped - last[i];
    if (delta > kPi)
      delta -= kTwoPi;
    else if (delta < -kPi)
      delta += kTwoPi;
    unwrapped[i] += delta;
    last[i] = wrapped;
  }
}

void tso_damp_joints(int count, const dJointID* joints, const unsigned char* sliders, const double* coefficients)
{
  int i;
  for (i = 0; i < count; ++i)
  {
    if (sliders[i])
      dJointAddSliderForce(joints[i], -coefficients[i] * dJointGetSliderPositionRate(joints[i]));
    else
      dJointAddHingeTorque(joints[i], -coefficients[i] * dJointGetHingeAngleRate(joints[i]));
  }
}
