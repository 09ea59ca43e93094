/* The pixels a shape's projection may cover (see ray_kernel.h): a camera tests a shape's rays only there. */
#include "ray_kernel.h"

#include <math.h>

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
int pixelBox(const double* centre, const double* axes, const double* half, double near, double far, double focal,
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

/* imageBox of a triangle's ``corners`` (optical frame). */
int trianglePixelBox(const double (*corners)[3], double near, double far, double focal, double cx, double cy, int width,
                     int height, int* box)
{
  return imageBox(corners, 3, kTriangleEdges, 3, near, far, focal, cx, cy, width, height, box);
}
