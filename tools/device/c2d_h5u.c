/* c2d_h5u RUN.h5 [REF.h5]: the largest displacement component of a contact2d run's end state,
 * max |u| over final/displacement, and with REF the difference max |u - u_ref| / max |u_ref|
 * ("bitwise" when every value is equal). Exit 1 with one line on stderr when a file or the
 * dataset cannot be read. For the device bundle's scaling script (no Python/h5py needed). */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static double *read_u(const char *path, hsize_t *n)
{
    hid_t f, d, s;
    hsize_t dims[2];
    double *u;
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) return NULL;
    d = H5Dopen2(f, "final/displacement", H5P_DEFAULT);
    if (d < 0) { H5Fclose(f); return NULL; }
    s = H5Dget_space(d);
    if (H5Sget_simple_extent_ndims(s) != 2) { H5Sclose(s); H5Dclose(d); H5Fclose(f); return NULL; }
    H5Sget_simple_extent_dims(s, dims, NULL);
    *n = dims[0] * dims[1];
    u = malloc(sizeof(double) * (*n ? *n : 1));
    if (!u || H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, u) < 0) { free(u); u = NULL; }
    H5Sclose(s); H5Dclose(d); H5Fclose(f);
    return u;
}

int main(int argc, char **argv)
{
    hsize_t n = 0, nr = 0, i;
    double *u, *r, umax = 0, rmax = 0, dmax = 0;
    int equal = 1;
    if (argc < 2 || argc > 3) { fprintf(stderr, "usage: c2d_h5u RUN.h5 [REF.h5]\n"); return 1; }
    u = read_u(argv[1], &n);
    if (!u) { fprintf(stderr, "c2d_h5u: cannot read final/displacement of %s\n", argv[1]); return 1; }
    for (i = 0; i < n; i++) umax = fmax(umax, fabs(u[i]));
    printf("%.6e", umax);
    if (argc == 3) {
        r = read_u(argv[2], &nr);
        if (!r || nr != n) { fprintf(stderr, "c2d_h5u: cannot compare with %s\n", argv[2]); return 1; }
        for (i = 0; i < n; i++) {
            rmax = fmax(rmax, fabs(r[i]));
            dmax = fmax(dmax, fabs(u[i] - r[i]));
            if (u[i] != r[i]) equal = 0;
        }
        if (equal) printf(" bitwise");
        else printf(" %.1e", dmax / rmax);
    }
    printf("\n");
    return 0;
}
