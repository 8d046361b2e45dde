#!/usr/bin/env bash
# Regenerates the failure envelopes under reports/stability/ (CSV + PNG per map).
# Usage: reports/tools/stability_maps.sh [path/to/asperity]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
bin="${1:-$root/build/bin/asperity}"
map="/usr/bin/python3 $root/reports/tools/stability_map.py --asperity $bin"
scenes="$root/reports/stability/scenes"
# Impact speed × step: where the Hertz–Mindlin sphere contact is accurate, inaccurate, unstable.
$map --scene "$scenes/sphere-plane-hertz-mindlin.json" --param bodies.0.velocity.2 \
  --values=-0.01,-0.1,-1,-10,-30 --label "impact speed (m/s)" --out "$root/reports/stability/sphere-speed"
# Damping × step: how the restitution target moves the stable step ((2/ω)(√(1+ξ²) − ξ)).
$map --scene "$scenes/sphere-plane-hertz-mindlin.json" --param materials.glass.restitution \
  --values=1,0.9,0.7,0.5,0.3,0.1 --label "restitution e" --out "$root/reports/stability/sphere-damping"
