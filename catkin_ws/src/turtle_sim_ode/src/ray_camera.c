/* A camera's picture (see ray_kernel.h): one ray per pixel from the optical centre, each shape tested only in the
 * pixels its projection may cover. The rays are (u, v, 1), so that a ray's parameter is the depth (numpy's
 * raycast: unit rays, the near clip turned into a distance per ray); both clip at the near plane, as OpenGL does. */
#include "ray_kernel.h"

#include <math.h>
#include <string.h>

static uint8_t channel(double value)
{
  return (uint8_t)(value <= 0.0 ? 0.0 : value >= 1.0 ? 255.0 : value * 255.0 + 0.5);
}

/* What tso_render draws and where it writes: see tso_render. */
typedef struct
{
  int width, height;
  const double* origin;
  const double* rotation;
  Shapes shapes;
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

/* A shape at ``position`` (``shape``: world from shape, row-major) as the camera sees it: ``centre`` its position in
 * the optical frame, ``local`` shape from optical (shape^T rotation, row-major), ``start`` the camera in its frame. */
static void shapeFromOptical(const Scene* s, const double* position, const double* shape, double* centre, double* local,
                             double* start)
{
  const double* origin = s->origin;
  const double* rotation = s->rotation;
  double rel[3] = { position[0] - origin[0], position[1] - origin[1], position[2] - origin[2] };
  for (int a = 0; a < 3; ++a)
  {
    centre[a] = rotation[a] * rel[0] + rotation[3 + a] * rel[1] + rotation[6 + a] * rel[2];
    for (int b = 0; b < 3; ++b)
    {
      local[3 * a + b] = shape[a] * rotation[b] + shape[3 + a] * rotation[3 + b] + shape[6 + a] * rotation[6 + b];
    }
    start[a] = -(shape[a] * rel[0] + shape[3 + a] * rel[1] + shape[6 + a] * rel[2]);
  }
}

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

/* A mesh's triangles in rows [rowBegin, rowEnd), each in the pixels its projection may cover, seen from both sides
 * (a mesh need not be closed, nor its faces wound one way) with one shade a triangle. Returns the ray tests made. */
static long meshRows(const Scene* s, const Mesh* mesh, int rowBegin, int rowEnd, double* restrict distance,
                     uint8_t* restrict rgb)
{
  const double* shape = mesh->pose + 3; /* world from mesh */
  const double* colour = mesh->pose + 12;
  const double invFocal = 1.0 / s->focal;
  double centre[3], local[9], start[3];
  shapeFromOptical(s, mesh->pose, shape, centre, local, start);
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
    if (!trianglePixelBox((const double(*)[3])corners, s->tMin, s->far, s->focal, s->cx, s->cy, s->width, s->height,
                          box))
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

/* A primitive row's shape in rows [rowBegin, rowEnd): a plane everywhere, any other shape in the pixels its bounding
 * box may cover. Returns the ray tests made. */
static long primitiveRows(const Scene* s, const double* row, int rowBegin, int rowEnd, double* restrict distance,
                          uint8_t* restrict rgb)
{
  int type = (int)row[0];
  const double* shape = row + kRotation; /* world from shape; a plane's normal */
  const double* params = row + kParams;
  const double* colour = row + kColour;
  if (type == kPlane)
  {
    return planeRows(s, rowBegin, rowEnd, shape, params[0] - dot3(shape, s->origin), colour, distance, rgb);
  }
  const int width = s->width;
  const double invFocal = 1.0 / s->focal;
  const double tMin = s->tMin;
  double centre[3], local[9], start[3];
  shapeFromOptical(s, row + kPosition, shape, centre, local, start);
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
  if (!pixelBox(centre, local, half, tMin, s->far, s->focal, s->cx, s->cy, width, s->height, box))
  {
    return 0;
  }
  int j0 = box[2] > rowBegin ? box[2] : rowBegin;
  int j1 = box[3] < rowEnd ? box[3] : rowEnd;
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
  long tests = 0;
  for (int j = j0; j < j1; ++j)
  {
    double v = (j - s->cy) * invFocal;
    double rowBase[3];
    for (int a = 0; a < 3; ++a)
    {
      rowBase[a] = local[3 * a + 1] * v + local[3 * a + 2];
    }
    for (int i = box[0]; i < box[1]; ++i)
    {
      int p = j * width + i;
      double u = (i - s->cx) * invFocal;
      double d[3]; /* the pixel's ray (u, v, 1) in the optical frame, in the shape's frame: t is its depth */
      for (int a = 0; a < 3; ++a)
      {
        d[a] = local[3 * a] * u + rowBase[a];
      }
      double n[3];
      ++tests;
      double t = hitPrimitive(type, start, d, params, tMin, n);
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
  return tests;
}

/* The band's rows of the picture: every mesh and primitive, then the sky where nothing was hit within far. */
static void* renderBand(void* arg)
{
  Band* band = (Band*)arg;
  const Scene* s = (const Scene*)band->job;
  const Shapes* shapes = &s->shapes;
  const int width = s->width;
  /* Local copies: stores through the uint8_t pointer could alias anything the struct points to. */
  double* restrict distance = s->distance;
  uint8_t* restrict rgb = s->rgb;
  long tests = 0;
  for (int p = band->rowBegin * width; p < band->rowEnd * width; ++p)
  {
    distance[p] = INFINITY;
  }
  for (int m = 0; m < shapes->meshCount; ++m)
  {
    tests += meshRows(s, &shapes->meshes[m], band->rowBegin, band->rowEnd, distance, rgb);
  }
  for (int k = 0; k < shapes->count; ++k)
  {
    tests += primitiveRows(s, shapes->primitives + (long)k * kStride, band->rowBegin, band->rowEnd, distance, rgb);
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
  Shapes shapes = { count, primitives, meshCount, meshes };
  Scene scene = { width, height, origin, rotation, shapes, tMin,     far,   focal,
                  cx,    cy,     light,  ambient,  sky,    distance, depth, rgb };
  return runBands(threads, height, renderBand, &scene);
}
