/* A depth camera's depth image and point cloud from a camera's picture (see ray_kernel.h). */
#include "ray_kernel.h"

#include <math.h>
#include <string.h>

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
