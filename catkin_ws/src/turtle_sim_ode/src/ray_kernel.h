/* The cameras' and lidars' ray caster (libturtle_sim_ode_rays.so, loaded by turtle_sim_ode.sensors.ray_kernel through
 * ctypes): rays against primitive shapes (box, sphere, cylinder, capsule along z, plane) and triangle meshes. The same
 * tests as turtle_sim_ode.sensors.raycast, which the Python side uses where this library is not built.
 *
 * The library's files, one a part:
 * - ray_shapes.c: a ray against one primitive or one mesh (a triangle's test, the innermost, is inline here);
 * - ray_image_box.c: the pixels a shape's projection may cover (cameras test only those);
 * - ray_camera.c: tso_render, a camera's picture, one ray per pixel;
 * - ray_cloud.c: tso_cloud, a depth camera's image and point cloud from a picture;
 * - ray_lidar.c: tso_rays, a multi-beam lidar's rays in any direction;
 * - ray_sectors.c: the lidar's broad phase, the shapes a ray heading into a sector of azimuth may meet;
 * - ray_bands.c: a job split into bands of rows run on threads;
 * - ray_velodyne.c: tso_velodyne_cloud, a Velodyne's cloud from a lidar's scan.
 * This header is theirs alone: only tso_render, tso_cloud, tso_rays and tso_velodyne_cloud are exported. */
#ifndef TURTLE_SIM_ODE_RAY_KERNEL_H
#define TURTLE_SIM_ODE_RAY_KERNEL_H

#include <math.h>
#include <stdint.h>

enum
{
  kBox = 0,
  kSphere = 1,
  kCylinder = 2,
  kCapsule = 3,
  kPlane = 4
};

/* One primitive row: type, position (3), rotation world-from-shape row-major (9), parameters (3: box half extents;
 * sphere radius; cylinder and capsule radius and length; plane normal (world) in the rotation's place and offset
 * as parameter 0), colour (3), bounding radius. */
enum
{
  kStride = 20,
  kPosition = 1,
  kRotation = 4,
  kParams = 13,
  kColour = 16,
  kRadius = 19
};

/* A triangle mesh (a trimesh geom): ``pose`` is its position (3), rotation world from mesh (9, row-major) and
 * colour (3); ``faces`` has three indices into ``vertices`` (x, y, z in the mesh's frame) a triangle. */
typedef struct
{
  const double* pose;
  int faceCount;
  const double* vertices;
  const uint32_t* faces;
} Mesh;

/* What the rays may meet: ``count`` primitive rows and ``meshCount`` meshes. */
typedef struct
{
  int count;
  const double* primitives;
  int meshCount;
  const Mesh* meshes;
} Shapes;

/* One thread's share of a job: the job (a camera's Scene, a Cloud, a lidar's Rays), the rows [rowBegin, rowEnd), and
 * what it counted (ray tests; points left out of the cloud). */
typedef struct
{
  const void* job;
  int rowBegin, rowEnd;
  long count;
} Band;

static inline double dot3(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void cross3(const double* a, const double* b, double* out)
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Moller-Trumbore: the parameter t at which the ray origin + t d meets the triangle v0 + a e1 + b e2 (either side),
 * INFINITY if it misses (inline: the innermost test of the cameras' and the lidars' meshes); ``toOrigin`` = origin - v0
 * and ``q`` = toOrigin x e1, the same for every ray from origin. */
static inline double triangleHit(const double* d, const double* e1, const double* e2, const double* toOrigin,
                                 const double* q)
{
  double pv[3];
  cross3(d, e2, pv);
  double det = dot3(e1, pv);
  if (det == 0.0)
  {
    return INFINITY;
  }
  double inverse = 1.0 / det;
  double a = dot3(toOrigin, pv) * inverse;
  double b = dot3(d, q) * inverse;
  if (a < 0.0 || b < 0.0 || a + b > 1.0)
  {
    return INFINITY;
  }
  return dot3(e2, q) * inverse;
}

#pragma GCC visibility push(hidden)

/* ray_shapes.c. A ray o + t d in a primitive's frame (``type`` not a plane, with its ``params``): the smallest
 * t > tMin at which it enters the shape, INFINITY if none; ``n`` gets the unit normal there (shape's frame). */
double hitPrimitive(int type, const double* o, const double* d, const double* params, double tMin, double* n);
/* The nearest hit on a mesh's triangles within (tMin, best), ``best`` if none; counts the tests in ``tests``. */
double meshHit(const Mesh* mesh, const double* start, const double* d, double tMin, double best, long* tests);

/* ray_image_box.c: box gets the pixels [box[0], box[1]) x [box[2], box[3]) a shape may cover; 0 if none. */
int pixelBox(const double* centre, const double* axes, const double* half, double near, double far, double focal,
             double cx, double cy, int width, int height, int* box);
int trianglePixelBox(const double (*corners)[3], double near, double far, double focal, double cx, double cy, int width,
                     int height, int* box);

/* ray_sectors.c */
enum
{
  /* Sectors of azimuth: a VLP-16's 1800 columns are ~3.5 a sector, and a shape a few degrees wide is in a few. */
  kAzimuthBuckets = 512
};
int headingSector(double x, double y);
void listShape(const double* row, const double* position, double radius, const double* origin, int index,
               int* candidates, int* listed, int stride);

/* ray_bands.c */
long runBands(int threads, int height, void* (*work)(void*), const void* job);

#pragma GCC visibility pop

long tso_render(int width, int height, const double* origin, const double* rotation, int count,
                const double* primitives, int meshCount, const Mesh* meshes, double tMin, double far, double focal,
                double cx, double cy, const double* light, double ambient, const double* sky, double* distance,
                float* depth, uint8_t* rgb, int threads);
long tso_cloud(int width, int height, const float* depth, const uint8_t* rgb, double focal, double cx, double cy,
               double cutoff, double cutoffMax, float* depthOut, uint8_t* cloud, int threads);
long tso_rays(int rayCount, const double* origin, const double* rotation, const double* directions, int count,
              const double* primitives, int meshCount, const Mesh* meshes, const double* meshRadii, double tMin,
              double tMax, double* distance, int threads);
long tso_velodyne_cloud(int azimuths, int rings, const double* ranges, const double* normals, double sigma, double low,
                        double high, int organised, int intensityKept, const double* directions, uint8_t* points);

#endif
