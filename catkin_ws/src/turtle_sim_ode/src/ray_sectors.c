/* The multi-beam lidars' broad phase (see ray_kernel.h): the shapes a ray heading into each of kAzimuthBuckets
 * sectors of azimuth about the lidar may meet, so that a ray tests only those of its sector. */
#include "ray_kernel.h"

#include <math.h>
#include <stddef.h>

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

/* The sector of the heading (x, y). */
int headingSector(double x, double y)
{
  int sector = (int)(pseudoAngle(x, y) * (kAzimuthBuckets / 4.0));
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
void listShape(const double* row, const double* position, double radius, const double* origin, int index,
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
    first = headingSector(cos(heading + low), sin(heading + low)) - 1;
    last = headingSector(cos(heading + high), sin(heading + high)) + 1;
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
