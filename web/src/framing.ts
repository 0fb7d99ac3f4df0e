// Where the camera goes to show a whole model (viewer.ts, fitToView): tight to its vertices rather
// than to its bounding sphere, whose framing left a flat terrain a thin strip using 60% of the
// view's width (issue 30), and centred on their projection.

import { Quaternion, Vector3, type Mesh, type Object3D } from 'three';

/** Share of the narrower side of the view the framed model spans. */
export const FILL = 0.9;
/** Vertices looked at when framing (every k-th beyond this many). */
const FRAMING_SAMPLES = 20_000;
/** A model this thin along its up axis, against both other sides, is flat (seen from higher up). */
const FLAT = 0.3;

/** World positions of (a sample of) the meshes' vertices. */
export function framingPoints(root: Object3D, meshes: Mesh[]): Vector3[] {
  root.updateMatrixWorld(true);
  let total = 0;
  for (const mesh of meshes) total += mesh.geometry.getAttribute('position').count;
  const stride = Math.max(1, Math.ceil(total / FRAMING_SAMPLES));
  const points: Vector3[] = [];
  for (const mesh of meshes) {
    const position = mesh.geometry.getAttribute('position');
    for (let i = 0; i < position.count; i += stride) points.push(new Vector3().fromBufferAttribute(position, i).applyMatrix4(mesh.matrixWorld));
  }
  return points;
}

/** Thin along the up axis compared with both other sides (a terrain, a relief, a plate). */
export function isFlat(points: Vector3[], up: Vector3): boolean {
  const toFrame = new Quaternion().setFromUnitVectors(up, new Vector3(0, 1, 0));
  const min = new Vector3(Infinity, Infinity, Infinity);
  const max = new Vector3(-Infinity, -Infinity, -Infinity);
  const p = new Vector3();
  for (const point of points) {
    p.copy(point).applyQuaternion(toFrame);
    min.min(p);
    max.max(p);
  }
  const size = max.sub(min);
  return size.y < FLAT * Math.min(size.x, size.z);
}

/**
 * Where to look from `direction` (unit, from the target towards the camera) so that every point is
 * in view with FILL to spare: the camera distance at which the widest point touches the narrower
 * side, then the target moved so that the points' projection is centred. `fov` is the vertical
 * field of view in degrees, `aspect` width over height.
 */
export function tightFrame(points: Vector3[], centre: Vector3, direction: Vector3, cameraUp: Vector3, fov: number, aspect: number): { target: Vector3; distance: number } {
  const forward = direction.clone().negate();
  const right = new Vector3().crossVectors(forward, cameraUp).normalize();
  const up = new Vector3().crossVectors(right, forward).normalize();
  const tanV = Math.tan((fov * Math.PI) / 360) * FILL;
  const tanH = tanV * aspect;
  const target = centre.clone();
  let distance = 0;
  const d = new Vector3();
  for (let pass = 0; pass < 2; pass++) {
    // Camera distance: each point p, at depth D - p·direction, needs |p·right| <= tanH·depth and
    // |p·up| <= tanV·depth.
    distance = 0;
    for (const point of points) {
      d.subVectors(point, target);
      const along = d.dot(direction);
      distance = Math.max(distance, along + Math.abs(d.dot(right)) / tanH, along + Math.abs(d.dot(up)) / tanV);
    }
    if (pass === 1 || points.length === 0) break;
    // Centre the projection: shift the target by the mid-point of the extreme view angles.
    let loX = Infinity, hiX = -Infinity, loY = Infinity, hiY = -Infinity;
    for (const point of points) {
      d.subVectors(point, target);
      const depth = Math.max(distance - d.dot(direction), 1e-9);
      loX = Math.min(loX, d.dot(right) / depth);
      hiX = Math.max(hiX, d.dot(right) / depth);
      loY = Math.min(loY, d.dot(up) / depth);
      hiY = Math.max(hiY, d.dot(up) / depth);
    }
    target.addScaledVector(right, ((loX + hiX) / 2) * distance).addScaledVector(up, ((loY + hiY) / 2) * distance);
  }
  return { target, distance: Math.max(distance, 1e-6) };
}
