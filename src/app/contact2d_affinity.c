/* Spread the team over the CPUs once (issue 13, docs/performance.md "Where a two-thread step
 * goes"): on the project's VM a thread woken from sleep runs on the waker's CPU and stays there
 * while both threads are busy, so a team formed again after a stretch on one thread shared one
 * core. Each thread moves itself to a CPU of its own (the k-th CPU allowed to it), then allows
 * all of its CPUs again: a nudge, not a binding, so the scheduler can still move it away from
 * a busy core. */
#define _GNU_SOURCE
#include <sched.h>

int contact2d_affinity_nudge(int k)
{
   cpu_set_t all, one;
   int c, seen = -1, n;
   if (sched_getaffinity(0, sizeof all, &all) != 0) return 1;
   n = CPU_COUNT(&all);
   if (n < 2) return 1;
   k %= n;
   for (c = 0; c < CPU_SETSIZE; c++) {
      if (CPU_ISSET(c, &all) && ++seen == k) break;
   }
   if (c >= CPU_SETSIZE) return 1;
   CPU_ZERO(&one);
   CPU_SET(c, &one);
   if (sched_setaffinity(0, sizeof one, &one) != 0) return 1;   /* moves the thread now */
   return sched_setaffinity(0, sizeof all, &all) != 0;
}
