/* contact2d_sys.c -- the few POSIX services Fortran lacks (bound in contact2d_sys.f90).
 *
 * - file kinds and identities (stat/lstat: regular file, directory, device, FIFO; device+inode),
 *   with the system's reason (strerror) when a call fails;
 * - the output lock: flock() on a lock file beside the output, so two runs aimed at one output
 *   cannot both write it (docs/output.md, "Output safety");
 * - link() without replacing (no-clobber publish) and rename() (replace);
 * - SIGINT/SIGTERM: the handler only stores the signal number in a sig_atomic_t; the step loop
 *   polls it once per step (no I/O, no allocation);
 * - the reason of the last HDF5 failure, read from the HDF5 error stack (e.g. the errno text of
 *   a failed write: "No space left on device");
 * - a small text file written whole with every write, fsync and close checked (the XDMF
 *   sidecar: gfortran's formatted I/O was seen to report success on a full disk).
 *
 * Every function returns 0 on success or an errno value; message buffers are NUL-terminated.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>
#include <hdf5.h>

static volatile sig_atomic_t c2d_signal = 0;

static void c2d_handler(int sig) { c2d_signal = sig; }

/* Install the SIGINT/SIGTERM handler (stop at the end of the current step); ignore SIGXFSZ. */
int c2d_signals_install(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = c2d_handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  if (sigaction(SIGINT, &sa, NULL) != 0) return errno;
  if (sigaction(SIGTERM, &sa, NULL) != 0) return errno;
  /* a file-size limit (ulimit -f) makes the write fail with EFBIG, reported like a full disk,
   * instead of killing the process */
  signal(SIGXFSZ, SIG_IGN);
  return 0;
}

/* The signal number received (0: none). Async-signal-safe read, no side effects. */
int c2d_signal_pending(void) { return (int)c2d_signal; }

/* strerror(err) into buf. */
void c2d_strerror(int err, char *buf, int len) {
  if (len <= 0) return;
  snprintf(buf, (size_t)len, "%s", strerror(err));
}

/* What a path is.  kind: 0 missing, 1 regular file, 2 directory, 3 character/block device,
 * 4 FIFO, 5 socket, 6 other, 7 dangling symbolic link.  Follows links (stat) and tells a
 * dangling link apart (lstat).  dev/ino identify the file, size in bytes.  Returns 0 or the
 * errno of stat when it failed for another reason than ENOENT (e.g. ENAMETOOLONG, EACCES,
 * ENOTDIR). */
int c2d_path_info(const char *path, int *kind, long long *dev, long long *ino, long long *size) {
  struct stat st;
  *kind = 0;
  *dev = 0;
  *ino = 0;
  *size = 0;
  if (stat(path, &st) != 0) {
    int err = errno;
    if (err == ENOENT) {
      struct stat lst;
      if (lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode)) *kind = 7;
      return 0;
    }
    return err;
  }
  *dev = (long long)st.st_dev;
  *ino = (long long)st.st_ino;
  *size = (long long)st.st_size;
  if (S_ISREG(st.st_mode)) *kind = 1;
  else if (S_ISDIR(st.st_mode)) *kind = 2;
  else if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) *kind = 3;
  else if (S_ISFIFO(st.st_mode)) *kind = 4;
  else if (S_ISSOCK(st.st_mode)) *kind = 5;
  else *kind = 6;
  return 0;
}

/* Can a file be created in directory dir?  0, or the errno (ENOENT, ENOTDIR, EACCES, EROFS...). */
int c2d_dir_writable(const char *dir) {
  struct stat st;
  if (stat(dir, &st) != 0) return errno;
  if (!S_ISDIR(st.st_mode)) return ENOTDIR;
  if (access(dir, W_OK | X_OK) != 0) return errno;
  return 0;
}

/* Take an exclusive, non-blocking flock on lockpath (created if needed).  *fd is the open
 * descriptor to pass to c2d_unlock.  EWOULDBLOCK: another process holds it.  The lock file is
 * re-checked after locking (same inode as the path), so a lock file unlinked by its previous
 * holder between our open and our flock is not trusted. */
int c2d_lock(const char *lockpath, int *fd) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    int f = open(lockpath, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (f < 0) return errno;
    if (flock(f, LOCK_EX | LOCK_NB) != 0) {
      int err = errno;
      close(f);
      return err;
    }
    struct stat a, b;
    if (fstat(f, &a) == 0 && stat(lockpath, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino) {
      char pid[32];
      int n = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
      if (ftruncate(f, 0) == 0 && n > 0) {
        ssize_t w = write(f, pid, (size_t)n);
        (void)w;
      }
      *fd = f;
      return 0;
    }
    close(f); /* the file was replaced or removed meanwhile: try again */
  }
  return EAGAIN;
}

/* Remove the lock file, then release the lock. */
void c2d_unlock(const char *lockpath, int fd) {
  if (fd < 0) return;
  unlink(lockpath);
  flock(fd, LOCK_UN);
  close(fd);
}

/* Move from -> to.  replace = 0: fail with EEXIST if `to` exists (link + unlink, atomic);
 * replace = 1: rename(), atomically replacing `to`. */
int c2d_publish(const char *from, const char *to, int replace) {
  if (replace) {
    if (rename(from, to) != 0) return errno;
    return 0;
  }
  if (link(from, to) != 0) return errno;
  if (unlink(from) != 0) return errno;
  return 0;
}

/* End the process at once with the code, running no exit handlers: after a failed write the
 * HDF5 library's own exit handler would try to flush the broken file again (and was seen to
 * crash doing so); what was flushed before stays as it is on disk. */
void c2d_exit_now(int code) { _exit(code); }

/* Create (or truncate) `path` and write len bytes of buf to it; 0 or the errno of the first
 * failed write, fsync or close (a short write is retried; no byte is ever silently lost). */
int c2d_write_file(const char *path, const char *buf, long long len) {
  int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return errno;
  long long done = 0;
  while (done < len) {
    ssize_t n = write(fd, buf + done, (size_t)(len - done));
    if (n < 0) {
      if (errno == EINTR) continue;
      int err = errno;
      close(fd);
      return err;
    }
    done += n;
  }
  if (fsync(fd) != 0) {
    int err = errno;
    close(fd);
    return err;
  }
  if (close(fd) != 0) return errno;
  return 0;
}

/* Remove a file (0 or errno; ENOENT counts as success). */
int c2d_remove(const char *path) {
  if (unlink(path) != 0 && errno != ENOENT) return errno;
  return 0;
}

/* ---- the reason of the last HDF5 failure ----------------------------------------------- */

struct c2d_walk {
  char *buf;
  size_t len;
  int found;
};

static herr_t c2d_walk_cb(unsigned n, const H5E_error2_t *err, void *data) {
  struct c2d_walk *w = (struct c2d_walk *)data;
  (void)n;
  if (w->found || err == NULL || err->desc == NULL) return 0;
  /* a failed POSIX call reports "..., errno = 28, error message = 'No space left on device', ..." */
  const char *p = strstr(err->desc, "error message = '");
  if (p != NULL) {
    p += strlen("error message = '");
    const char *q = strchr(p, '\'');
    size_t k = q ? (size_t)(q - p) : strlen(p);
    if (k >= w->len) k = w->len - 1;
    memcpy(w->buf, p, k);
    w->buf[k] = '\0';
    w->found = 1;
  }
  return 0;
}

/* The system's reason in the current HDF5 error stack, if any ("" otherwise). */
void c2d_h5_reason(char *buf, int len) {
  struct c2d_walk w;
  if (len <= 0) return;
  buf[0] = '\0';
  w.buf = buf;
  w.len = (size_t)len;
  w.found = 0;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, c2d_walk_cb, &w);
}
