/* The cameras' ray caster (loaded by turtle_sim_ode.sensors.ray_kernel through ctypes): one ray per pixel from the
 * optical centre against primitive shapes (box, sphere, cylinder, capsule along z, plane) and triangle meshes, each
 * tested only in the pixels its projection may cover. The same tests as turtle_sim_ode.sensors.raycast, which the
 * Python side uses where this library is not built, but on rays (u, v, 1) whose parameter is the depth (numpy: unit
 * rays, the near clip turned into a distance per ray); both clip at the near plane, as OpenGL does. The multi-beam
 * lidars' rays (tso_rays, at the end) are unit rays in any direction against the same shapes. */
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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

static double dot3(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

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

/* The pixels [box[0], box[1]) x [box[2], box[3]) where a solid with ``count`` corners ``points`` (optical frame)
 * and ``edgeCount`` ``edges`` (pairs of corner indices) may show: the bounding rectangle of its corners in front
 * of the near plane and of its edges' crossings of that plane. 0 if it lies wholly before the near plane, beyond
 * far, or outside the image. */
static int imageBox(const double (*points)[3], int count, const uint8_t (*edges)[2], int edgeCount, double near,
                    double far, double focal, double cx, double cy, int width, int height, int* box)
{
  double zMin = INFINITY, zMax = -INFINITY;
  for (int k = 0; k < count; ++k)
  {
    zMin = fmin(zMin, points[k][2]);
    zMax = fmax(zMax, points[k][2]);
  }
  if (zMax < near || zMin > far)
  {
    return 0;
  }
  double u0 = INFINITY, u1 = -INFINITY, v0 = INFINITY, v1 = -INFINITY;
  for (int k = 0; k < count; ++k)
  {
    const double* p = points[k];
    if (p[2] >= near)
    {
      u0 = fmin(u0, p[0] / p[2]);
      u1 = fmax(u1, p[0] / p[2]);
      v0 = fmin(v0, p[1] / p[2]);
      v1 = fmax(v1, p[1] / p[2]);
    }
  }
  for (int e = 0; e < edgeCount; ++e)
  {
    const double* p = points[edges[e][0]];
    const double* q = points[edges[e][1]];
    if ((p[2] < near) == (q[2] < near))
    {
      continue;
    }
    double s = (near - p[2]) / (q[2] - p[2]);
    double x = (p[0] + s * (q[0] - p[0])) / near;
    double y = (p[1] + s * (q[1] - p[1])) / near;
    u0 = fmin(u0, x);
    u1 = fmax(u1, x);
    v0 = fmin(v0, y);
    v1 = fmax(v1, y);
  }
  /* In pixels, clamped to the image before the conversion to int (the crossings may project very far out). */
  box[0] = (int)fmax(0.0, floor(fmax(-1.0, u0 * focal + cx)));
  box[1] = (int)fmin((double)width, ceil(fmin((double)width, u1 * focal + cx)) + 1.0);
  box[2] = (int)fmax(0.0, floor(fmax(-1.0, v0 * focal + cy)));
  box[3] = (int)fmin((double)height, ceil(fmin((double)height, v1 * focal + cy)) + 1.0);
  return box[0] < box[1] && box[2] < box[3];
}

/* The 12 edges of a box whose corner k has the sign of half extent a in bit a. */
static const uint8_t kBoxEdges[12][2] = { { 0, 1 }, { 2, 3 }, { 4, 5 }, { 6, 7 }, { 0, 2 }, { 1, 3 },
                                          { 4, 6 }, { 5, 7 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
static const uint8_t kTriangleEdges[3][2] = { { 0, 1 }, { 1, 2 }, { 2, 0 } };

/* imageBox of a shape's bounding box: ``half`` extents along ``axes`` (the rows of a 3 x 3: the shape's axes in
 * optical coordinates) about ``centre`` in the optical frame. */
static int pixelBox(const double* centre, const double* axes, const double* half, double near, double far, double focal,
                    double cx, double cy, int width, int height, int* box)
{
  double corners[8][3];
  for (int k = 0; k < 8; ++k)
  {
    for (int b = 0; b < 3; ++b)
    {
      corners[k][b] = centre[b];
      for (int a = 0; a < 3; ++a)
      {
        corners[k][b] += ((k >> a) & 1 ? half[a] : -half[a]) * axes[3 * a + b];
      }
    }
  }
  return imageBox((const double(*)[3])corners, 8, kBoxEdges, 12, near, far, focal, cx, cy, width, height, box);
}

static uint8_t channel(double value)
{
  return (uint8_t)(value <= 0.0 ? 0.0 : value >= 1.0 ? 255.0 : value * 255.0 + 0.5);
}

/* A triangle mesh (a trimesh geom): ``pose`` is its position (3), rotation world from mesh (9, row-major) and
 * colour (3); ``faces`` has three indices into ``vertices`` (x, y, z in the mesh's frame) a triangle. */
typedef struct
{
  const double* pose;
  int faceCount;
  const double* vertices;
  const uint32_t* faces;
} Mesh;

/* What tso_render draws and where it writes: see tso_render. */
typedef struct
{
  int width, height;
  const double* origin;
  const double* rotation;
  int count;
  const double* primitives;
  int meshCount;
  const Mesh* meshes;
  double tMin, far, focal, cx, cy;
  const double* light;
  double ambient;
  const double* sky;
  double* distance;
  float* depth;
  uint8_t* rgb;
} Scene;

/* ``colour`` lit by the scene's ambient light and its sun on a surface of unit ``normal`` (world frame). */
static void shadeInto(const Scene* s, const double* colour, const double* normal, uint8_t* out)
{
  double lit = dot3(normal, s->light);
  double shade = s->ambient + (1.0 - s->ambient) * (lit <= 0.0 ? 0.0 : lit >= 1.0 ? 1.0 : lit);
  out[0] = channel(colour[0] * shade);
  out[1] = channel(colour[1] * shade);
  out[2] = channel(colour[2] * shade);
}

/* One thread's share of a picture: its job (a Scene or a Cloud), the rows [rowBegin, rowEnd), and what it counted
 * (ray tests; points left out of the cloud). */
typedef struct
{
  const void* job;
  int rowBegin, rowEnd;
  long count;
} Band;

/* The plane normal . p = offset (``normal`` in the world frame, ``height`` = offset - normal . origin), seen from
 * its front, in rows [j0, j1): its depth along a pixel's ray (u, v, 1) is height / (normal . ray), and the normal,
 * so the shade, is the same everywhere. Returns the ray tests made. */
static long planeRows(const Scene* s, int j0, int j1, const double* normal, double height, const double* colour,
                      double* restrict distance, uint8_t* restrict rgb)
{
  const double* rotation = s->rotation; /* world from optical: the ray's world direction is rotation (u, v, 1) */
  const double invFocal = 1.0 / s->focal;
  double perU = 0.0, perV = 0.0, ahead = 0.0; /* normal . ray = perU u + perV v + ahead */
  for (int a = 0; a < 3; ++a)
  {
    perU += normal[a] * rotation[3 * a];
    perV += normal[a] * rotation[3 * a + 1];
    ahead += normal[a] * rotation[3 * a + 2];
  }
  uint8_t shade[3];
  shadeInto(s, colour, normal, shade);
  for (int j = j0; j < j1; ++j)
  {
    double rowFacing = perV * ((j - s->cy) * invFocal) + ahead;
    for (int i = 0; i < s->width; ++i)
    {
      double facing = perU * ((i - s->cx) * invFocal) + rowFacing;
      if (!(facing < 0.0))
      {
        continue;
      }
      double t = height / facing;
      int p = j * s->width + i;
      if (t > s->tMin && t < distance[p])
      {
        distance[p] = t;
        memcpy(rgb + 3 * p, shade, 3);
      }
    }
  }
  return (long)(j1 - j0) * s->width;
}

static void cross3(const double* a, const double* b, double* out)
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Moller-Trumbore: the parameter t at which the ray origin + t d meets the triangle v0 + a e1 + b e2 (either side),
 * INFINITY if it misses; ``toOrigin`` = origin - v0 and ``q`` = toOrigin x e1, the same for every ray from origin. */
static double triangleHit(const double* d, const double* e1, const double* e2, const double* toOrigin, const double* q)
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

/* A mesh's triangles in rows [rowBegin, rowEnd), each in the pixels its projection may cover, seen from both sides
 * (a mesh need not be closed, nor its faces wound one way) with one shade a triangle. Returns the ray tests made. */
static long meshRows(const Scene* s, const Mesh* mesh, int rowBegin, int rowEnd, double* restrict distance,
                     uint8_t* restrict rgb)
{
  const double* origin = s->origin;
  const double* rotation = s->rotation;
  const double* position = mesh->pose;
  const double* shape = mesh->pose + 3; /* world from mesh */
  const double* colour = mesh->pose + 12;
  const double invFocal = 1.0 / s->focal;
  double rel[3] = { position[0] - origin[0], position[1] - origin[1], position[2] - origin[2] };
  double centre[3]; /* the mesh's origin in the optical frame */
  double local[9];  /* mesh from optical */
  double start[3];  /* the camera in the mesh's frame */
  for (int a = 0; a < 3; ++a)
  {
    centre[a] = rotation[a] * rel[0] + rotation[3 + a] * rel[1] + rotation[6 + a] * rel[2];
    for (int b = 0; b < 3; ++b)
    {
      local[3 * a + b] = shape[a] * rotation[b] + shape[3 + a] * rotation[3 + b] + shape[6 + a] * rotation[6 + b];
    }
    start[a] = -(shape[a] * rel[0] + shape[3 + a] * rel[1] + shape[6 + a] * rel[2]);
  }
  long tests = 0;
  for (int f = 0; f < mesh->faceCount; ++f)
  {
    const double* v[3];
    double corners[3][3]; /* optical frame */
    for (int k = 0; k < 3; ++k)
    {
      v[k] = mesh->vertices + 3 * (long)mesh->faces[3 * (long)f + k];
      for (int b = 0; b < 3; ++b)
      {
        corners[k][b] = centre[b] + local[b] * v[k][0] + local[3 + b] * v[k][1] + local[6 + b] * v[k][2];
      }
    }
    int box[4];
    if (!imageBox((const double(*)[3])corners, 3, kTriangleEdges, 3, s->tMin, s->far, s->focal, s->cx, s->cy, s->width,
                  s->height, box))
    {
      continue;
    }
    int j0 = box[2] > rowBegin ? box[2] : rowBegin;
    int j1 = box[3] < rowEnd ? box[3] : rowEnd;
    double e1[3], e2[3], normal[3], toCamera[3];
    for (int a = 0; a < 3; ++a)
    {
      e1[a] = v[1][a] - v[0][a];
      e2[a] = v[2][a] - v[0][a];
      toCamera[a] = start[a] - v[0][a];
    }
    cross3(e1, e2, normal);
    double length = sqrt(dot3(normal, normal));
    if (j0 >= j1 || !(length > 0.0))
    {
      continue; /* not in this band, or degenerate */
    }
    double side = dot3(normal, toCamera) < 0.0 ? -1.0 : 1.0; /* the face towards the camera */
    double world[3];
    for (int a = 0; a < 3; ++a)
    {
      world[a] =
          side * (shape[3 * a] * normal[0] + shape[3 * a + 1] * normal[1] + shape[3 * a + 2] * normal[2]) / length;
    }
    uint8_t shade[3];
    shadeInto(s, colour, world, shade);
    double q[3]; /* Moller-Trumbore: toCamera x e1 is the same for every ray */
    cross3(toCamera, e1, q);
    for (int j = j0; j < j1; ++j)
    {
      double vv = (j - s->cy) * invFocal;
      for (int i = box[0]; i < box[1]; ++i)
      {
        double u = (i - s->cx) * invFocal;
        double d[3];
        for (int a = 0; a < 3; ++a)
        {
          d[a] = local[3 * a] * u + local[3 * a + 1] * vv + local[3 * a + 2];
        }
        ++tests;
        double t = triangleHit(d, e1, e2, toCamera, q); /* the hit's depth: the ray's optical z is 1 */
        int p = j * s->width + i;
        if (t > s->tMin && t < distance[p])
        {
          distance[p] = t;
          memcpy(rgb + 3 * p, shade, 3);
        }
      }
    }
  }
  return tests;
}

/* The band's rows of the picture, every primitive, then the sky where nothing was hit within far. */
static void* renderBand(void* arg)
{
  Band* band = (Band*)arg;
  const Scene* s = (const Scene*)band->job;
  const int width = s->width;
  const double* origin = s->origin;
  const double* rotation = s->rotation;
  const double invFocal = 1.0 / s->focal;
  const double tMin = s->tMin;
  /* Local copies: stores through the uint8_t pointer could alias anything the struct points to. */
  double* restrict distance = s->distance;
  uint8_t* restrict rgb = s->rgb;
  long tests = 0;
  for (int p = band->rowBegin * width; p < band->rowEnd * width; ++p)
  {
    distance[p] = INFINITY;
  }
  for (int m = 0; m < s->meshCount; ++m)
  {
    tests += meshRows(s, &s->meshes[m], band->rowBegin, band->rowEnd, distance, rgb);
  }
  for (int k = 0; k < s->count; ++k)
  {
    const double* row = s->primitives + (long)k * kStride;
    int type = (int)row[0];
    const double* position = row + kPosition;
    const double* shape = row + kRotation; /* world from shape */
    const double* params = row + kParams;
    const double* colour = row + kColour;
    int i0 = 0, i1 = width, j0 = band->rowBegin, j1 = band->rowEnd;
    double local[9]; /* shape from optical: shape^T rotation */
    double start[3]; /* the origin in the shape's frame */
    if (type != kPlane)
    {
      double rel[3] = { position[0] - origin[0], position[1] - origin[1], position[2] - origin[2] };
      double c[3]; /* the centre in the optical frame: rotation^T rel */
      for (int a = 0; a < 3; ++a)
      {
        c[a] = rotation[a] * rel[0] + rotation[3 + a] * rel[1] + rotation[6 + a] * rel[2];
      }
      for (int a = 0; a < 3; ++a)
      {
        for (int b = 0; b < 3; ++b)
        {
          local[3 * a + b] = shape[a] * rotation[b] + shape[3 + a] * rotation[3 + b] + shape[6 + a] * rotation[6 + b];
        }
        start[a] = -(shape[a] * rel[0] + shape[3 + a] * rel[1] + shape[6 + a] * rel[2]);
      }
      double half[3] = { params[0], params[0], params[0] };
      if (type == kBox)
      {
        half[1] = params[1];
        half[2] = params[2];
      }
      else if (type == kCylinder || type == kCapsule)
      {
        half[2] = params[1] / 2.0 + (type == kCapsule ? params[0] : 0.0);
      }
      int box[4];
      if (!pixelBox(c, local, half, tMin, s->far, s->focal, s->cx, s->cy, width, s->height, box))
      {
        continue;
      }
      i0 = box[0];
      i1 = box[1];
      j0 = box[2] > j0 ? box[2] : j0;
      j1 = box[3] < j1 ? box[3] : j1;
    }
    else
    {
      for (int a = 0; a < 9; ++a)
      {
        local[a] = rotation[a];
      }
      start[0] = origin[0];
      start[1] = origin[1];
      start[2] = origin[2];
    }
    if (type == kPlane)
    {
      tests += planeRows(s, j0, j1, shape, params[0] - dot3(shape, start), colour, distance, rgb);
      continue;
    }
    /* A box face has one shade: 2 * axis + (1 on the positive side). */
    uint8_t flat[6][3];
    if (type == kBox)
    {
      for (int face = 0; face < 6; ++face)
      {
        double sign = face % 2 ? 1.0 : -1.0;
        double world[3] = { sign * shape[face / 2], sign * shape[3 + face / 2], sign * shape[6 + face / 2] };
        shadeInto(s, colour, world, flat[face]);
      }
    }
    for (int j = j0; j < j1; ++j)
    {
      double v = (j - s->cy) * invFocal;
      double rowBase[3];
      for (int a = 0; a < 3; ++a)
      {
        rowBase[a] = local[3 * a + 1] * v + local[3 * a + 2];
      }
      for (int i = i0; i < i1; ++i)
      {
        int p = j * width + i;
        double u = (i - s->cx) * invFocal;
        double d[3]; /* the pixel's ray (u, v, 1) in the optical frame, in the shape's frame: t is its depth */
        for (int a = 0; a < 3; ++a)
        {
          d[a] = local[3 * a] * u + rowBase[a];
        }
        double n[3];
        double t = INFINITY;
        ++tests;
        switch (type)
        {
          case kBox:
            t = hitBox(start, d, params, tMin, n);
            break;
          case kSphere:
            t = hitSphere(start, d, params[0], tMin, n);
            break;
          case kCylinder:
            t = hitCylinder(start, d, params[0], params[1], tMin, n);
            break;
          case kCapsule:
            t = hitCapsule(start, d, params[0], params[1], tMin, n);
            break;
          default:
            break;
        }
        if (!(t < distance[p]))
        {
          continue;
        }
        distance[p] = t;
        uint8_t* out = rgb + 3 * p;
        if (type == kBox)
        {
          int axis = n[0] != 0.0 ? 0 : n[1] != 0.0 ? 1 : 2;
          memcpy(out, flat[2 * axis + (n[axis] > 0.0)], 3);
        }
        else
        {
          double world[3];
          for (int a = 0; a < 3; ++a)
          {
            world[a] = shape[3 * a] * n[0] + shape[3 * a + 1] * n[1] + shape[3 * a + 2] * n[2];
          }
          shadeInto(s, colour, world, out);
        }
      }
    }
  }
  for (int p = band->rowBegin * width; p < band->rowEnd * width; ++p)
  {
    double z = distance[p];
    if (z <= s->far)
    {
      s->depth[p] = (float)z;
    }
    else
    {
      distance[p] = INFINITY;
      s->depth[p] = NAN;
      rgb[3 * p] = channel(s->sky[0]);
      rgb[3 * p + 1] = channel(s->sky[1]);
      rgb[3 * p + 2] = channel(s->sky[2]);
    }
  }
  band->count = tests;
  return NULL;
}

enum
{
  kMaxThreads = 8,
  kMinRowsPerThread = 16 /* below this a thread costs more than it saves */
};

/* Runs ``work`` on ``job`` in up to ``threads`` bands of ``height`` rows: the calling thread takes the first, a new
 * thread each other band (a thread that cannot be started leaves its band to the calling thread). Returns the sum
 * of the bands' counts. */
static long runBands(int threads, int height, void* (*work)(void*), const void* job)
{
  int wanted = height / kMinRowsPerThread;
  int count = threads < wanted ? threads : wanted;
  count = count < 1 ? 1 : count > kMaxThreads ? kMaxThreads : count;
  Band bands[kMaxThreads];
  pthread_t ids[kMaxThreads];
  int started[kMaxThreads] = { 0 };
  for (int b = 0; b < count; ++b)
  {
    bands[b].job = job;
    bands[b].rowBegin = (int)((long)height * b / count);
    bands[b].rowEnd = (int)((long)height * (b + 1) / count);
    bands[b].count = 0;
  }
  for (int b = 1; b < count; ++b)
  {
    started[b] = pthread_create(&ids[b], NULL, work, &bands[b]) == 0;
  }
  work(&bands[0]);
  for (int b = 1; b < count; ++b)
  {
    if (started[b])
    {
      pthread_join(ids[b], NULL);
    }
    else
    {
      work(&bands[b]);
    }
  }
  long total = 0;
  for (int b = 0; b < count; ++b)
  {
    total += bands[b].count;
  }
  return total;
}

/* Render ``count`` primitives and ``meshCount`` meshes seen from ``origin`` with ``rotation`` (world from optical,
 * row-major), one ray through each pixel's centre: (u, v, 1) in the optical frame with u = (i - cx) / focal, v = (j -
 * cy) / focal, so that a ray's parameter at a hit is the hit's depth along the optical axis. Fills ``distance`` (that
 * depth, INFINITY where nothing is hit at a depth within (tMin, far]), ``depth`` (the same as float, NAN there) and
 * ``rgb`` (shaded colours, ``sky`` there), in up to ``threads`` bands of rows at once. Returns the number of ray tests
 * made. */
long tso_render(int width, int height, const double* origin, const double* rotation, int count,
                const double* primitives, int meshCount, const Mesh* meshes, double tMin, double far, double focal,
                double cx, double cy, const double* light, double ambient, const double* sky, double* distance,
                float* depth, uint8_t* rgb, int threads)
{
  Scene scene = { width, height, origin, rotation, count,   primitives, meshCount, meshes, tMin, far,
                  focal, cx,     cy,     light,    ambient, sky,        distance,  depth,  rgb };
  return runBands(threads, height, renderBand, &scene);
}

/* What tso_cloud reads and writes: see tso_cloud. */
typedef struct
{
  int width;
  const float* depth;
  const uint8_t* rgb;
  double focal, cx, cy, cutoff, cutoffMax;
  float* depthOut;
  uint8_t* cloud;
} Cloud;

static void* cloudBand(void* arg)
{
  Band* band = (Band*)arg;
  const Cloud* c = (const Cloud*)band->job;
  long missing = 0;
  for (int j = band->rowBegin; j < band->rowEnd; ++j)
  {
    double y = (j - c->cy) / c->focal;
    for (int i = 0; i < c->width; ++i)
    {
      long p = (long)j * c->width + i;
      float z = c->depth[p];
      float point[3];
      if (z > c->cutoff && z < c->cutoffMax)
      {
        point[0] = (float)(z * ((i - c->cx) / c->focal));
        point[1] = (float)(z * y);
        point[2] = z;
      }
      else
      {
        z = NAN;
        point[0] = point[1] = point[2] = NAN;
        ++missing;
      }
      c->depthOut[p] = z;
      uint8_t* out = c->cloud + 32 * p;
      memcpy(out, point, sizeof point);
      out[16] = c->rgb[3 * p + 2];
      out[17] = c->rgb[3 * p + 1];
      out[18] = c->rgb[3 * p];
    }
  }
  band->count = missing;
  return NULL;
}

/* gazebo_ros_openni_kinect's depth image and organised cloud from a rendering's ``depth`` and ``rgb``: ``depthOut``
 * keeps the depths within (cutoff, cutoffMax), NAN elsewhere; ``cloud`` gets 32 bytes a point: x, y, z (float32,
 * optical frame, NAN outside the cutoffs), 4 bytes of padding, b, g, r, 0, and 12 of padding; the padding bytes
 * are left as they are (zeros: the caller's buffer is zeroed once and reused). Up to ``threads`` bands of rows at
 * once. Returns the number of NAN points. */
long tso_cloud(int width, int height, const float* depth, const uint8_t* rgb, double focal, double cx, double cy,
               double cutoff, double cutoffMax, float* depthOut, uint8_t* cloud, int threads)
{
  Cloud job = { width, depth, rgb, focal, cx, cy, cutoff, cutoffMax, depthOut, cloud };
  return runBands(threads, height, cloudBand, &job);
}

/* What tso_rays casts: see tso_rays. */
typedef struct
{
  const double* origin;
  const double* directions;
  int count;
  const double* primitives;
  int meshCount;
  const Mesh* meshes;
  const double* meshRadii;
  double tMin, tMax;
  double* distance;
  /* The broad phase: for each of kAzimuthBuckets sectors of azimuth about the origin, the primitives (k) and then
   * the meshes (count + m) a ray heading into it may meet, ``candidates[bucket * stride ...]``, ``listed[bucket]``
   * of them; NULL: every ray tests everything. */
  const int* candidates;
  const int* listed;
  int stride;
} Rays;

enum
{
  /* Sectors of azimuth: a VLP-16's 1800 columns are ~3.5 a sector, and a shape a few degrees wide is in a few. */
  kAzimuthBuckets = 512
};

/* The nearest hit of the ray start + t d (``d`` a unit vector, both in the mesh's frame) on ``mesh``'s triangles
 * with t in (tMin, best), seen from both sides; ``best`` if none. Counts the tests in ``tests``. */
static double meshHit(const Mesh* mesh, const double* start, const double* d, double tMin, double best, long* tests)
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

static const double kPi = 3.14159265358979323846;

/* A pseudo-angle of the heading (x, y): in [0, 4), rising with the angle from +x towards +y as atan2 does (one
 * quarter turn per unit) at the cost of a division; 0 for (0, 0). */
static double pseudoAngle(double x, double y)
{
  double sum = fabs(x) + fabs(y);
  if (sum == 0.0)
  {
    return 0.0;
  }
  double p = y >= 0.0 ? (x >= 0.0 ? y / sum : 1.0 - x / sum) : (x < 0.0 ? 2.0 - y / sum : 3.0 + x / sum);
  return p < 4.0 ? p : 0.0;
}

/* The sector of a heading's pseudo-angle. */
static int sectorOf(double pseudo)
{
  int sector = (int)(pseudo * (kAzimuthBuckets / 4.0));
  return sector < 0 ? 0 : sector >= kAzimuthBuckets ? kAzimuthBuckets - 1 : sector;
}

/* The headings (radians about ``heading``, the centre's) of ``count`` corners (x, y) seen from the origin, as an
 * interval [*low, *high]: 0 if they do not all lie within less than half a turn of it (the origin then may be inside
 * their hull, and a ray in any heading may meet the shape). */
static int headingSpan(const double (*corners)[2], int count, double heading, double* low, double* high)
{
  *low = INFINITY;
  *high = -INFINITY;
  for (int k = 0; k < count; ++k)
  {
    double turn = atan2(corners[k][1], corners[k][0]) - heading;
    turn = turn > kPi ? turn - 2.0 * kPi : turn < -kPi ? turn + 2.0 * kPi : turn;
    *low = fmin(*low, turn);
    *high = fmax(*high, turn);
  }
  return *high - *low < 0.9 * kPi;
}

/* Lists shape ``index`` in every sector of heading a ray from ``origin`` may take to meet it: the headings of its
 * bounding box's corners (a box's own, a cylinder's or capsule's about its axis) seen from above, or of its bounding
 * sphere (a sphere, a mesh; radius ``radius`` about ``position``), a projection bringing no point nearer. In every
 * sector for a plane, or a shape the origin's vertical may pass through. Widened by a sector each side, so rounding
 * never drops a ray the exact test would keep. */
static void listShape(const double* row, const double* position, double radius, const double* origin, int index,
                      int* candidates, int* listed, int stride)
{
  int type = row != NULL ? (int)row[0] : kSphere;
  double x = position[0] - origin[0];
  double y = position[1] - origin[1];
  double heading = atan2(y, x);
  double low = 0.0, high = 0.0;
  int bounded = 0;
  if (type == kSphere && hypot(x, y) > radius * (1.0 + 1e-9) + 1e-12)
  {
    double spread = asin(fmin(1.0, radius / hypot(x, y)));
    low = -spread;
    high = spread;
    bounded = spread < 0.45 * kPi;
  }
  else if (type == kBox || type == kCylinder || type == kCapsule)
  {
    const double* params = row + kParams;
    const double* shape = row + kRotation; /* world from shape, row-major */
    double half[3] = { params[0], params[1], params[2] };
    if (type != kBox)
    {
      half[1] = params[0];
      half[2] = params[1] / 2.0 + (type == kCapsule ? params[0] : 0.0);
    }
    double corners[8][2];
    for (int k = 0; k < 8; ++k)
    {
      corners[k][0] = x;
      corners[k][1] = y;
      for (int a = 0; a < 3; ++a)
      {
        double along = (k >> a) & 1 ? half[a] : -half[a];
        corners[k][0] += shape[a] * along;
        corners[k][1] += shape[3 + a] * along;
      }
    }
    bounded = headingSpan((const double(*)[2])corners, 8, heading, &low, &high);
  }
  long first = 0, last = kAzimuthBuckets - 1;
  if (bounded)
  {
    first = sectorOf(pseudoAngle(cos(heading + low), sin(heading + low))) - 1;
    last = sectorOf(pseudoAngle(cos(heading + high), sin(heading + high))) + 1;
    if (last < first + 2)
    {
      last += kAzimuthBuckets; /* across the sector of heading 0 */
    }
    if (last - first + 1 >= kAzimuthBuckets)
    {
      first = 0;
      last = kAzimuthBuckets - 1;
    }
  }
  for (long b = first; b <= last; ++b)
  {
    int sector = (int)(((b % kAzimuthBuckets) + kAzimuthBuckets) % kAzimuthBuckets);
    candidates[(long)sector * stride + listed[sector]++] = index;
  }
}

/* The band's rays: every primitive and mesh whose bounding sphere the ray passes within (tMin, best so far). */
static void* raysBand(void* arg)
{
  Band* band = (Band*)arg;
  const Rays* s = (const Rays*)band->job;
  const double* origin = s->origin;
  long tests = 0;
  for (int r = band->rowBegin; r < band->rowEnd; ++r)
  {
    const double* d = s->directions + 3 * (long)r;
    double best = INFINITY;
    const int* candidates = NULL;
    int listed = s->count + s->meshCount;
    if (s->candidates != NULL)
    {
      int bucket = sectorOf(pseudoAngle(d[0], d[1]));
      candidates = s->candidates + (long)bucket * s->stride;
      listed = s->listed[bucket];
    }
    /* Primitives first, then meshes (in index order either way): the nearest hit does not depend on the order. */
    int c = 0;
    for (; c < listed; ++c)
    {
      int k = candidates != NULL ? candidates[c] : c;
      if (k >= s->count)
      {
        break;
      }
      const double* row = s->primitives + (long)k * kStride;
      int type = (int)row[0];
      const double* shape = row + kRotation; /* world from shape; a plane's normal */
      const double* params = row + kParams;
      if (type == kPlane)
      {
        ++tests;
        double facing = dot3(shape, d);
        if (facing < 0.0)
        {
          double t = (params[0] - dot3(shape, origin)) / facing;
          if (t > s->tMin && t < best)
          {
            best = t;
          }
        }
        continue;
      }
      double rel[3] = { row[kPosition] - origin[0], row[kPosition + 1] - origin[1], row[kPosition + 2] - origin[2] };
      double along = dot3(rel, d);
      double radius = row[kRadius];
      if (along + radius <= s->tMin || along - radius >= best || dot3(rel, rel) - along * along > radius * radius)
      {
        continue;
      }
      double start[3], local[3]; /* the ray in the shape's frame */
      for (int a = 0; a < 3; ++a)
      {
        start[a] = -(shape[a] * rel[0] + shape[3 + a] * rel[1] + shape[6 + a] * rel[2]);
        local[a] = shape[a] * d[0] + shape[3 + a] * d[1] + shape[6 + a] * d[2];
      }
      double n[3];
      double t = INFINITY;
      ++tests;
      switch (type)
      {
        case kBox:
          t = hitBox(start, local, params, s->tMin, n);
          break;
        case kSphere:
          t = hitSphere(start, local, params[0], s->tMin, n);
          break;
        case kCylinder:
          t = hitCylinder(start, local, params[0], params[1], s->tMin, n);
          break;
        case kCapsule:
          t = hitCapsule(start, local, params[0], params[1], s->tMin, n);
          break;
        default:
          break;
      }
      if (t < best)
      {
        best = t;
      }
    }
    for (; c < listed; ++c)
    {
      int m = (candidates != NULL ? candidates[c] : c) - s->count;
      const Mesh* mesh = &s->meshes[m];
      const double* position = mesh->pose;
      const double* shape = mesh->pose + 3;
      double rel[3] = { position[0] - origin[0], position[1] - origin[1], position[2] - origin[2] };
      double along = dot3(rel, d);
      double radius = s->meshRadii[m];
      if (along + radius <= s->tMin || along - radius >= best || dot3(rel, rel) - along * along > radius * radius)
      {
        continue;
      }
      double start[3], local[3];
      for (int a = 0; a < 3; ++a)
      {
        start[a] = -(shape[a] * rel[0] + shape[3 + a] * rel[1] + shape[6 + a] * rel[2]);
        local[a] = shape[a] * d[0] + shape[3 + a] * d[1] + shape[6 + a] * d[2];
      }
      best = meshHit(mesh, start, local, s->tMin, best, &tests);
    }
    s->distance[r] = best <= s->tMax ? best : INFINITY;
  }
  band->count = tests;
  return NULL;
}

/* A multi-beam lidar's rays: ``rayCount`` unit ``directions`` (world frame, 3 doubles each) from ``origin`` against
 * ``count`` primitives (rows as tso_render's; planes included) and ``meshCount`` meshes (``meshRadii``: each mesh's
 * bounding radius about its position). Fills ``distance`` with each ray's nearest hit at a distance in (tMin, tMax],
 * INFINITY where there is none, in up to ``threads`` bands of rays at once. Returns the number of ray tests made. */
long tso_rays(int rayCount, const double* origin, const double* directions, int count, const double* primitives,
              int meshCount, const Mesh* meshes, const double* meshRadii, double tMin, double tMax, double* distance,
              int threads)
{
  Rays job = {
    origin, directions, count, primitives, meshCount, meshes, meshRadii, tMin, tMax, distance, NULL, NULL, 0
  };
  int shapes = count + meshCount;
  int* candidates = NULL;
  int* listed = NULL;
  /* Sorting shapes into sectors pays once there are more rays than sectors (a 2D lidar's few hundred do without). */
  if (rayCount > kAzimuthBuckets && shapes > 0)
  {
    candidates = malloc(sizeof(int) * (size_t)kAzimuthBuckets * (size_t)shapes);
    listed = calloc(kAzimuthBuckets, sizeof(int));
  }
  if (candidates != NULL && listed != NULL)
  {
    for (int k = 0; k < shapes; ++k)
    {
      const double* row = k < count ? primitives + (long)k * kStride : NULL;
      const double* position = row != NULL ? row + kPosition : meshes[k - count].pose;
      double radius = row != NULL ? row[kRadius] : meshRadii[k - count];
      listShape(row, position, radius, origin, k, candidates, listed, shapes);
    }
    job.candidates = candidates;
    job.listed = listed;
    job.stride = shapes;
  }
  long tests = runBands(threads, rayCount, raysBand, &job);
  free(candidates);
  free(listed);
  return tests;
}
