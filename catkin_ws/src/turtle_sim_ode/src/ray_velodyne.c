/* A Velodyne's cloud from its scan, as GazeboRosVelodyneLaser::OnScan builds it (see ray_kernel.h and
 * turtle_sim_ode.sensors.plugins.velodyne, whose numpy path it repeats number for number). */
#include "ray_kernel.h"

#include <string.h>

enum
{
  kPointStep = 22 /* x, y, z, intensity float32 at 0, 4, 8, 12; ring uint16 at 16; time float32 at 18 */
};

static void writePoint(uint8_t* point, float x, float y, float z, float intensity, uint16_t ring)
{
  const float time = 0.0f;
  memcpy(point, &x, 4);
  memcpy(point + 4, &y, 4);
  memcpy(point + 8, &z, 4);
  memcpy(point + 12, &intensity, 4);
  memcpy(point + 16, &ring, 2);
  memcpy(point + 18, &time, 4);
}

/* The points of a scan of ``azimuths`` x ``rings`` rays, azimuth by azimuth and ring by ring within each, into
 * ``points`` (room for every ray); returns how many were written. ``ranges``: (rings, azimuths) row-major, as
 * measured; ``normals``: (azimuths, rings) standard normals, times ``sigma`` the noise (NULL: none); ``directions``:
 * (azimuths, rings, 3) unit rays in the sensor frame. A ray is in band where low < range < high. Not ``organised``: a
 * point where both the noisy and the measured range are in band (none unless ``intensityKept``); organised: every ray,
 * NaN out of band. */
long tso_velodyne_cloud(int azimuths, int rings, const double* ranges, const double* normals, double sigma, double low,
                        double high, int organised, int intensityKept, const double* directions, uint8_t* points)
{
  long written = 0;
  for (int i = 0; i < azimuths; ++i)
  {
    for (int j = 0; j < rings; ++j)
    {
      long ray = (long)i * rings + j;
      double measured = ranges[(long)j * azimuths + i];
      /* Rounded as numpy rounds noise = normal * sigma, then measured + noise (no fused multiply-add). */
      double noise = normals != NULL ? normals[ray] * sigma : 0.0;
      double noisy = normals != NULL ? measured + noise : measured;
      int inBand = noisy > low && noisy < high;
      const double* d = directions + 3 * ray;
      if (organised)
      {
        float x = inBand ? (float)(noisy * d[0]) : NAN;
        float y = inBand ? (float)(noisy * d[1]) : NAN;
        float z = inBand ? (float)(noisy * d[2]) : NAN;
        writePoint(points + kPointStep * written++, x, y, z, inBand ? 0.0f : NAN, (uint16_t)j);
      }
      else if (inBand && measured > low && measured < high && intensityKept)
      {
        writePoint(points + kPointStep * written++, (float)(noisy * d[0]), (float)(noisy * d[1]), (float)(noisy * d[2]),
                   0.0f, (uint16_t)j);
      }
    }
  }
  return written;
}
