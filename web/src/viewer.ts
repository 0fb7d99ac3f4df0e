// The 3D view: renderer, camera, orbit controls, lights and the model on screen. It renders only
// when something changed (camera move, new model, view mode, resize), so an idle page costs
// nothing, which matters once the wasm filters share the CPU with it.

import {
  BufferGeometry,
  Color,
  Mesh as ThreeMesh,
  MeshBasicMaterial,
  SphereGeometry,
  DirectionalLight,
  HemisphereLight,
  PerspectiveCamera,
  Raycaster,
  Vector2,
  Scene,
  Quaternion,
  Sphere,
  Vector3,
  WebGLRenderer,
  type Mesh,
  type Object3D,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { framingPoints, isFlat, tightFrame } from './framing';
import { materialFor, type ViewMode } from './materials';

export interface ViewerModel {
  root: Object3D;
  meshes: Mesh[];
}

/**
 * Before/after comparison: `before` holds the geometry each mesh had before the last change. With
 * `split` set, the left `split` fraction of the view shows before and the rest after; otherwise
 * `showBefore` picks one for the whole view.
 */
export interface Comparison {
  before: Map<Mesh, BufferGeometry>;
  showBefore: boolean;
  split: number | null;
}

// The default view looks at the model from the front, a little from above and the right, in a
// frame where +Y is up; other up axes rotate it (for +Z up the front is -Y, as Z-up tools have it).
const VIEW_DIRECTION = new Vector3(0.35, 0.3, 1).normalize();
// A flat model (a terrain, a relief) is seen from higher up, so that its relief shows instead of a
// thin strip at a grazing angle (issue 30): 50° above the horizon.
const FLAT_VIEW_DIRECTION = new Vector3(0.35 * Math.cos((50 * Math.PI) / 180), Math.sin((50 * Math.PI) / 180), Math.cos((50 * Math.PI) / 180)).normalize();
const CAMERA_UP = new Vector3(0, 1, 0);

export class Viewer {
  readonly canvas: HTMLCanvasElement;
  private readonly renderer: WebGLRenderer;
  private readonly scene = new Scene();
  private readonly camera = new PerspectiveCamera(40, 1, 0.01, 100);
  private controls: OrbitControls;
  /** The side the default view looks from: 1 the default one, −1 the opposite (setUp). */
  private front: 1 | -1 = 1;
  /** World direction of "up": the camera orbits about it and Reset view stands the model on it. */
  private readonly up = new Vector3(0, 1, 0);
  private readonly hemisphere = new HemisphereLight(0xffffff, 0x3a3d44, 1.1);
  private model: ViewerModel | null = null;
  private mode: ViewMode = 'shaded';
  private comparison: Comparison = { before: new Map(), showBefore: false, split: null };
  private frameRequested = false;
  private frameWaiters: Array<() => void> = [];
  /** The model's bounding sphere (world), for the clipping planes; null: to be measured again. */
  private modelSphere: Sphere | null = null;
  /** The camera is where fitToView put it (no drag since): a resize frames the model again. */
  private framed = false;
  /** A point marked on the model (the source of a geodesic distance), drawn over everything. */
  private readonly marker = new ThreeMesh(
    new SphereGeometry(1, 16, 12),
    new MeshBasicMaterial({ color: 0xff3b6b, depthTest: false, transparent: true, opacity: 0.95 }),
  );

  /** Throws if WebGL is unavailable; the caller reports it. */
  constructor(private readonly container: HTMLElement) {
    this.renderer = new WebGLRenderer({ antialias: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.canvas = this.renderer.domElement;
    this.canvas.dataset.testid = 'canvas';
    container.append(this.canvas);

    this.scene.background = new Color(0x1d2127);
    // Lights ride with the camera so that whatever side the user orbits to is lit the same way.
    // The directional light's target must be in the camera's subtree too, or the light would keep
    // pointing at the world origin.
    const key = new DirectionalLight(0xffffff, 2.6);
    key.position.set(0.6, 0.8, 1);
    this.camera.add(key, key.target);
    // HemisphereLight takes its direction from its world position, not its orientation, so it cannot
    // simply be parented to the camera; updateLights() points it at the camera's "up" every frame.
    this.scene.add(this.camera, this.hemisphere);

    this.controls = this.createControls();
    this.marker.visible = false;
    this.marker.renderOrder = 10;
    this.scene.add(this.marker);

    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  /** Replaces the model on screen, disposes the previous one's geometry, and frames the new one. */
  setModel(model: ViewerModel): void {
    if (this.model) {
      this.scene.remove(this.model.root);
      for (const mesh of this.model.meshes) mesh.geometry.dispose();
    }
    this.comparison = { before: new Map(), showBefore: false, split: null };
    this.marker.visible = false;
    this.modelSphere = null;
    this.model = model;
    this.scene.add(model.root);
    this.applyMode();
    this.fitToView();
  }

  /**
   * Marks a vertex of a mesh on screen (world position, a dot 1.5% of the model's size), or
   * removes the mark (null).
   */
  setMarker(at: { mesh: Mesh; vertex: number } | null): void {
    this.marker.visible = false;
    if (at && this.model) {
      const position = at.mesh.geometry.getAttribute('position');
      if (at.vertex >= 0 && at.vertex < position.count) {
        at.mesh.updateWorldMatrix(true, false);
        this.marker.position.fromBufferAttribute(position, at.vertex).applyMatrix4(at.mesh.matrixWorld);
        this.marker.scale.setScalar(0.015 * this.boundingSphere(this.model).radius);
        this.marker.visible = true;
      }
    }
    this.requestRender();
  }

  /** Where the marker is (world), or null when none is shown. */
  markerPosition(): number[] | null {
    return this.marker.visible ? this.marker.position.toArray() : null;
  }

  setViewMode(mode: ViewMode): void {
    this.mode = mode;
    this.applyMode();
  }

  /** Re-picks materials after attributes were added or removed (new colors, a scalar field). */
  geometryChanged(): void {
    // Positions may have moved (a denoised mesh, noise added).
    this.modelSphere = null;
    this.applyMode();
  }

  setComparison(comparison: Comparison): void {
    this.comparison = comparison;
    this.requestRender();
  }

  /**
   * Sets the up direction (a unit axis) and frames the model again standing on it, seen from the
   * default side (front 1) or the opposite one (−1, up-axis.ts guesses which side is the front).
   */
  setUp(up: Vector3, front: 1 | -1 = 1): void {
    this.front = front;
    if (!up.equals(this.up)) {
      this.up.copy(up).normalize();
      // OrbitControls reads camera.up once, when it is created, so a new up needs new controls.
      this.camera.up.copy(this.up);
      this.controls.dispose();
      this.controls = this.createControls();
    }
    this.fitToView();
  }

  /** Where the camera is (tests check that Reset view and touch gestures move it as expected). */
  cameraState(): { position: number[]; target: number[]; up: number[] } {
    return { position: this.camera.position.toArray(), target: this.controls.target.toArray(), up: this.camera.up.toArray() };
  }

  /**
   * Draws a frame now and hands the canvas to `read` before the browser may clear it (the WebGL
   * canvas keeps no copy of its pixels once the frame is shown), e.g. to copy it into a snapshot.
   */
  drawNow<T>(read: (canvas: HTMLCanvasElement) => T): T {
    this.render();
    return read(this.canvas);
  }

  /**
   * Frames the whole model: seen from the default direction (from higher up for a flat model),
   * centred, its vertices spanning most of the narrower side of the view (framing.ts).
   */
  fitToView(): void {
    if (!this.model) return;
    const sphere = this.boundingSphere(this.model);
    const radius = Math.max(sphere.radius, 1e-6);
    const points = framingPoints(this.model.root, this.model.meshes);
    const toUp = new Quaternion().setFromUnitVectors(CAMERA_UP, this.up);
    const direction = (isFlat(points, this.up) ? FLAT_VIEW_DIRECTION : VIEW_DIRECTION).clone().applyQuaternion(toUp);
    if (this.front < 0) direction.applyAxisAngle(this.up, Math.PI);
    // Motion left over from a drag (damping) would carry the camera away from the new framing.
    this.controls.enableDamping = false;
    this.controls.update();
    this.controls.enableDamping = true;
    const { target, distance } = tightFrame(points, sphere.center, direction, this.up, this.camera.fov, this.camera.aspect);
    this.camera.up.copy(this.up);
    this.camera.position.copy(target).addScaledVector(direction, distance);
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(target);
    this.controls.minDistance = radius * 0.01;
    this.controls.maxDistance = radius * 50;
    this.controls.update();
    this.framed = true;
    this.requestRender();
  }

  /** The mesh and the nearest corner of the triangle under a point of the canvas, if any. */
  pick(clientX: number, clientY: number): { mesh: Mesh; vertex: number } | null {
    if (!this.model) return null;
    const rect = this.canvas.getBoundingClientRect();
    const ndc = new Vector2(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1);
    const raycaster = new Raycaster();
    raycaster.setFromCamera(ndc, this.camera);
    const hit = raycaster.intersectObjects(this.model.meshes, false)[0];
    if (!hit?.face) return null;
    const mesh = hit.object as Mesh;
    const position = mesh.geometry.getAttribute('position');
    const local = mesh.worldToLocal(hit.point.clone());
    let best = hit.face.a;
    let bestDistance = Infinity;
    for (const v of [hit.face.a, hit.face.b, hit.face.c]) {
      const d = local.distanceToSquared(new Vector3().fromBufferAttribute(position, v));
      if (d < bestDistance) [best, bestDistance] = [v, d];
    }
    return { mesh, vertex: best };
  }

  /** Resolves after the next frame has been drawn (requesting one if none is pending). */
  nextFrame(): Promise<void> {
    return new Promise((resolve) => {
      this.frameWaiters.push(resolve);
      this.requestRender();
    });
  }

  requestRender(): void {
    if (this.frameRequested) return;
    this.frameRequested = true;
    requestAnimationFrame(() => this.render());
  }

  private render(): void {
    this.frameRequested = false;
    // With damping, update() keeps moving the camera after the pointer stops and fires 'change',
    // which requests the next frame until the motion settles.
    this.controls.update();
    this.updateLights();
    this.updateClipping();
    const { before, showBefore, split } = this.comparison;
    if (before.size > 0 && split !== null) {
      const width = Math.max(1, this.container.clientWidth);
      const height = Math.max(1, this.container.clientHeight);
      const cut = Math.round(width * Math.min(1, Math.max(0, split)));
      this.renderer.setScissorTest(true);
      this.renderer.setScissor(0, 0, cut, height);
      this.renderWith(before);
      this.renderer.setScissor(cut, 0, width - cut, height);
      this.renderer.render(this.scene, this.camera);
      this.renderer.setScissorTest(false);
    } else if (before.size > 0 && showBefore) {
      this.renderWith(before);
    } else {
      this.renderer.render(this.scene, this.camera);
    }
    const waiters = this.frameWaiters;
    this.frameWaiters = [];
    for (const resolve of waiters) resolve();
  }

  // The meshes keep their current geometry (export and stats read it); the earlier one is swapped
  // in only for this draw.
  private renderWith(geometries: Map<Mesh, BufferGeometry>): void {
    const current = new Map<Mesh, BufferGeometry>();
    for (const [mesh, geometry] of geometries) {
      current.set(mesh, mesh.geometry);
      mesh.geometry = geometry;
      mesh.material = materialFor(this.mode, mesh);
    }
    try {
      this.renderer.render(this.scene, this.camera);
    } finally {
      for (const [mesh, geometry] of current) {
        mesh.geometry = geometry;
        mesh.material = materialFor(this.mode, mesh);
      }
    }
  }

  private createControls(): OrbitControls {
    // Touch: one finger rotates, two pan and pinch-zoom (OrbitControls' defaults, kept explicit).
    const controls = new OrbitControls(this.camera, this.canvas);
    controls.enableDamping = true;
    controls.enableRotate = controls.enablePan = controls.enableZoom = true;
    // The wheel zooms toward the point under the pointer, so that a closer look at a detail stays
    // outside the surface instead of diving through it toward the model's centre.
    controls.zoomToCursor = true;
    controls.addEventListener('change', () => this.requestRender());
    // The person moved the view: a resize keeps their view instead of framing the model again.
    controls.addEventListener('start', () => {
      this.framed = false;
    });
    return controls;
  }

  /**
   * Near and far planes around the model as seen from where the camera is now. With fixed planes
   * (radius / 1000 to 100 radii beyond) the depth buffer resolved ~1/2000 of the model's size,
   * coarser than the gap between the two sides of a tight fold of a sculpted mesh: the far side
   * showed through as dotted hairline cracks along every fold (issue 30). Here the range is about
   * the model's depth, a few hundred times finer.
   */
  private updateClipping(): void {
    if (!this.model) return;
    this.modelSphere ??= this.boundingSphere(this.model);
    const { center, radius } = this.modelSphere;
    const distance = this.camera.position.distanceTo(center);
    const near = Math.max(distance - 1.05 * radius, distance / 500, radius / 5000);
    const far = Math.max(distance + 1.05 * radius, near * 2);
    if (near !== this.camera.near || far !== this.camera.far) {
      this.camera.near = near;
      this.camera.far = far;
      this.camera.updateProjectionMatrix();
    }
  }

  private updateLights(): void {
    this.hemisphere.position.copy(CAMERA_UP).applyQuaternion(this.camera.quaternion);
  }

  private applyMode(): void {
    if (!this.model) return;
    for (const mesh of this.model.meshes) {
      // The file's own material is kept for export (model.ts puts it back there).
      if (mesh.userData.fileMaterial === undefined) mesh.userData.fileMaterial = mesh.material;
      mesh.material = materialFor(this.mode, mesh);
    }
    this.requestRender();
  }

  private boundingSphere(model: ViewerModel): Sphere {
    model.root.updateMatrixWorld(true);
    const total = new Sphere();
    total.makeEmpty();
    for (const mesh of model.meshes) {
      if (!mesh.geometry.boundingSphere) mesh.geometry.computeBoundingSphere();
      const sphere = mesh.geometry.boundingSphere!.clone().applyMatrix4(mesh.matrixWorld);
      total.union(sphere);
    }
    return total;
  }

  private resize(): void {
    const width = Math.max(1, this.container.clientWidth);
    const height = Math.max(1, this.container.clientHeight);
    // updateStyle=false: CSS sizes the canvas to its container; we only match the drawing buffer.
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    // The phone's sheet opening or closing resizes the view: the mesh is framed in what is left.
    if (this.framed) this.fitToView();
    this.requestRender();
  }
}
