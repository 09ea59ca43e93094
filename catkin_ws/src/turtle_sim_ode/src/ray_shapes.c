/* A ray against one shape (see ray_kernel.h), in the shape's frame: the primitives but planes (their callers test
 * those), a mesh's triangles. The same tests as turtle_sim_ode.sensors.raycast. */
#include "ray_kernel.h"

#include <math.h>

static double hitSphere(const double* o, const double* d, double r, double tMin, double* n)
{
  double a = dot3(d, d);
  double b = dot3(d, o);
  double disc = b * b - a * (dot3(o, o) - r * r);
  if (disc < 0.0)
  {
    return INFINITY;
  }
  double t = (-b - sqrt(disc)) / a;
  if (t <= tMin)
  {
    return INFINITY;
  }
  for (int i = 0; i < 3; ++i)
  {
    n[i] = (o[i] + t * d[i]) / r;
  }
  return t;
}

static double hitBox(const double* o, const double* d, const double* half, double tMin, double* n)
{
  double tNear = -INFINITY;
  double tFar = INFINITY;
  int axis = -1;
  for (int i = 0; i < 3; ++i)
  {
    if (d[i] == 0.0)
    {
      if (o[i] < -half[i] || o[i] > half[i])
      {
        return INFINITY;
      }
      continue;
    }
    double inverse = 1.0 / d[i];
    double t1 = (-half[i] - o[i]) * inverse;
    double t2 = (half[i] - o[i]) * inverse;
    if (t1 > t2)
    {
      double swap = t1;
      t1 = t2;
      t2 = swap;
    }
    if (t1 > tNear)
    {
      tNear = t1;
      axis = i;
    }
    if (t2 < tFar)
    {
      tFar = t2;
    }
  }
  if (axis < 0 || tNear > tFar || tNear <= tMin)
  {
    return INFINITY;
  }
  n[0] = n[1] = n[2] = 0.0;
  n[axis] = d[axis] > 0.0 ? -1.0 : 1.0;
  return tNear;
}

/* The curved side of a cylinder along z of half length hl. */
static double hitSide(const double* o, const double* d, double r, double hl, double tMin, double* n)
{
  double a = d[0] * d[0] + d[1] * d[1];
  if (a <= 0.0)
  {
    return INFINITY;
  }
  double b = d[0] * o[0] + d[1] * o[1];
  double c = o[0] * o[0] + o[1] * o[1] - r * r;
  double disc = b * b - a * c;
  if (disc < 0.0)
  {
    return INFINITY;
  }
  double t = (-b - sqrt(disc)) / a;
  if (t <= tMin || fabs(o[2] + t * d[2]) > hl)
  {
    return INFINITY;
  }
  n[0] = (o[0] + t * d[0]) / r;
  n[1] = (o[1] + t * d[1]) / r;
  n[2] = 0.0;
  return t;
}

static double hitCylinder(const double* o, const double* d, double r, double length, double tMin, double* n)
{
  double hl = length / 2.0;
  double best = hitSide(o, d, r, hl, tMin, n);
  for (int side = 0; side < 2; ++side)
  {
    double sign = side == 0 ? 1.0 : -1.0;
    if (d[2] * sign >= 0.0)
    {
      continue;
    }
    double t = (sign * hl - o[2]) / d[2];
    double x = o[0] + t * d[0];
    double y = o[1] + t * d[1];
    if (t > tMin && t < best && x * x + y * y <= r * r)
    {
      best = t;
      n[0] = n[1] = 0.0;
      n[2] = sign;
    }
  }
  return best;
}

static double hitCapsule(const double* o, const double* d, double r, double length, double tMin, double* n)
{
  double hl = length / 2.0;
  double best = hitSide(o, d, r, hl, tMin, n);
  for (int side = 0; side < 2; ++side)
  {
    double shifted[3] = { o[0], o[1], o[2] - (side == 0 ? hl : -hl) };
    double normal[3];
    double t = hitSphere(shifted, d, r, tMin, normal);
    if (t < best)
    {
      best = t;
      n[0] = normal[0];
      n[1] = normal[1];
      n[2] = normal[2];
    }
  }
  return best;
}

double hitPrimitive(int type, const double* o, const double* d, const double* params, double tMin, double* n)
{
  switch (type)
  {
    case kBox:
      return hitBox(o, d, params, tMin, n);
    case kSphere:
      return hitSphere(o, d, params[0], tMin, n);
    case kCylinder:
      return hitCylinder(o, d, params[0], params[1], tMin, n);
    case kCapsule:
      return hitCapsule(o, d, params[0], params[1], tMin, n);
    default:
      return INFINITY;
  }
}

/* The nearest hit of the ray start + t d (``d`` a unit vector, both in the mesh's frame) on ``mesh``'s triangles
 * with t in (tMin, best), seen from both sides; ``best`` if none. Counts the tests in ``tests``. */
double meshHit(const Mesh* mesh, const double* start, const double* d, double tMin, double best, long* tests)
{
  for (int f = 0; f < mesh->faceCount; ++f)
  {
    const double* v0 = mesh->vertices + 3 * (long)mesh->faces[3 * (long)f];
    const double* v1 = mesh->vertices + 3 * (long)mesh->faces[3 * (long)f + 1];
    const double* v2 = mesh->vertices + 3 * (long)mesh->faces[3 * (long)f + 2];
    double e1[3], e2[3], toStart[3];
    for (int a = 0; a < 3; ++a)
    {
      e1[a] = v1[a] - v0[a];
      e2[a] = v2[a] - v0[a];
      toStart[a] = start[a] - v0[a];
    }
    ++*tests;
    double q[3];
    cross3(toStart, e1, q);
    double t = triangleHit(d, e1, e2, toStart, q);
    if (t > tMin && t < best)
    {
      best = t;
    }
  }
  return best;
}
