#!/bin/bash
# The GPU check (as `make gpu-check`) from a bundle made by tools/gpu_bundle.sh, on a node with an
# NVIDIA GPU, its driver and the CUDA toolkit's libraries, but not the build's dependencies. Run from
# the repository root. Within DEADLINE seconds: the unit tests on the device (each program on its
# own, in parallel), then bench_ib, bench_cells, bench_fluid and chapter4_cells at quick scale and
# chapter4_cells at full scale (the whole-blood step at the seed's sizes), each only if its time is
# left; reports in reports/gpu/<study> name the GPU. Logs: LOGDIR/unit.log (one line per program and
# every failed test), LOGDIR/unit_full.log, LOGDIR/run.log; with ARCHIVE, reports/gpu and the runs'
# results are also packed into it after each study.
#
#   tools/gpu_check_bundle.sh BUNDLE [DEADLINE=480] [LOGDIR=runs/gpu/logs] [ARCHIVE]
set -uo pipefail
bundle=${1:?usage: tools/gpu_check_bundle.sh BUNDLE [DEADLINE] [LOGDIR] [ARCHIVE]}
deadline=${2:-480}
logs=${3:-runs/gpu/logs}
archive=${4:-}
root=$PWD
py=""  # a Python with the harness's packages (matplotlib, yaml)
for p in python3 /usr/bin/python3; do
  "$p" -c "import matplotlib, yaml" 2>/dev/null && { py=$(command -v "$p"); break; }
done
mkdir -p "$logs"
exec > >(tee -a "$logs/run.log") 2>&1
left() { echo $((deadline - SECONDS)); }
nvidia-smi -L 2>/dev/null | grep -q GPU || { echo "gpu_check_bundle: no NVIDIA GPU here (nvidia-smi -L lists none)"; exit 2; }
[ -n "$py" ] || echo "gpu_check_bundle: no Python with matplotlib and yaml: the studies will not run"
echo "== $(date -u) on $(hostname)"
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,clocks.max.mem,memory.total --format=csv
echo "$(nproc) CPU threads: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"

here=$(mktemp -d /tmp/rbfib-gpu.XXXX)
tar -C "$here" -xJf "$bundle" || { echo "gpu_check_bundle: cannot unpack $bundle"; exit 2; }
# The test programs read the repository's data under the source path they were compiled with.
src=$(cat "$here/source_dir" 2>/dev/null || true)
if [ -n "$src" ] && [ "$src" != "$root" ] && [ ! -e "$src" ]; then
  mkdir -p "$(dirname "$src")" && ln -s "$root" "$src" && echo "source path $src -> $root"
fi
# The CUDA libraries: the toolkit's, else the CUDA wheels' of this node's Python.
cuda=""
for d in /usr/local/cuda/lib64 /usr/local/cuda/targets/x86_64-linux/lib /usr/local/cuda-*/lib64; do
  [ -e "$d/libcudart.so" ] || ls "$d"/libcublas.so.* >/dev/null 2>&1 && cuda="$cuda:$d"
done
if [ -z "$cuda" ]; then
  nv=$("$py" -c "import nvidia, os; print(os.path.dirname(list(nvidia.__path__)[0]))" 2>/dev/null)
  [ -n "$nv" ] && for d in $(find "$nv/nvidia" -name 'lib*.so.*' -printf '%h\n' 2>/dev/null | sort -u); do cuda="$cuda:$d"; done
fi
libs="$here/lib$cuda${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# Each program behind a wrapper that sets its library path, so that the harness's Python keeps its own.
for b in "$here"/build/tests/test_* "$here"/build/studies/study_*; do
  mv "$b" "$b.bin"
  printf '#!/bin/sh\nLD_LIBRARY_PATH="%s" exec "%s.bin" "$@"\n' "$libs" "$b" > "$b"
  chmod +x "$b"
  LD_LIBRARY_PATH="$libs" ldd "$b.bin" | grep "not found" | sed "s|^|$(basename "$b"): missing |"
done

echo "== unit tests on the device ($(date -u +%T), $(left) s left)"
mkdir -p "$here/unit"
pids=""
for t in "$here"/build/tests/test_*.bin; do
  n=$(basename "$t" .bin)
  (OMP_NUM_THREADS=2 OMP_WAIT_POLICY=PASSIVE timeout -k 5 $(( $(left) / 3 )) "${t%.bin}" --gtest_brief=1 > "$here/unit/$n.log" 2>&1
   echo "exit status $?" >> "$here/unit/$n.log") &
  pids="$pids $!"
done
wait $pids  # not a bare wait: the tee above is a child too
for f in "$here"/unit/*.log; do
  n=$(basename "$f" .log)
  echo "$n: $(grep -o '[0-9]* tests\? from [0-9]* test suites\? ran' "$f" | tail -1); $(grep -c '^\[  FAILED  \] [A-Za-z]' "$f") failed; $(tail -1 "$f")"
  grep '^\[  FAILED  \] [A-Za-z]' "$f" | sed 's/^/    /'
done | tee "$logs/unit.log"
cat "$here"/unit/*.log > "$logs/unit_full.log"

echo "== benchmarks ($(date -u +%T), $(left) s left)"
pack() { [ -n "$archive" ] && tar -czf "$archive" --exclude='*.h5' reports/gpu runs/gpu/*/ 2>/dev/null; true; }
study() {  # name scale seconds-it-needs
  if [ "$(left)" -lt "$3" ]; then echo "-- $1 ($2): skipped, $(left) s left"; return; fi
  echo "-- $1 ($2), $(date -u +%T)"
  OMP_NUM_THREADS=$(nproc) OMP_WAIT_POLICY=PASSIVE PYTHONUNBUFFERED=1 timeout -k 5 $(( $(left) - 10 )) \
    "$py" -m harness run "$1" --scale "$2" --build "$here/build" --reports reports/gpu --out runs/gpu
  echo "-- $1 ($2): exit status $?, $(date -u +%T)"
  pack
}
study chapter4_cells quick 60
study bench_fluid quick 40
study bench_ib quick 40
study bench_cells quick 25
study chapter4_cells full 150
echo "== end $(date -u +%T), $SECONDS s"
