/* A job split into bands of rows, each band run on a thread of its own (see ray_kernel.h). */
#include "ray_kernel.h"

#include <pthread.h>

enum
{
  kMaxThreads = 8,
  kMinRowsPerThread = 16 /* below this a thread costs more than it saves */
};

/* Runs ``work`` on ``job`` in up to ``threads`` bands of ``height`` rows: the calling thread takes the first, a new
 * thread each other band (a thread that cannot be started leaves its band to the calling thread). Returns the sum
 * of the bands' counts. */
long runBands(int threads, int height, void* (*work)(void*), const void* job)
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
