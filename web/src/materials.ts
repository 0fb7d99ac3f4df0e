// One material per view mode, shared by every mesh on screen. Files' own materials are not used:
// the app shows geometry and per-vertex signals, and a uniform clay look makes filtering visible.

import { DoubleSide, MeshStandardMaterial, type Material, type Mesh } from 'three';

export const VIEW_MODES = ['shaded', 'colors', 'wireframe'] as const;
export type ViewMode = (typeof VIEW_MODES)[number];

export function isViewMode(value: string): value is ViewMode {
  return (VIEW_MODES as readonly string[]).includes(value);
}

// DoubleSide: scans are often open, and their inside should look like a surface, not a hole.
const shaded = new MeshStandardMaterial({ color: 0xc9c4bc, roughness: 0.65, metalness: 0, side: DoubleSide });
const colors = new MeshStandardMaterial({ color: 0xffffff, roughness: 0.8, metalness: 0, vertexColors: true, side: DoubleSide });
const wireframe = new MeshStandardMaterial({ color: 0x9cc3ff, roughness: 0.8, metalness: 0, wireframe: true, side: DoubleSide });

/** The material for a mesh in a mode; meshes without a color attribute stay shaded in 'colors'. */
export function materialFor(mode: ViewMode, mesh: Mesh): Material {
  switch (mode) {
    case 'shaded':
      return shaded;
    case 'colors':
      return mesh.geometry.getAttribute('color') ? colors : shaded;
    case 'wireframe':
      return wireframe;
  }
}
