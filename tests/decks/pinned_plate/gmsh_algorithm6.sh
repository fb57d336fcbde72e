#!/bin/sh
# gmsh with pycalculix's Frontal-Delaunay for quads (Mesh.Algorithm 8), which
# makes Debian's gmsh 4.8.4 crash on this geometry, replaced by
# Frontal-Delaunay (6) with the same recombination: $1 is the .geo
sed -i 's/^Mesh.Algorithm = 8;/Mesh.Algorithm = 6;/' "$1"
exec gmsh "$@"
