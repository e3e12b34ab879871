#!/usr/bin/env bash
# How billiards/export/vendor/three-viewer.min.js was made: the parts of three.js the
# replay page uses (renderer, scene, cameras, lights, animation mixer, GLTFLoader,
# OrbitControls), from the npm registry's three@$THREE, bundled and minified by esbuild
# into one script that sets the global THREE (the page embeds it; no module loading,
# no network). Run from the repository's root with Node and npm; it rewrites the
# bundle and its licence. Not part of the build: the bundle is committed.
set -euo pipefail
THREE=0.169.0
ESBUILD=0.24.0
out="$(pwd)/billiards/export/vendor"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
npm pack --silent "three@$THREE" >/dev/null
tar xzf "three-$THREE.tgz"
npm install --silent --no-save --no-audit --no-fund "esbuild@$ESBUILD" >/dev/null
# The examples import 'three'; point them at the same sources the entry uses.
sed -i "s#from 'three'#from '$work/package/src/Three.js'#" \
    package/examples/jsm/loaders/GLTFLoader.js \
    package/examples/jsm/controls/OrbitControls.js \
    package/examples/jsm/utils/BufferGeometryUtils.js
cat > entry.js <<'JS'
export { WebGLRenderer, Scene, PerspectiveCamera, OrthographicCamera, AnimationMixer, Color,
  HemisphereLight, DirectionalLight, AmbientLight, Vector3, SRGBColorSpace,
  ACESFilmicToneMapping, LoopOnce, MathUtils } from './package/src/Three.js';
export { GLTFLoader } from './package/examples/jsm/loaders/GLTFLoader.js';
export { OrbitControls } from './package/examples/jsm/controls/OrbitControls.js';
JS
node_modules/@esbuild/linux-x64/bin/esbuild entry.js --bundle --minify --format=iife \
    --global-name=THREE --legal-comments=none \
    --banner:js="/* three.js ${THREE} (https://threejs.org), MIT licence: LICENSE-three.txt */" \
    --outfile="$out/three-viewer.min.js"
cp package/LICENSE "$out/LICENSE-three.txt"
echo "three@$THREE -> $out/three-viewer.min.js ($(wc -c <"$out/three-viewer.min.js") bytes)"
