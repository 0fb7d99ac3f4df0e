// The threaded flavour's pthread script (geoshift_web_mt.worker.js of the wasm build) as text:
// scripts/build.mjs writes dist/pthread-worker.js. worker.ts says why it is not a file of its own.
declare const source: string;
export default source;
