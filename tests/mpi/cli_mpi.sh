#!/usr/bin/env bash
# tests/mpi/cli_mpi.sh MPIEXEC POLYDEC N SHARED_DATA — `polydec ... --engine petsc` under mpirun at N
# ranks: bad input (a file the last rank cannot read, another mesh on the last rank than the others',
# a non-manifold mesh whose bad edge joins faces of different ranks) ends every rank with the same
# one-line error and exit code 3, without a hang;
# a good run gives the serial command's numbers (distances 1e-8 of the largest, eigenvalues 1e-8).
# The meshes: SHARED_DATA/suzanne-half.obj (and quad-plane.obj as the other mesh), or on a clone
# without that folder two generated saddle grids; a missing file fails when
# POLYDEC_REQUIRE_SHARED_DATA=1.
set -u
MPIEXEC=$1 POLYDEC=$2 N=$3 DATA=$4
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
mpi() { timeout 90 "$MPIEXEC" --oversubscribe --mca mpi_yield_when_idle 1 "$@"; }

# An OBJ of NX x NY quads over [0,1]^2 bent into the saddle z = (x - 1/2)^2 - (y - 1/2)^2 (open,
# curved, non-planar quads).
saddle_obj() {
  awk -v nx="$1" -v ny="$2" 'BEGIN {
    for (j = 0; j <= ny; ++j) for (i = 0; i <= nx; ++i) {
      x = i / nx; y = j / ny; printf "v %.17g %.17g %.17g\n", x, y, (x - 0.5)^2 - (y - 0.5)^2 }
    for (j = 0; j < ny; ++j) for (i = 0; i < nx; ++i) {
      a = j * (nx + 1) + i + 1; printf "f %d %d %d %d\n", a, a + 1, a + nx + 2, a + nx + 1 } }'
}
if [ -f "$DATA/suzanne-half.obj" ] && [ -f "$DATA/quad-plane.obj" ]; then
  GOOD=$DATA/suzanne-half.obj OTHER=$DATA/quad-plane.obj
elif [ "${POLYDEC_REQUIRE_SHARED_DATA:-}" = 1 ]; then
  fail "required test meshes missing: $DATA/suzanne-half.obj, $DATA/quad-plane.obj"
else
  echo "note: $DATA/suzanne-half.obj not found (clone without shared data): generated saddle grids instead"
  GOOD=$TMP/saddle.obj OTHER=$TMP/saddle-small.obj
  saddle_obj 16 12 > "$GOOD"
  saddle_obj 6 5 > "$OTHER"
fi

# A non-manifold mesh: edge (0, 1) shared by three triangles.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n' > "$TMP/nonmanifold.obj"

# One rank's run: its stderr and exit code in files of its own (mpirun would interleave the ranks'
# stderr, and kill the other ranks as soon as one exits non-zero, perhaps before they print).
cat > "$TMP/rank.sh" <<RANK
#!/usr/bin/env bash
"$POLYDEC" geodesics "\$1" --source 0 --engine petsc > /dev/null 2> "$TMP/err.\$OMPI_COMM_WORLD_RANK"
echo \$? > "$TMP/rc.\$OMPI_COMM_WORLD_RANK"
RANK

# Ranks 0 .. N-2 read $3 (default GOOD), rank N-1 reads $1; expects exit code 3 on every rank and N
# identical error lines containing $2.
bad_last_rank() {
  local bad=$1 expect=$2 others=${3:-$GOOD}
  rm -f "$TMP"/err.* "$TMP"/rc.*
  mpi -n $((N - 1)) bash "$TMP/rank.sh" "$others" : -n 1 bash "$TMP/rank.sh" "$bad"
  local rc=$?
  [ "$rc" -ne 124 ] || fail "$bad: timed out (hang)"
  for r in $(seq 0 $((N - 1))); do
    [ "$(cat "$TMP/rc.$r" 2> /dev/null)" = 3 ] || { cat "$TMP"/err.*; fail "$bad: rank $r exit code $(cat "$TMP/rc.$r"), expected 3"; }
  done
  local lines
  lines=$(cat "$TMP"/err.* | grep '^polydec: bad input: ' | sort | uniq -c)
  [ "$(echo "$lines" | wc -l)" -eq 1 ] || { echo "$lines"; fail "$bad: the ranks reported different errors"; }
  [ "$(echo "$lines" | awk '{print $1}')" -eq "$N" ] || { echo "$lines"; fail "$bad: not every rank reported"; }
  echo "$lines" | grep -q -- "$expect" || { echo "$lines"; fail "$bad: message lacks '$expect'"; }
  echo "ok: $bad on rank $((N - 1)) of $N: $(echo "$lines" | sed 's/^ *[0-9]* //')"
}
bad_last_rank "$TMP/missing.obj" "missing.obj"
bad_last_rank "$TMP/nonmanifold.obj" "non-manifold" "$TMP/nonmanifold.obj"  # every rank reads it
bad_last_rank "$OTHER" "different meshes"

# Good runs against the serial command.
json_number() { grep "\"$1\":" "$2" | head -1 | sed 's/.*: *//; s/,$//'; }
"$POLYDEC" geodesics "$GOOD" --source 3 --json > "$TMP/serial.json" || fail "serial geodesics"
mpi -n "$N" "$POLYDEC" geodesics "$GOOD" --source 3 --json --engine petsc --out "$TMP/d.ply" > "$TMP/petsc.json" \
  || fail "petsc geodesics"
[ -s "$TMP/d.ply" ] || fail "no PLY written"
for key in max mean; do
  a=$(json_number $key "$TMP/serial.json") b=$(json_number $key "$TMP/petsc.json")
  awk -v a="$a" -v b="$b" -v m="$(json_number max "$TMP/serial.json")" \
    'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-8 * m) }' || fail "geodesics $key: serial $a, petsc $b"
done
grep -q '"peak_rss_mb"' "$TMP/petsc.json" || fail "no per-rank summary"
[ "$(grep -c '"peak_rss_mb"' "$TMP/petsc.json")" -eq "$N" ] || fail "summary lacks a rank"
"$POLYDEC" spectrum "$GOOD" --k 8 --out "$TMP/s" > /dev/null || fail "serial spectrum"
mpi -n "$N" "$POLYDEC" spectrum "$GOOD" --k 8 --engine petsc --out "$TMP/p" > /dev/null || fail "petsc spectrum"
paste "$TMP/s/eigenvalues.txt" "$TMP/p/eigenvalues.txt" | awk 'NR == 2 { s = $1 } { d = $1 - $2; if (d < 0) d = -d;
  e = $1 > s ? $1 : s; if (NR > 1 && d > 1e-8 * e) bad = 1 } END { exit bad || NR != 8 }' \
  || { paste "$TMP/s/eigenvalues.txt" "$TMP/p/eigenvalues.txt"; fail "eigenvalues differ"; }
[ -s "$TMP/p/eigenvectors.mtx" ] && [ -s "$TMP/p/eigenvectors.ply" ] || fail "eigenvector files missing"
echo "ok: geodesics and spectrum at $N ranks equal the serial command's"
