#!/usr/bin/env bash
# bench/scale_torus.sh NU NV OUT.obj — writes a quad torus (NU x NV quads, radii 1 and 0.4) for the scale
# runs of docs/scale.md.
set -eu
awk -v nu="$1" -v nv="$2" 'BEGIN {
  pi = atan2(0, -1); R = 1.0; r = 0.4
  for (i = 0; i < nu; i++) for (j = 0; j < nv; j++) {
    u = 2 * pi * i / nu; v = 2 * pi * j / nv
    printf "v %.17g %.17g %.17g\n", (R + r * cos(v)) * cos(u), (R + r * cos(v)) * sin(u), r * sin(v)
  }
  for (i = 0; i < nu; i++) for (j = 0; j < nv; j++) {
    a = i * nv + j; b = ((i + 1) % nu) * nv + j; c = ((i + 1) % nu) * nv + (j + 1) % nv; d = i * nv + (j + 1) % nv
    printf "f %d %d %d %d\n", a + 1, b + 1, c + 1, d + 1
  }
}' > "$3"
