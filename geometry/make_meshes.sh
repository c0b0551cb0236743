#!/usr/bin/env bash
# Write the committed meshes geometry/*.msh from their .geo files with gmsh
# (Debian package gmsh; only needed to change a mesh, not to run viscofilm):
# 2D, all quadrilaterals, msh 2.2 ASCII (what deal.II's GridIn reads), only
# the elements of physical groups (so every boundary face carries its tag).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")"
command -v gmsh > /dev/null || { echo "make_meshes.sh: needs gmsh (apt-get install gmsh)" >&2; exit 1; }
for geo in cylinder flow_cell; do
  gmsh -2 -format msh22 -o "$geo.msh" "$geo.geo" > "$geo.log"
  rm "$geo.log"
  echo "wrote geometry/$geo.msh"
done
