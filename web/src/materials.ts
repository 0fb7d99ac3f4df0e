// One material per view mode, shared by every mesh on screen. Files' own materials are kept aside
// for export (see model.ts): the app shows geometry and per-vertex signals, and a uniform clay look
// makes filtering visible.

import { DoubleSide, FrontSide, MeshStandardMaterial, type Material, type Mesh } from 'three';

export const VIEW_MODES = ['shaded', 'colors', 'scalar', 'wireframe'] as const;
export type ViewMode = (typeof VIEW_MODES)[number];

export function isViewMode(value: string): value is ViewMode {
  return (VIEW_MODES as readonly string[]).includes(value);
}

/** The attribute scalar mode reads; written by the app from the chosen scalar field. */
export const SCALAR_COLOR = 'scalarColor';

// Both sides of an open surface are drawn: scans are often open, and their inside should look like
// a surface, not a hole. A closed one (loaders.ts, isClosed) shows its outside only: drawn double
// sided, the inner face of a tight fold fought the outer one for depth along the fold's crest and
// showed as dotted hairline cracks (issue 30; the start-up sample's mane and chest).
const shaded = new MeshStandardMaterial({ color: 0xc9c4bc, roughness: 0.65, metalness: 0, side: DoubleSide });
const colors = new MeshStandardMaterial({ color: 0xffffff, roughness: 0.8, metalness: 0, vertexColors: true, side: DoubleSide });
const wireframe = new MeshStandardMaterial({ color: 0x9cc3ff, roughness: 0.8, metalness: 0, wireframe: true, side: DoubleSide });

// Vertex colors taken from SCALAR_COLOR instead of "color", so a color-mapped field never
// overwrites the mesh's own colors (which the filters and the export need).
const scalar = new MeshStandardMaterial({ color: 0xffffff, roughness: 0.85, metalness: 0, vertexColors: true, side: DoubleSide });
scalar.onBeforeCompile = (shader) => {
  shader.vertexShader = `attribute vec3 ${SCALAR_COLOR};\n${shader.vertexShader.replace(
    '#include <color_vertex>',
    // three declares vColor as vec4 whenever vertex colors are on.
    `vColor = vec4( ${SCALAR_COLOR}, 1.0 );`,
  )}`;
};
scalar.customProgramCacheKey = () => 'geoshift-scalar';

// Kept beside the meshes rather than in their userData, which the glTF export writes as extras.
const closedMeshes = new WeakSet<Mesh>();

/** The mesh is a closed surface: its outside only is drawn. */
export function markClosed(mesh: Mesh): void {
  closedMeshes.add(mesh);
}

/** The same material drawing front faces only, made once per material. */
const frontOnly = new Map<Material, Material>();
function outsideOnly(material: Material): Material {
  let front = frontOnly.get(material);
  if (!front) {
    front = material.clone();
    front.side = FrontSide;
    // clone() keeps the properties, not the shader hook of the scalar material.
    front.onBeforeCompile = material.onBeforeCompile;
    front.customProgramCacheKey = () => `${material.customProgramCacheKey()}-front`;
    frontOnly.set(material, front);
  }
  return front;
}

/** The material for a mesh in a mode; meshes without the needed attribute stay shaded. */
export function materialFor(mode: ViewMode, mesh: Mesh): Material {
  const material = materialOf(mode, mesh);
  return closedMeshes.has(mesh) && mode !== 'wireframe' ? outsideOnly(material) : material;
}

function materialOf(mode: ViewMode, mesh: Mesh): Material {
  switch (mode) {
    case 'shaded':
      return shaded;
    case 'colors':
      return mesh.geometry.getAttribute('color') ? colors : shaded;
    case 'scalar':
      return mesh.geometry.getAttribute(SCALAR_COLOR) ? scalar : shaded;
    case 'wireframe':
      return wireframe;
  }
}
