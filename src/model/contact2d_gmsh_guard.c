/* contact2d_gmsh_guard.c -- the Gmsh library's ways of ending the process, turned into one line
 * (bound in contact2d_gmsh.f90; docs/geometry.md "What a Gmsh file may do").
 *
 * While a guard is armed (c2d_gmsh_guard_begin .. c2d_gmsh_guard_end):
 * - stderr (fd 2) goes to /dev/null: Gmsh's own messages and libstdc++'s report of an uncaught
 *   exception ("terminate called after throwing an instance of 'std::bad_alloc'") stay off the
 *   terminal; the program's one line is written to the saved descriptor instead;
 * - SIGSEGV, SIGBUS, SIGABRT (an uncaught C++ exception: std::terminate calls abort), SIGFPE and
 *   SIGILL write the armed line, naming the signal, and end the process with _exit(1) (on an
 *   alternate stack, so that a stack overflow is caught too);
 * - exit() called by Gmsh (a .geo's `Exit;` statement ends the program through Msg::Exit) runs
 *   the atexit handler below, which writes its own line and ends the process with _exit(1)
 *   instead of the status 0 Gmsh asked for.
 * Nothing has been written by then: the mesh is read before any output file is created.
 * After a Gmsh failure the caller arms the guard with its refusal line before gmshFinalize, which
 * was seen to crash after a failed allocation: the line then still says why.
 * Only async-signal-safe calls (write, _exit) run in the handlers.
 */
#define _GNU_SOURCE
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char guard_line[2048];
static size_t guard_len = 0;
static char exit_line[2048];
static size_t exit_len = 0;
static int saved_fd = -1;
static volatile sig_atomic_t armed = 0;
static int atexit_done = 0;
static const int guarded[] = {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL};
#define NGUARDED (sizeof guarded / sizeof guarded[0])
static struct sigaction previous[NGUARDED];
static int installed = 0;
static char altstack[65536];

static void put(const char *s, size_t n) {
  int fd = saved_fd >= 0 ? saved_fd : 2;
  while (n > 0) {
    ssize_t w = write(fd, s, n);
    if (w <= 0) return;
    s += w;
    n -= (size_t)w;
  }
}

static const char *signal_name(int sig) {
  switch (sig) {
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS: return "SIGBUS";
    case SIGABRT: return "SIGABRT, an uncaught C++ exception such as std::bad_alloc";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    default: return "a signal";
  }
}

static void crash_handler(int sig) {
  const char *name = signal_name(sig);
  put(guard_line, guard_len);
  put(" (", 2);
  put(name, strlen(name));
  put(")\n", 2);
  _exit(1);
}

static void exit_handler(void) {
  if (!armed) return;
  put(exit_line, exit_len);
  put("\n", 1);
  _exit(1);
}

static void copy_line(char *dst, size_t *n, const char *src, int len) {
  size_t m = len < 0 ? 0 : (size_t)len;
  if (m > 2047) m = 2047;
  memcpy(dst, src, m);
  dst[m] = '\0';
  *n = m;
}

/* The lines the handlers write: crash_line (followed by " (SIGNAME)"), exit_line (Gmsh called
 * exit()). May be called again while armed to name the current stage. */
void c2d_gmsh_guard_lines(const char *crash, int crash_n, const char *ex, int ex_n) {
  copy_line(guard_line, &guard_len, crash, crash_n);
  copy_line(exit_line, &exit_len, ex, ex_n);
}

/* Arm: stderr to /dev/null, crash handlers, the exit() handler. A failing system call leaves the
 * process less guarded but working: Gmsh then reports as it would without the guard. */
void c2d_gmsh_guard_begin(void) {
  if (!atexit_done) {
    if (atexit(exit_handler) == 0) atexit_done = 1;
  }
  if (!installed) {
    stack_t ss;
    struct sigaction sa;
    size_t i;
    ss.ss_sp = altstack;
    ss.ss_size = sizeof altstack;
    ss.ss_flags = 0;
    sigaltstack(&ss, NULL);
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = crash_handler;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_ONSTACK | SA_RESETHAND;
    for (i = 0; i < NGUARDED; i++) sigaction(guarded[i], &sa, &previous[i]);
    installed = 1;
  }
  fflush(NULL);
  if (saved_fd < 0) {
    int null = open("/dev/null", O_WRONLY | O_CLOEXEC);
    saved_fd = fcntl(2, F_DUPFD_CLOEXEC, 3);
    if (null >= 0 && saved_fd >= 0) dup2(null, 2);
    if (null >= 0) close(null);
  }
  armed = 1;
}

/* Disarm: stderr back, the previous signal handlers back. */
void c2d_gmsh_guard_end(void) {
  size_t i;
  armed = 0;
  if (saved_fd >= 0) {
    dup2(saved_fd, 2);
    close(saved_fd);
    saved_fd = -1;
  }
  if (installed) {
    for (i = 0; i < NGUARDED; i++) sigaction(guarded[i], &previous[i], NULL);
    installed = 0;
  }
}
