#!/usr/bin/env bash
# Rebuilds assets/three.min.js, the three.js subset that motion.html inlines (the page must work offline,
# so nothing is loaded from a CDN). three ships no minified single-file build any more (ESM only), so we
# bundle the classes the viewer uses, plus OrbitControls, into one minified IIFE that defines `THREE`.
# Run from anywhere; needs node/npm and the npm registry. Bump THREE_VERSION to upgrade.
set -euo pipefail
THREE_VERSION=0.187.0
ESBUILD_VERSION=0.28.2
repo=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
npm init -y >/dev/null
npm install --no-audit --no-fund --save-exact "three@$THREE_VERSION" "esbuild@$ESBUILD_VERSION" >/dev/null
# Keep this list in step with what src/report/viewer.html uses (`THREE.X`).
cat > entry.js <<'JS'
export {
  AmbientLight, ArrowHelper, BoxGeometry, CapsuleGeometry, Color, CylinderGeometry, DirectionalLight,
  DoubleSide, GridHelper, Group, HemisphereLight, Mesh, MeshBasicMaterial, MeshStandardMaterial,
  PerspectiveCamera, PlaneGeometry, Quaternion, REVISION, Scene, SphereGeometry, Vector3, WebGLRenderer,
  BufferGeometry, Float32BufferAttribute, LineSegments, LineBasicMaterial, LineLoop,
} from 'three';
export { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
JS
banner="/* three.js ${THREE_VERSION} (MIT, see assets/three.LICENSE), subset + OrbitControls bundled by scripts/vendor-three.sh */"
npx esbuild entry.js --bundle --minify --format=iife --global-name=THREE --legal-comments=none \
    --banner:js="$banner" --outfile="$repo/assets/three.min.js"
cp node_modules/three/LICENSE "$repo/assets/three.LICENSE"
echo "wrote $repo/assets/three.min.js ($(wc -c < "$repo/assets/three.min.js") bytes) and assets/three.LICENSE"
