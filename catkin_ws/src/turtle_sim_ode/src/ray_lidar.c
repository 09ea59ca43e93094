/* A multi-beam lidar's rays (see ray_kernel.h): unit rays in any direction from one origin against the shapes, each
 * nearest hit a distance. */
#include "ray_kernel.h"

#include <math.h>
#include <stdlib.h>

/* What tso_rays casts: see tso_rays. */
typedef struct
{
  const double* origin;
  const double* rotation;
  const double* directions;
  Shapes shapes;
  const double* meshRadii;
  double tMin, tMax;
  double* distance;
  /* The broad phase (ray_sectors.c): for each of kAzimuthBuckets sectors of azimuth about the origin, the
   * primitives (k) and then the meshes (count + m) a ray heading into it may meet, ``candidates[bucket * stride
   * ...]``, ``listed[bucket]`` of them; NULL: every ray tests everything. */
  const int* candidates;
  const int* listed;
  int stride;
} Rays;

/* The ray origin + t d in the frame of a shape at ``position`` (``shape``: world from shape, row-major) as start + t
 * local; 0, leaving them unset, where the ray meets the shape's bounding sphere (``radius``) nowhere within (tMin,
 * best). */
static int rayInShape(const Rays* s, const double* d, const double* position, const double* shape, double radius,
                      double best, double* start, double* local)
{
  const double* origin = s->origin;
  double rel[3] = { position[0] - origin[0], position[1] - origin[1], position[2] - origin[2] };
  double along = dot3(rel, d);
  if (along + radius <= s->tMin || along - radius >= best || dot3(rel, rel) - along * along > radius * radius)
  {
    return 0;
  }
  for (int a = 0; a < 3; ++a)
  {
    start[a] = -(shape[a] * rel[0] + shape[3 + a] * rel[1] + shape[6 + a] * rel[2]);
    local[a] = shape[a] * d[0] + shape[3 + a] * d[1] + shape[6 + a] * d[2];
  }
  return 1;
}

/* The band's rays: every primitive and mesh whose bounding sphere the ray passes within (tMin, best so far). */
static void* raysBand(void* arg)
{
  Band* band = (Band*)arg;
  const Rays* s = (const Rays*)band->job;
  const Shapes* shapes = &s->shapes;
  long tests = 0;
  for (int r = band->rowBegin; r < band->rowEnd; ++r)
  {
    /* The ray in the world: the rotation (row-major) times the ray in the sensor frame. */
    const double* ray = s->directions + 3 * (long)r;
    const double* R = s->rotation;
    double d[3];
    for (int a = 0; a < 3; ++a)
    {
      d[a] = R[3 * a] * ray[0] + R[3 * a + 1] * ray[1] + R[3 * a + 2] * ray[2];
    }
    double best = INFINITY;
    const int* candidates = NULL;
    int listed = shapes->count + shapes->meshCount;
    if (s->candidates != NULL)
    {
      int bucket = headingSector(d[0], d[1]);
      candidates = s->candidates + (long)bucket * s->stride;
      listed = s->listed[bucket];
    }
    /* Primitives first, then meshes (in index order either way): the nearest hit does not depend on the order. */
    int c = 0;
    for (; c < listed; ++c)
    {
      int k = candidates != NULL ? candidates[c] : c;
      if (k >= shapes->count)
      {
        break;
      }
      const double* row = shapes->primitives + (long)k * kStride;
      int type = (int)row[0];
      const double* shape = row + kRotation; /* world from shape; a plane's normal */
      const double* params = row + kParams;
      if (type == kPlane)
      {
        ++tests;
        double facing = dot3(shape, d);
        if (facing < 0.0)
        {
          double t = (params[0] - dot3(shape, s->origin)) / facing;
          if (t > s->tMin && t < best)
          {
            best = t;
          }
        }
        continue;
      }
      double start[3], local[3];
      if (!rayInShape(s, d, row + kPosition, shape, row[kRadius], best, start, local))
      {
        continue;
      }
      double n[3];
      ++tests;
      double t = hitPrimitive(type, start, local, params, s->tMin, n);
      if (t < best)
      {
        best = t;
      }
    }
    for (; c < listed; ++c)
    {
      int m = (candidates != NULL ? candidates[c] : c) - shapes->count;
      const Mesh* mesh = &shapes->meshes[m];
      double start[3], local[3];
      if (rayInShape(s, d, mesh->pose, mesh->pose + 3, s->meshRadii[m], best, start, local))
      {
        best = meshHit(mesh, start, local, s->tMin, best, &tests);
      }
    }
    s->distance[r] = best <= s->tMax ? best : s->tMax;
  }
  band->count = tests;
  return NULL;
}

/* A multi-beam lidar's rays: ``rayCount`` unit ``directions`` (the sensor's frame, 3 doubles each; ``rotation``, 9
 * row-major, takes them to the world's) from ``origin`` against ``count`` primitives (rows as tso_render's; planes
 * included) and ``meshCount`` meshes (``meshRadii``: each mesh's bounding radius about its position). Fills
 * ``distance`` with each ray's nearest hit at a distance in (tMin, tMax], tMax where there is none (as a ray sensor
 * reads), in up to ``threads`` bands of rays at once. Returns the number of ray tests made. */
long tso_rays(int rayCount, const double* origin, const double* rotation, const double* directions, int count,
              const double* primitives, int meshCount, const Mesh* meshes, const double* meshRadii, double tMin,
              double tMax, double* distance, int threads)
{
  Shapes shapes = { count, primitives, meshCount, meshes };
  Rays job = { origin, rotation, directions, shapes, meshRadii, tMin, tMax, distance, NULL, NULL, 0 };
  int shapeCount = count + meshCount;
  int* candidates = NULL;
  int* listed = NULL;
  /* Sorting shapes into sectors pays once there are more rays than sectors (a 2D lidar's few hundred do without). */
  if (rayCount > kAzimuthBuckets && shapeCount > 0)
  {
    candidates = malloc(sizeof(int) * (size_t)kAzimuthBuckets * (size_t)shapeCount);
    listed = calloc(kAzimuthBuckets, sizeof(int));
  }
  if (candidates != NULL && listed != NULL)
  {
    for (int k = 0; k < shapeCount; ++k)
    {
      const double* row = k < count ? primitives + (long)k * kStride : NULL;
      const double* position = row != NULL ? row + kPosition : meshes[k - count].pose;
      double radius = row != NULL ? row[kRadius] : meshRadii[k - count];
      listShape(row, position, radius, origin, k, candidates, listed, shapeCount);
    }
    job.candidates = candidates;
    job.listed = listed;
    job.stride = shapeCount;
  }
  long tests = runBands(threads, rayCount, raysBand, &job);
  free(candidates);
  free(listed);
  return tests;
}
