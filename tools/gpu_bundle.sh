#!/bin/bash
# Packs a CUDA build for a GPU node that lacks the build's dependencies (a cluster's compute node,
# a container with only the CUDA runtime): the unit tests, the GPU check's study drivers, and the
# shared libraries they load that are neither glibc's nor the CUDA toolkit's (HDF5, yaml-cpp and
# theirs), in one xz tarball. tools/gpu_check_bundle.sh runs it there.
#
#   tools/gpu_bundle.sh [BUILD_CUDA] [OUT]      (defaults: build-cuda, build-cuda/rbfib-gpu-bundle.tar.xz)
set -euo pipefail
build=${1:-build-cuda}
out=${2:-$build/rbfib-gpu-bundle.tar.xz}
studies="bench_ib bench_cells bench_fluid chapter4_cells"
[ -f "$build/CMakeCache.txt" ] && grep -q "^RBFIB_BACKEND:STRING=CUDA" "$build/CMakeCache.txt" \
  || { echo "gpu_bundle: $build is not a CUDA build (make build-cuda)" >&2; exit 2; }
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/build/tests" "$stage/build/studies" "$stage/lib"
bins=()
for t in "$build"/tests/test_*; do
  [ -f "$t" ] && [ -x "$t" ] || continue
  strip -o "$stage/build/tests/$(basename "$t")" "$t"; bins+=("$t")
done
for s in $studies; do
  exe="$build/studies/study_$s"
  [ -x "$exe" ] || { echo "gpu_bundle: $exe not built (make build-cuda)" >&2; exit 2; }
  strip -o "$stage/build/studies/study_$s" "$exe"; bins+=("$exe")
done
# Libraries: all that ldd resolves, but glibc's own and the CUDA toolkit's (the node's driver and
# toolkit provide those; they must match the node's driver).
for b in "${bins[@]}"; do ldd "$b"; done | awk '$2 == "=>" && $3 ~ /^\// {print $3}' | sort -u \
  | grep -v -E '/(libc|libm|libdl|libpthread|librt|libresolv|libutil)\.so|/ld-linux|cuda|/libcu[a-z]*\.so|/libnv[A-Za-z]*\.so' \
  | while read -r l; do cp -L "$l" "$stage/lib/"; done
# The source path the test programs were compiled with (they read the repository's data there).
sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt" > "$stage/source_dir"
echo "gpu_bundle: $(ls "$stage/build/tests" | wc -l) test programs, $(ls "$stage/build/studies" | wc -l) drivers, $(ls "$stage/lib" | wc -l) libraries"
tar -C "$stage" -cf - build lib source_dir | xz -9 -T0 > "$out"
echo "gpu_bundle: $out ($(du -h "$out" | cut -f1))"
