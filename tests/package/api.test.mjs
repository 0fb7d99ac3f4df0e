// The package's API under Node (package/dist, as the workspace links it): the order of jobs, what a
// cancel does to a running and to a queued job, kept meshes across a replaced worker, previews,
// terminate, and the checks at the JS edge. Small meshes, one worker per test.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { createGeoshift, GeoshiftError } from 'geoshift';
import { firstMismatch, saddle } from '../wasm/support.mjs';

const mesh = saddle(12);

/** The rejection of `promise`, as { kind, message }; fails if it resolves. */
async function failure(promise) {
  try {
    await promise;
  } catch (error) {
    assert.ok(error instanceof GeoshiftError, `not a GeoshiftError: ${error}`);
    return { kind: error.kind, message: error.message };
  }
  assert.fail('the call succeeded');
}

/** A smoothing that runs until cancelled, and a promise that settles at its first progress report. */
function longJob(gs, signal) {
  let started;
  const running = new Promise((resolve) => (started = resolve));
  const job = gs.smooth(mesh, { iterations: 1_000_000, signal, onProgress: () => started() });
  job.catch(() => undefined);
  return { job, running };
}

for (const threads of [1, 2]) {
  test(`${threads === 1 ? 'one thread' : 'threads'}: a cancelled run fails as cancelled, a queued job behind it still runs, a cancelled queued job never starts`, async () => {
    const gs = await createGeoshift({ threads });
    try {
      assert.equal(gs.info.threaded, threads > 1);
      const controller = new AbortController();
      const { job, running } = longJob(gs, controller.signal);
      const queuedController = new AbortController();
      let queuedProgress = 0;
      const queued = gs.smooth(mesh, { iterations: 2, signal: queuedController.signal, onProgress: () => queuedProgress++ });
      const after = gs.curvature(mesh);
      await running;
      queuedController.abort();
      assert.deepEqual(await failure(queued), { kind: 'cancelled', message: 'cancelled' });
      controller.abort();
      assert.deepEqual(await failure(job), { kind: 'cancelled', message: 'cancelled' });
      assert.equal(queuedProgress, 0, 'the cancelled queued job ran');
      assert.deepEqual(Object.keys((await after).attributes), ['_CURVATURE']);
      // An already aborted signal fails at once.
      assert.equal((await failure(gs.noise(mesh, { signal: AbortSignal.abort() }))).kind, 'cancelled');
    } finally {
      gs.terminate();
    }
  });
}

test('jobs run in the order they were called, and their results do not depend on it', async () => {
  const gs = await createGeoshift({ threads: 1 });
  try {
    const order = [];
    const jobs = [1, 2, 3].map((iterations) => gs.smooth(mesh, { iterations, onProgress: () => order.at(-1) !== iterations && order.push(iterations) }));
    const results = await Promise.all(jobs);
    assert.deepEqual(order, [1, 2, 3]);
    assert.deepEqual((await gs.smooth(mesh, { iterations: 2 })).positions, results[1].positions);
    assert.deepEqual(mesh.positions, saddle(12).positions, 'the input was modified');
  } finally {
    gs.terminate();
  }
});

test('a kept mesh chains runs; after its worker is replaced (a cancel on one thread) its calls fail saying so', async () => {
  const gs = await createGeoshift({ threads: 1 });
  try {
    const kept = await gs.load(mesh);
    assert.equal(kept.info.vertexCount, 13 * 13);
    assert.ok(kept.info.averageEdgeLength > 0);
    const noisy = await kept.run('noise', { amount: 0.3, seed: 4 });
    const smoothed = await kept.run('smooth', { iterations: 5 });
    // The chain equals the two jobs one after another on the arrays (to float rounding: the kept
    // mesh keeps doubles between runs).
    const again = await gs.smooth({ ...mesh, positions: noisy.positions }, { iterations: 5 });
    assert.equal(firstMismatch(smoothed.positions, again.positions, 1e-5), -1);
    assert.notDeepEqual(smoothed.positions, noisy.positions);
    const preview = await kept.preview('smooth', { iterations: 5, maxVertices: 100 });
    assert.ok(preview.stats.previewVertices <= 100, JSON.stringify(preview.stats));
    assert.equal(preview.positions.length, mesh.positions.length);

    const controller = new AbortController();
    const { job, running } = longJob(gs, controller.signal);
    await running;
    controller.abort();
    await failure(job);
    const gone = await failure(kept.run('curvature'));
    assert.equal(gone.kind, 'input');
    assert.match(gone.message, /worker that has since been replaced.*load it again/);
    await kept.free(); // nothing left to free: no error
    const reloaded = await gs.load(mesh);
    assert.ok((await reloaded.run('curvature')).attributes._CURVATURE);
    await reloaded.free();
    assert.equal((await failure(reloaded.run('curvature'))).kind, 'input');
  } finally {
    gs.terminate();
  }
});

test('terminate fails what is pending and what comes after, as cancelled', async () => {
  const gs = await createGeoshift({ threads: 1 });
  const { job, running } = longJob(gs);
  const queued = gs.curvature(mesh);
  await running;
  gs.terminate();
  assert.deepEqual(await failure(job), { kind: 'cancelled', message: 'the geoshift worker was terminated' });
  assert.equal((await failure(queued)).kind, 'cancelled');
  assert.equal((await failure(gs.curvature(mesh))).kind, 'cancelled');
});

test('bad arguments are refused at the JS edge, naming what is wrong; bad options by the core, naming the option', async () => {
  const gs = await createGeoshift({ threads: 1 });
  try {
    const cases = [
      [gs.denoise(null), 'mesh must be an object with positions (got null)'],
      [gs.denoise({ positions: new Float64Array(9) }), 'mesh.positions must be a Float32Array (got Float64Array)'],
      [gs.denoise({ positions: new Float32Array(10) }), 'mesh.positions holds 10 numbers, not x, y, z per vertex'],
      [gs.denoise({ positions: new Float32Array(12) }), 'mesh has no indices and 4 vertices, not three per triangle'],
      [gs.denoise({ positions: new Float32Array(9), indices: [0, 1, 2] }), 'mesh.indices must be a Uint32Array or a Uint16Array (got Array)'],
      [gs.denoise({ positions: new Float32Array(9), indices: new Uint32Array(4) }), 'mesh.indices holds 4 numbers, not three per triangle'],
      [gs.filter({ ...mesh, colors: new Float32Array(5) }), 'mesh.colors holds 5 numbers for 169 vertices; give 3 (RGB) or 4 (RGBA) per vertex'],
      [gs.filter({ ...mesh, attributes: { h: new Float32Array(170) } }), 'mesh.attributes["h"] holds 170 numbers for 169 vertices; give 1 to 16 per vertex'],
      [gs.filter({ ...mesh, attributes: { color: new Float32Array(169) } }), 'mesh.attributes["color"]: the name must not be empty, "color" or "normal" (colors go in colors; normals come from the geometry)'],
      [gs.smooth(mesh, { onProgress: 3 }), 'smooth: onProgress must be a function'],
      [gs.filter(mesh, { signal: 'color' }), 'filter: signal must be an AbortSignal (the values to filter are option field)'],
      [gs.read([1, 2], 'x.obj'), 'read: bytes must be a Uint8Array or an ArrayBuffer'],
    ];
    for (const [call, message] of cases) assert.deepEqual(await failure(call), { kind: 'input', message });
    const typo = await failure(gs.denoise(mesh, { strenght: 2 }));
    assert.equal(typo.kind, 'input');
    assert.match(typo.message, /^denoise: unknown parameter "strenght" \(accepted: .*strength/);
    const range = await failure(gs.smooth(mesh, { iterations: -1 }));
    assert.match(range.message, /iterations/);
    await assert.rejects(createGeoshift({ threads: 0 }), /threads must be 'auto' or a whole number from 1 to 64 \(got 0\)/);
    await assert.rejects(createGeoshift({ maxMemoryMB: 10 }), /maxMemoryMB must be at least 64 \(got 10\)/);
  } finally {
    gs.terminate();
  }
});

test('a module file that cannot be found fails createGeoshift as internal, naming the flavour', async () => {
  const error = await failure(createGeoshift({ threads: 1, locateFile: (file) => (file.endsWith('.wasm') ? '/nonexistent/geoshift_web.wasm' : undefined) }));
  assert.equal(error.kind, 'internal');
  assert.match(error.message, /geoshift_web could not start.*nonexistent/);
});

test('read gives the parts\' arrays in the file\'s order, or only counts', async () => {
  const gs = await createGeoshift({ threads: 1 });
  try {
    const obj = new TextEncoder().encode('v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2//1 4//1 3//1\n');
    const r = await gs.read(obj, 'quad.obj');
    assert.equal(r.vertices, 4);
    const [part] = r.parts;
    assert.deepEqual(Array.from(part.mesh.indices), [0, 1, 2, 1, 3, 2]);
    assert.deepEqual(Array.from(part.mesh.positions.slice(9)), [1, 1, 0]);
    assert.equal(part.mesh.normals?.length, 12);
    assert.deepEqual(Array.from(part.transforms), [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
    assert.equal(obj[0], 'v'.charCodeAt(0), 'the bytes were detached');
    const counts = await gs.read(obj.buffer, 'quad.obj', { meshes: false });
    assert.equal(counts.parts[0].mesh, undefined);
    assert.equal(counts.triangles, 2);
    const limited = await failure(gs.read(obj, 'quad.obj', { maxVertices: 3 }));
    assert.equal(limited.kind, 'input');
    assert.match(limited.message, /^quad\.obj: .*4 vertices, more than the limit of 3/);
  } finally {
    gs.terminate();
  }
});
