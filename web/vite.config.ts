import { defineConfig } from 'vite';

// Cross-origin isolation: the multi-threaded wasm build needs SharedArrayBuffer, which browsers only
// grant to pages served with both headers. Dev server and preview must match production hosting.
const isolationHeaders = {
  'Cross-Origin-Opener-Policy': 'same-origin',
  'Cross-Origin-Embedder-Policy': 'require-corp',
};

export default defineConfig({
  // The root is web/: `vite build web`, scripts/serve.mjs and the e2e harness all pass it, and the
  // paths below are relative to it.
  base: './',
  server: { headers: isolationHeaders },
  preview: { headers: isolationHeaders },
  build: {
    outDir: '../dist',
    // dist/ lies outside the root, so Vite refuses to clear it unless told to.
    emptyOutDir: true,
    // three.js alone is ~650 kB minified and cannot be split further; warn only beyond that.
    chunkSizeWarningLimit: 800,
  },
  optimizeDeps: {
    // Pre-bundle the three.js modules up front: otherwise the dev server discovers them on the first
    // page load and reloads the page mid-test when it finishes optimizing.
    include: [
      'three',
      'three/examples/jsm/controls/OrbitControls.js',
      'three/examples/jsm/loaders/GLTFLoader.js',
      'three/examples/jsm/loaders/DRACOLoader.js',
      'three/examples/jsm/exporters/GLTFExporter.js',
      'lil-gui',
      'three/examples/jsm/loaders/OBJLoader.js',
      'three/examples/jsm/loaders/PLYLoader.js',
      'three/examples/jsm/loaders/STLLoader.js',
      'three/examples/jsm/libs/meshopt_decoder.module.js',
    ],
  },
});
