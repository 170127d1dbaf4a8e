/* Spread the team over the CPUs once (docs/performance.md "Threads that never
 * hurt"): on the project's VM a thread woken from sleep runs on the waker's CPU and stays there
 * while both threads are busy, so a team formed again after a stretch on one thread shared one
 * core. Each thread moves itself to a CPU of its own (the k-th CPU allowed to it), then allows
 * all of its CPUs again: a nudge, not a binding, so the scheduler can still move it away from
 * a busy core. */
#define _GNU_SOURCE
#include <dirent.h>
#include <fcntl.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

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

/* How busy the other processes keep the CPUs (docs/performance.md "Threads that never hurt"): the
 * seconds the CPUs allowed to this process have been idle since boot (/proc/stat: idle + iowait
 * of each allowed CPU, kept by the kernel to the tick, 1/CLK_TCK s), the CPU seconds of this
 * process (getrusage: all its threads, to the microsecond), a monotonic clock in seconds and
 * the number of allowed CPUs. Between two calls, other processes kept
 * ncpu*dwall - didle - down CPU-seconds busy. 0 on success; no allocation (a stack buffer). */
int contact2d_cpu_times(double *idle, double *own, double *wall, int *ncpu)
{
   char buf[16384];
   cpu_set_t allowed;
   struct rusage ru;
   struct timespec ts;
   unsigned long long v[5], ticks = 0;
   long hz = sysconf(_SC_CLK_TCK);
   ssize_t n, got = 0;
   char *p, *end;
   int fd, cpu, count = 0;
   if (hz <= 0 || sched_getaffinity(0, sizeof allowed, &allowed) != 0) return 1;
   fd = open("/proc/stat", O_RDONLY | O_CLOEXEC);
   if (fd < 0) return 1;
   while (got < (ssize_t)sizeof buf - 1 && (n = read(fd, buf + got, sizeof buf - 1 - got)) > 0) got += n;
   close(fd);
   buf[got] = '\0';
   /* lines "cpuN user nice system idle iowait ...": the first line (all CPUs) has no N */
   for (p = buf; p < buf + got; p = end + 1) {
      end = strchr(p, '\n');
      if (end == NULL || strncmp(p, "cpu", 3) != 0) break;
      if (p[3] >= '0' && p[3] <= '9') {
         cpu = (int)strtol(p + 3, &p, 10);
         if (sscanf(p, "%llu %llu %llu %llu %llu", &v[0], &v[1], &v[2], &v[3], &v[4]) != 5) return 1;
         if (cpu >= 0 && cpu < CPU_SETSIZE && CPU_ISSET(cpu, &allowed)) {
            ticks += v[3] + v[4];
            count++;
         }
      }
   }
   if (count == 0 || getrusage(RUSAGE_SELF, &ru) != 0 || clock_gettime(CLOCK_MONOTONIC, &ts) != 0) return 1;
   *idle = (double)ticks/(double)hz;
   *own = (double)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + 1e-6*(double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
   *wall = (double)ts.tv_sec + 1e-9*(double)ts.tv_nsec;
   *ncpu = count;
   return 0;
}

/* Runnable threads on the machine other than this process's, now: /proc/loadavg's fourth field
 * ("running/total") counts every runnable thread, this process's own (the caller, and OpenMP
 * workers still spinning after a parallel region) included; those are counted from
 * /proc/self/task/<tid>/stat (state R) and taken off. -1 when unknown. Called twice per run,
 * outside the step loop (opendir allocates). */
int contact2d_runnable_others(void)
{
   char buf[512], path[64];
   ssize_t got;
   int fd = open("/proc/loadavg", O_RDONLY | O_CLOEXEC), running, total, own = 0;
   double a, b, c;
   DIR *dir;
   struct dirent *e;
   char *p;
   if (fd < 0) return -1;
   got = read(fd, buf, sizeof buf - 1);
   close(fd);
   if (got <= 0) return -1;
   buf[got] = '\0';
   if (sscanf(buf, "%lf %lf %lf %d/%d", &a, &b, &c, &running, &total) != 5 || running < 1) return -1;
   dir = opendir("/proc/self/task");
   if (dir == NULL) return -1;
   while ((e = readdir(dir)) != NULL) {
      if (e->d_name[0] < '0' || e->d_name[0] > '9') continue;
      snprintf(path, sizeof path, "/proc/self/task/%.20s/stat", e->d_name);
      fd = open(path, O_RDONLY | O_CLOEXEC);
      if (fd < 0) continue;
      got = read(fd, buf, sizeof buf - 1);
      close(fd);
      if (got <= 0) continue;
      buf[got] = '\0';
      p = strrchr(buf, ')');           /* "tid (name) S ...": the state follows the name */
      if (p != NULL && p[1] == ' ' && p[2] == 'R') own++;
   }
   closedir(dir);
   if (own < 1) own = 1;
   return running > own ? running - own : 0;
}
