// Export of the open file, with the filter results, as .glb. The whole scene of the file is written
// (nodes, transforms, the file's own materials, other attributes); only the app's display state
// (view materials, the scalar color attribute) is taken out for the duration of the export.

import type { Mesh, Object3D } from 'three';
import { SCALAR_COLOR } from './materials';

export async function exportGlb(root: Object3D, meshes: Mesh[]): Promise<ArrayBuffer> {
  const { GLTFExporter } = await import('three/examples/jsm/exporters/GLTFExporter.js');
  const restore: Array<() => void> = [];
  for (const mesh of meshes) {
    const shown = mesh.material;
    const fileMaterial = mesh.userData.fileMaterial as Mesh['material'] | undefined;
    if (fileMaterial) mesh.material = fileMaterial;
    const scalarColor = mesh.geometry.getAttribute(SCALAR_COLOR);
    if (scalarColor) mesh.geometry.deleteAttribute(SCALAR_COLOR);
    restore.push(() => {
      mesh.material = shown;
      if (scalarColor) mesh.geometry.setAttribute(SCALAR_COLOR, scalarColor);
    });
  }
  try {
    const result = await new GLTFExporter().parseAsync(root, { binary: true, onlyVisible: false });
    if (!(result instanceof ArrayBuffer)) throw new Error('the exporter did not produce a binary glTF');
    return result;
  } finally {
    for (const undo of restore) undo();
  }
}

/** Offers a file to download without leaving the page. */
export function saveBlob(blob: Blob, fileName: string): void {
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url;
  a.download = fileName;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** Offers GLB bytes as a download. */
export function download(bytes: ArrayBuffer, fileName: string): void {
  saveBlob(new Blob([bytes], { type: 'model/gltf-binary' }), fileName);
}

/** "scan.obj" -> "scan-geoshift.glb". */
export function exportName(fileName: string): string {
  const dot = fileName.lastIndexOf('.');
  return `${dot > 0 ? fileName.slice(0, dot) : fileName}-geoshift.glb`;
}
