#!/bin/sh
# The rbfib command on several processes against one (apps/rbfib): a short run of a shortened
# scenes/two_red_cells.yaml (two red cells, one in each process's slab; no snapshots) on 1 and on 2
# processes gives the same diagnostics table (every column but the timings, as printed, 6
# significant digits); each run's checkpoint continued on the other number of processes (2 -> 1,
# 1 -> 2) gives the table of an uninterrupted run. (Three processes would own fewer planes than
# the 15 of halo a red cell needs at h = 0.5 um: refused, named.) Snapshots on 2 processes, also
# across a restart on 2, are the series one process writes: the same run.xmf, the same files, every
# dataset within 1e-10 of its largest value and the same t and step (measured: positions 3e-16,
# fluid 1e-12, the force density 2.2e-11, a small difference of large terms near the rest shape). A scene with walls across z
# is refused on 2 processes with exit status 2 and one line naming the field. The shortened
# scenes/platelets_near_wall.yaml (an endothelium of tethered points) gives the same table on 1 and
# 2 processes, and so does the same scene with its endothelium's plane held by a solve (a held wall).
#
# usage: on_ranks.sh RBFIB MPIEXEC SCENE WORKDIR (SCENE: scenes/two_red_cells.yaml, beside the others)
set -eu
rbfib=$1 mpiexec=$2 scene=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
sed '/snapshot_every/d; s/diagnostics_every: 10/diagnostics_every: 2/' "$scene" > s.yaml
columns() { cut -d, -f1-8,13- "$1/diagnostics.csv"; }  # not the seconds of the phases (9-12)
same() {
  if ! diff "$1" "$2" > diff.txt; then echo "FAIL: $3"; head -5 diff.txt; exit 1; fi
}
"$rbfib" run s.yaml --out one --until '1 us' > one.log
"$mpiexec" -n 2 "$rbfib" run s.yaml --out two --until '1 us' > two.log
columns one > one.csv; columns two > two.csv
[ "$(wc -l < one.csv)" -eq 6 ] || { echo "FAIL: expected 5 rows of diagnostics"; cat one.csv; exit 1; }
same one.csv two.csv "2 processes differ from one"
cp -r one uninterrupted && "$rbfib" restart uninterrupted --until '2 us' > u.log
"$rbfib" restart two --until '2 us' > r1.log
"$mpiexec" -n 2 "$rbfib" restart one --until '2 us' > r3.log
columns uninterrupted > u.csv; columns two > r1.csv; columns one > r3.csv
[ "$(wc -l < u.csv)" -eq 11 ] || { echo "FAIL: expected 10 rows after the restart"; exit 1; }
same u.csv r1.csv "a 2-process checkpoint continued on 1 process"
same u.csv r3.csv "a 1-process checkpoint continued on 2 processes"
# Snapshots: one series whatever the number of processes.
sed 's/^  snapshot_every: .*/  snapshot_every: 0.5 us/' "$scene" > snap.yaml
"$rbfib" run snap.yaml --out snap_one --until '2 us' > snap_one.log
"$mpiexec" -n 2 "$rbfib" run snap.yaml --out snap_two --until '1 us' > snap_two.log
"$mpiexec" -n 2 "$rbfib" restart snap_two --until '2 us' > snap_two_restart.log
same snap_one/run.xmf snap_two/run.xmf "the XDMF series of 2 processes differs from one process's"
/usr/bin/python3 - snap_one snap_two <<'PY' || { echo "FAIL: the snapshots of 2 processes differ from one process's"; exit 1; }
import glob, os, sys
import h5py, numpy as np
one, two = sys.argv[1:3]
names = lambda d: sorted(os.path.basename(f) for f in glob.glob(d + "/snapshots/*.h5"))
files = names(one)
assert files == names(two), f"files {files} against {names(two)}"
assert len(files) == 5, f"expected 5 snapshots (0 to 2 us every 0.5 us), found {len(files)}"
worst = 0.0
for f in files:
    with h5py.File(f"{one}/snapshots/{f}", "r") as a, h5py.File(f"{two}/snapshots/{f}", "r") as b:
        for key in ("t", "step"):
            assert a.attrs[key] == b.attrs[key], f"{f}: attribute {key} {a.attrs[key]} against {b.attrs[key]}"
        sets = []
        a.visit(lambda n: sets.append(n) if isinstance(a[n], h5py.Dataset) else None)
        assert len(sets) >= 7, f"{f}: only {sets}"
        for n in sets:
            x, y = np.asarray(a[n][()], float), np.asarray(b[n][()], float)
            assert x.shape == y.shape, f"{f}:{n} shape {x.shape} against {y.shape}"
            worst = max(worst, float(np.abs(x - y).max() / max(np.abs(x).max(), 1e-300)))
print(f"snapshots: largest difference {worst:.2e} of a dataset's largest value")
sys.exit(0 if worst <= 1e-10 else 1)
PY
# Tethered points (an endothelium of 16,000 points, split by anchor) with two platelets.
sed '/snapshot_every/d; s/diagnostics_every: 20/diagnostics_every: 2/' "$(dirname "$scene")/platelets_near_wall.yaml" > tethers.yaml
"$rbfib" run tethers.yaml --out tethers_one --until '0.25 us' > tethers_one.log
"$mpiexec" -n 2 "$rbfib" run tethers.yaml --out tethers_two --until '0.25 us' > tethers_two.log
columns tethers_one > t1.csv; columns tethers_two > t2.csv
[ "$(wc -l < t1.csv)" -eq 6 ] || { echo "FAIL: expected 5 rows of diagnostics with tethered points"; cat t1.csv; exit 1; }
same t1.csv t2.csv "tethered points on 2 processes differ from one"
# A held wall (the endothelium's plane held by a solve, 20 x 20 markers 2h apart) with the two platelets.
sed -e '/snapshot_every/d' -e 's/diagnostics_every: 20/diagnostics_every: 2/' -e '/^tethered_points:/,/^    eta:/d' \
    -e 's/^output:/held_walls:\n  - {name: endothelium, plane: {y: 1 um, points: [20, 20]}}\noutput:/' \
    "$(dirname "$scene")/platelets_near_wall.yaml" > held.yaml
grep -q '^held_walls:' held.yaml && ! grep -q '^tethered_points:' held.yaml || { echo "FAIL: the held-wall scene was not made"; exit 1; }
"$rbfib" run held.yaml --out held_one --until '0.25 us' > held_one.log
"$mpiexec" -n 2 "$rbfib" run held.yaml --out held_two --until '0.25 us' > held_two.log
columns held_one > h1.csv; columns held_two > h2.csv
[ "$(wc -l < h1.csv)" -eq 6 ] || { echo "FAIL: expected 5 rows of diagnostics with a held wall"; cat h1.csv; exit 1; }
same h1.csv h2.csv "a held wall on 2 processes differs from one"
# Walls across z: the multigrid path, one process only.
sed 's/periodic: \[x, z\]/periodic: [x, y]/; s/^    y: {lower/    z: {lower/' s.yaml > walls_z.yaml
status=0
"$mpiexec" -n 2 "$rbfib" run walls_z.yaml --out walls_z > walls_z.out 2> walls_z.err || status=$?
[ "$status" -eq 2 ] || { echo "FAIL: walls across z on 2 processes: exit status $status, expected 2"; exit 1; }
[ "$(grep -c '^rbfib: grid.boundary' walls_z.err)" -eq 1 ] || { echo "FAIL: expected one line naming grid.boundary"; cat walls_z.err; exit 1; }
echo "PASS: 1 and 2 processes agree; restarts 2 -> 1 and 1 -> 2 agree; snapshots one series; tethered points split; a held wall held; walls across z refused"
