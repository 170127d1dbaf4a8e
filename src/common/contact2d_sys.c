/* contact2d_sys.c -- the few POSIX services Fortran lacks (bound in contact2d_sys.f90).
 *
 * - file kinds and identities (stat/lstat: regular file, directory, device, FIFO; device+inode),
 *   with the system's reason (strerror) when a call fails;
 * - the output lock: flock() on a lock file beside the output, so two runs aimed at one output
 *   cannot both write it (docs/output.md, "Output safety"). The lock file is created without
 *   following links (O_CREAT|O_EXCL|O_NOFOLLOW); an existing one is taken over only if it is a
 *   regular file with one link that holds what a lock holds (a process id or nothing: a stale
 *   lock of a killed run), never a symbolic link, another kind of file, or a file with content;
 * - the files this process created itself: every file created here exclusively (the sidecar's
 *   temporary file, the HDF5 file registered by c2d_h5_register) is remembered by device and
 *   inode, and only those are ever moved into place or removed (c2d_publish, c2d_remove_own):
 *   a run never removes or renames a file it did not create (an earlier run's kept partial
 *   file, a link planted under a temporary name);
 * - link() without replacing (no-clobber publish) and rename() (replace);
 * - SIGINT/SIGTERM: the handler only stores the signal number in a sig_atomic_t; the step loop
 *   polls it once per step (no I/O, no allocation);
 * - the reason of the last HDF5 failure, read from the HDF5 error stack (e.g. the errno text of
 *   a failed write: "No space left on device");
 * - a small text file created and written whole with every write, fsync and close checked (the
 *   XDMF sidecar: gfortran's formatted I/O was seen to report success on a full disk).
 *
 * Every function returns 0 on success or an errno value, or one of the C2D_E* codes below
 * (negative; c2d_strerror words them); message buffers are NUL-terminated.
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

/* Refusals that are no errno (negative, so they never collide with one). */
enum {
  C2D_ESYMLINK = -1, /* the path is a symbolic link (never followed) */
  C2D_ENOTREG = -2,  /* the path is not a regular file */
  C2D_ELINKS = -3,   /* the file has other hard links */
  C2D_ENOTLOCK = -4, /* the file holds something else than a lock's process id */
  C2D_ENOTOWN = -5   /* the file was not created by this process */
};

static volatile sig_atomic_t c2d_signal = 0;

/* ---- the files this process created ---------------------------------------------------- */

/* A run creates at most a lock, a sidecar lock, an HDF5 file and a sidecar; room for more. */
#define C2D_OWN_MAX 32
static struct {
  dev_t dev;
  ino_t ino;
} c2d_own[C2D_OWN_MAX];
static int c2d_nown = 0;

static void own_add(const struct stat *st) {
  if (c2d_nown < C2D_OWN_MAX) {
    c2d_own[c2d_nown].dev = st->st_dev;
    c2d_own[c2d_nown].ino = st->st_ino;
    ++c2d_nown;
  }
}

/* Is path itself (not following a link) a regular file this process created?  0 if so, else
 * ENOENT, C2D_ENOTOWN or the errno of lstat. */
static int own_check(const char *path) {
  struct stat st;
  if (lstat(path, &st) != 0) return errno;
  if (!S_ISREG(st.st_mode)) return C2D_ENOTOWN;
  for (int k = 0; k < c2d_nown; ++k)
    if (c2d_own[k].dev == st.st_dev && c2d_own[k].ino == st.st_ino) return 0;
  return C2D_ENOTOWN;
}

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

/* Record a signal as if it had arrived here: several processes agree on one that reached any of
   them (contact2d_explicit), so that each takes the same decision. */
void c2d_signal_raise(int sig) { c2d_signal = sig; }

/* strerror(err) into buf; the C2D_E* codes in words. */
void c2d_strerror(int err, char *buf, int len) {
  const char *text;
  if (len <= 0) return;
  switch (err) {
  case C2D_ESYMLINK: text = "is a symbolic link"; break;
  case C2D_ENOTREG: text = "is not a regular file"; break;
  case C2D_ELINKS: text = "has other hard links (it is another file's name too)"; break;
  case C2D_ENOTLOCK: text = "holds something else than a lock (a lock holds a process id)"; break;
  case C2D_ENOTOWN: text = "was not created by this run"; break;
  default: text = strerror(err);
  }
  snprintf(buf, (size_t)len, "%s", text);
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

/* May the existing file open on f be taken over as a lock?  A regular file with one link
 * holding at most a process id and a newline (what c2d_lock writes; empty: a run killed between
 * creating and writing it).  0 or a C2D_E* code. */
static int lock_content_ok(int f) {
  struct stat st;
  char buf[40];
  if (fstat(f, &st) != 0) return errno;
  if (!S_ISREG(st.st_mode)) return C2D_ENOTREG;
  if (st.st_nlink != 1) return C2D_ELINKS;
  if (st.st_size >= (off_t)sizeof buf) return C2D_ENOTLOCK;
  ssize_t n = pread(f, buf, sizeof buf, 0);
  if (n < 0) return errno;
  for (ssize_t k = 0; k < n; ++k) {
    if (buf[k] >= '0' && buf[k] <= '9') continue;
    if (buf[k] == '\n' && k == n - 1) continue;
    return C2D_ENOTLOCK;
  }
  return 0;
}

/* Can lockpath serve as a lock file?  0 if it is missing or a lock file (stale or held), else
 * C2D_ESYMLINK, C2D_ENOTREG, C2D_ELINKS, C2D_ENOTLOCK or an errno.  Opens nothing but a regular
 * file, read-only, without following links; writes nothing. */
int c2d_lock_check(const char *lockpath) {
  struct stat st;
  if (lstat(lockpath, &st) != 0) return errno == ENOENT ? 0 : errno;
  if (S_ISLNK(st.st_mode)) return C2D_ESYMLINK;
  if (!S_ISREG(st.st_mode)) return C2D_ENOTREG;
  int f = open(lockpath, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (f < 0) return errno == ELOOP ? C2D_ESYMLINK : (errno == ENOENT ? 0 : errno);
  int err = lock_content_ok(f);
  close(f);
  return err;
}

/* Take an exclusive, non-blocking flock on lockpath.  *fd is the open descriptor to pass to
 * c2d_unlock.  EWOULDBLOCK: another process holds it.  The file is created without following
 * links; an existing one (a stale lock) is used only if c2d_lock_check would accept it, so a
 * planted link or another file is never followed, truncated or removed.  The lock file is
 * re-checked after locking (same inode as the path), so a lock file unlinked by its previous
 * holder between our open and our flock is not trusted. */
int c2d_lock(const char *lockpath, int *fd) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    int created = 1;
    int f = open(lockpath, O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (f < 0) {
      if (errno != EEXIST) return errno;
      created = 0;
      struct stat st;
      if (lstat(lockpath, &st) != 0) {
        if (errno == ENOENT) continue; /* removed meanwhile: try again */
        return errno;
      }
      if (S_ISLNK(st.st_mode)) return C2D_ESYMLINK;
      if (!S_ISREG(st.st_mode)) return C2D_ENOTREG;
      f = open(lockpath, O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
      if (f < 0) {
        if (errno == ENOENT) continue;
        return errno == ELOOP ? C2D_ESYMLINK : errno;
      }
    }
    if (flock(f, LOCK_EX | LOCK_NB) != 0) {
      int err = errno;
      close(f);
      return err;
    }
    struct stat a, b;
    if (fstat(f, &a) == 0 && lstat(lockpath, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino) {
      if (!created) {
        /* checked under the lock: no other run writes it now */
        int err = lock_content_ok(f);
        if (err != 0) {
          flock(f, LOCK_UN);
          close(f);
          return err;
        }
      }
      char pid[32];
      int n = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
      if (ftruncate(f, 0) == 0 && n > 0) {
        ssize_t w = pwrite(f, pid, (size_t)n, 0);
        (void)w;
      }
      *fd = f;
      return 0;
    }
    close(f); /* the file was replaced or removed meanwhile: try again */
  }
  return EAGAIN;
}

/* Remove the lock file (only if the path still names the file locked on fd), then release the
 * lock. */
void c2d_unlock(const char *lockpath, int fd) {
  struct stat a, b;
  if (fd < 0) return;
  if (fstat(fd, &a) == 0 && lstat(lockpath, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino)
    unlink(lockpath);
  flock(fd, LOCK_UN);
  close(fd);
}

/* Move from -> to.  replace = 0: fail with EEXIST if `to` exists (link + unlink, atomic);
 * replace = 1: rename(), atomically replacing `to`.  `from` must be a file this process created
 * (else C2D_ENOTOWN: nothing is moved). */
int c2d_publish(const char *from, const char *to, int replace) {
  int own = own_check(from);
  if (own != 0) return own;
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

/* Create `path` (it must not exist: O_EXCL, and a link there is never followed) and write len
 * bytes of buf to it; 0 or the errno of the create or of the first failed write, fsync or close
 * (a short write is retried; no byte is ever silently lost).  The file is remembered as this
 * process's own (c2d_remove_own may remove it after a failed write). */
int c2d_write_file(const char *path, const char *buf, long long len) {
  int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) return errno;
  struct stat st;
  if (fstat(fd, &st) == 0) own_add(&st);
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

/* Remove a regular file (0 or errno; ENOENT counts as success; a symbolic link or another kind
 * of file is left alone: C2D_ESYMLINK, C2D_ENOTREG).  Only for the one file a user's --force
 * gives up (the old sidecar of the replaced result, docs/output.md); a temporary file goes with
 * c2d_remove_own. */
int c2d_remove(const char *path) {
  struct stat st;
  if (lstat(path, &st) != 0) return errno == ENOENT ? 0 : errno;
  if (S_ISLNK(st.st_mode)) return C2D_ESYMLINK; /* the user's link: left alone */
  if (!S_ISREG(st.st_mode)) return C2D_ENOTREG;
  if (unlink(path) != 0 && errno != ENOENT) return errno;
  return 0;
}

/* Remove path if it is a file this process created (0; ENOENT counts as success), else leave
 * it as it is (C2D_ENOTOWN or the errno of lstat/unlink). */
int c2d_remove_own(const char *path) {
  int own = own_check(path);
  if (own == ENOENT) return 0;
  if (own != 0) return own;
  if (unlink(path) != 0 && errno != ENOENT) return errno;
  return 0;
}

/* Remember the HDF5 file just created (exclusively) on `file` as this process's own: its device
 * and inode from HDF5's own descriptor (the POSIX driver's handle is an int file descriptor;
 * another driver, chosen by HDF5_DRIVER, is asked for the name, lstat at once). */
int c2d_h5_register(hid_t file) {
  struct stat st;
  hid_t fapl = H5Fget_access_plist(file);
  if (fapl < 0) return EINVAL;
  hid_t driver = H5Pget_driver(fapl);
  H5Pclose(fapl);
  if (driver == H5FD_SEC2) {
    void *handle = NULL;
    if (H5Fget_vfd_handle(file, H5P_DEFAULT, &handle) < 0 || handle == NULL) return EINVAL;
    if (fstat(*(int *)handle, &st) != 0) return errno;
  } else {
    char name[PATH_MAX];
    if (H5Fget_name(file, name, sizeof name) < 0) return EINVAL;
    if (lstat(name, &st) != 0) return errno;
  }
  own_add(&st);
  return 0;
}

void c2d_h5_reason(char *buf, int len);

/* After an exclusive HDF5 create of `path` failed: claim the file at path as this process's own
 * unless the create failed because the name existed (EEXIST in the HDF5 error stack: then the file
 * is someone else's).  HDF5 opens with O_CREAT|O_EXCL and may fail after that open (a full disk:
 * an empty file is left), and the name was free when chosen under the output lock, so a file
 * there now is the one that open created.  0 if claimed, ENOENT if there is none, EEXIST. */
int c2d_h5_claim_failed(const char *path) {
  char reason[256];
  struct stat st;
  c2d_h5_reason(reason, (int)sizeof reason);
  if (strcmp(reason, strerror(EEXIST)) == 0) return EEXIST;
  if (lstat(path, &st) != 0) return errno;
  if (!S_ISREG(st.st_mode)) return C2D_ENOTREG;
  own_add(&st);
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
