/* Counts heap allocations of the test process: the executable's malloc/calloc/realloc
 * interpose glibc's (they forward to __libc_*), so every allocation made by Fortran code,
 * libgfortran or LAPACK is seen. Used by test_step_no_alloc.pf to keep the step loop free of
 * heap allocation (STYLE.md). glibc only. */
#include <stddef.h>
extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
extern void __libc_free(void *);

static volatile long c2d_calls = 0;

void *malloc(size_t n) { ++c2d_calls; return __libc_malloc(n); }
void *calloc(size_t a, size_t b) { ++c2d_calls; return __libc_calloc(a, b); }
void *realloc(void *p, size_t n) { ++c2d_calls; return __libc_realloc(p, n); }
void free(void *p) { __libc_free(p); }

/* Allocations so far. */
long c2d_malloc_calls(void) { return c2d_calls; }
