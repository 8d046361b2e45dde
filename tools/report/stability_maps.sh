#!/usr/bin/env bash
# Regenerates the failure envelopes under reports/stability/ (CSV + PNG per map; the runs behind
# them go to MAP/runs/, not kept). About 2 minutes on 2 cores in Release.
# Usage: tools/report/stability_maps.sh [path/to/asperity]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
bin="${1:-$root/build/bin/asperity}"
map="/usr/bin/python3 $root/tools/report/stability_map.py --asperity $bin"
scenes="$root/reports/stability/scenes"
out="$root/reports/stability"

# Spheres (Hertz–Mindlin on a plane).
# Impact speed × step: where the Hertz–Mindlin sphere contact is accurate, inaccurate, unstable.
$map --scene "$scenes/sphere-plane-hertz-mindlin.json" --param bodies.0.velocity.2 \
  --values=-0.01,-0.1,-1,-10,-30 --label "impact speed (m/s)" --out "$out/sphere-speed"
# Damping × step: how the restitution target moves the stable step ((2/ω)(√(1+ξ²) − ξ)).
$map --scene "$scenes/sphere-plane-hertz-mindlin.json" --param materials.glass.restitution \
  --values=1,0.9,0.7,0.5,0.3,0.1 --label "restitution e" --out "$out/sphere-damping"

# FEM/DEM: a generated rock particle (100 triangles, TetGen tetrahedra) striking a fixed block
# through Munjiza's potential contact (docs/physics.md, "Failure maps of the penalty contact").
# Impact speed × step, deformable particle (element and contact limits together) and rigid one
# (contact limit alone): accurate, overshooting, unstable or tunnelled.
$map --scene "$scenes/fem-particle-block.json" --param bodies.0.velocity.2 \
  --values=-0.3,-1,-3,-10,-30,-100 --label "impact speed (m/s)" --factors 0.5,1,1.5,2,3,5,8 \
  --reference-factor 0.1 --out "$out/fem-speed"
$map --scene "$scenes/rigid-particle-block.json" --param bodies.0.velocity.2 \
  --values=-0.3,-1,-3,-10,-30,-100 --label "impact speed (m/s)" --factors 1,3,10,30,60,100,200 \
  --reference-factor 0.1 --out "$out/rigid-speed"
# Penalty α = p/E (E = 5e10 Pa in the scenes) × step at 10 m/s: the predicted step shortens as
# 1/√α once the contact dominates; too soft a penalty is tunnelled.
$map --scene "$scenes/fem-particle-penalty.json" --param contact.penalty --scale 5e10 \
  --values=1e-4,1e-3,1e-2,0.1,1,10,100,1000 --label "penalty α = p / E" \
  --factors 0.5,1,1.5,2,3,5,8,12,20,40 --reference-factor 0.1 \
  --dt-panel --expect "1/sqrt(v)" --expect-anchor 7 --expect-label "∝ 1/√α" --out "$out/fem-penalty"
$map --scene "$scenes/rigid-particle-penalty.json" --param contact.penalty --scale 5e10 \
  --values=1e-4,1e-3,1e-2,0.1,1,10,100,1000 --label "penalty α = p / E" \
  --factors 1,3,10,30,60,100,200 --reference-factor 0.1 \
  --dt-panel --expect "1/sqrt(v)" --expect-anchor 7 --expect-label "∝ 1/√α" --out "$out/rigid-penalty"
# FEM damping ratio (of the highest element mode) × step, with a soft penalty (α = 0.01) so that
# the element limit decides and the damped bound (2/ω)(√(1+ξ²) − ξ) applies alone.
$map --scene "$scenes/fem-particle-damping.json" --param bodies.0.damping_ratio \
  --values=0,0.1,0.3,0.5,1,2 --label "damping ratio ξ (highest element mode)" \
  --factors 0.5,0.75,1,1.25,1.5,2,3,5 --reference-factor 0.1 --dt-panel --dt-panel-xscale linear \
  --expect "sqrt(1+v*v)-v" --expect-label "(2/ω)(√(1+ξ²) − ξ)" --out "$out/fem-damping"
# Flattened tetrahedra: a particle of one tetrahedron whose height falls from the regular one's to
# 1/100 of it (the base 3e-5 m above the block), its predicted step ∝ height.
$map --scene "$scenes/fem-flat-tet.json" --param bodies.0.shape.file \
  --template "meshes/flat-tet-{v}.off" --also "bodies.0.position.2=0.0163299316*v/4+3e-5" \
  --values=1,0.3,0.1,0.03,0.01 --label "height / regular tetrahedron's" \
  --factors 0.5,0.75,1,1.25,1.5,2,3,5 --reference-factor 0.05 \
  --dt-panel --expect "v" --expect-anchor 4 --expect-label "∝ height" --out "$out/fem-flat-tet"
