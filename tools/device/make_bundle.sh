#!/usr/bin/env bash
# Builds the static-engine scaling bundle for a machine with many cores (run here, on the project's
# machine): a portable Release build (-DCONTACT2D_NATIVE=OFF: x86-64 baseline; OpenBLAS picks its
# kernels for the CPU at run time) of contact2d-solver, the shared libraries it loads for a
# --static run on the built-in mesh (ldd; libgmsh is opened only for Gmsh meshes), glibc and its
# loader apart (lib-glibc/, used only when the host's glibc is older), the paper deck P1, and
# c2d_h5u (max |u| of an end state and its difference to another), packed into
# device/contact2d_static_bundle.tar.gz beside device/run_static_scaling.sh (a copy of this folder's);
# device/ is git-ignored. Usage, from the repository root: tools/device/make_bundle.sh
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$here"
bdir=build-portable
cmake -S . -B "$bdir" -DCMAKE_BUILD_TYPE=Release -DCONTACT2D_NATIVE=OFF -DBUILD_TESTING=OFF \
      -DCONTACT2D_PYTHON=/usr/bin/python3 > "$bdir.configure.log" 2>&1 || { tail -20 "$bdir.configure.log"; exit 1; }
grep -i "openblas" "$bdir.configure.log" | head -1
cmake --build "$bdir" -j2 --target contact2d contact2d-solver 2>&1 | tail -1
stage=device/stage/c2d
rm -rf device/stage
mkdir -p device
cp tools/device/run_static_scaling.sh tools/device/README.txt device/
mkdir -p "$stage/bin" "$stage/lib" "$stage/lib-glibc" "$stage/inputs"
cp "$bdir/bin/contact2d" "$bdir/bin/contact2d-solver" "$stage/bin/"
gcc -O2 -o "$stage/bin/c2d_h5u" tools/device/c2d_h5u.c -I/usr/include/hdf5/serial \
    -L/usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5 -lm
cp inputs/baillet_sassi_2002_p1.nml "$stage/inputs/"
git rev-parse HEAD > "$stage/COMMIT"
git status --short -- src CMakeLists.txt >> "$stage/COMMIT"
{ ldd "$stage/bin/contact2d-solver"; ldd "$stage/bin/c2d_h5u"; } | awk '/=>/ && $3 ~ /^\// {print $1, $3}' | sort -u |
while read -r name path; do
  case "$name" in
    libc.so.*|libm.so.*|libpthread.so.*|libdl.so.*|librt.so.*|libresolv.so.*|ld-linux*) cp -L "$path" "$stage/lib-glibc/$name" ;;
    *) cp -L "$path" "$stage/lib/$name" ;;
  esac
done
cp -L /lib64/ld-linux-x86-64.so.2 "$stage/lib-glibc/"
# the OpenBLAS the build linked (its OpenMP build), under the name the solver asks for
grep -q "openblas-openmp" <(ldd "$stage/bin/contact2d-solver") || echo "make_bundle: warning: the solver does not load OpenBLAS's OpenMP build" >&2
tar -C device/stage -cf - c2d | gzip -9 > device/contact2d_static_bundle.tar.gz
rm -rf device/stage
ls -l device/contact2d_static_bundle.tar.gz
