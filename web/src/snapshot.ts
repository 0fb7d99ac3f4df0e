// PNG snapshot of the view: the 3D canvas as drawn (the split view included, since the viewer draws
// both halves into it), with the color legend and the split line painted on top where the page
// shows them, at the canvas's own resolution.

import type { LegendContent } from './legend';
import type { Viewer } from './viewer';

export interface Overlays {
  /** The viewport element the canvas fills; overlay positions are taken relative to it. */
  viewport: HTMLElement;
  legend: { element: HTMLElement; content: LegendContent | null };
  splitLine: HTMLElement;
}

/** Renders a frame and composes the snapshot; resolves with PNG bytes. */
export async function snapshotPng(viewer: Viewer, overlays: Overlays): Promise<Blob> {
  const composed = viewer.drawNow((gl) => {
    const out = document.createElement('canvas');
    out.width = gl.width;
    out.height = gl.height;
    const ctx = out.getContext('2d');
    if (!ctx) throw new Error('this browser cannot draw into a 2D canvas');
    // Copied within the same task as the render: the WebGL canvas still holds the frame.
    ctx.drawImage(gl, 0, 0);
    return { out, ctx };
  });
  const { out, ctx } = composed;
  const box = overlays.viewport.getBoundingClientRect();
  const scale = out.width / Math.max(1, box.width);
  const rectOf = (el: HTMLElement) => {
    const r = el.getBoundingClientRect();
    return { x: (r.left - box.left) * scale, y: (r.top - box.top) * scale, w: r.width * scale, h: r.height * scale };
  };
  if (!overlays.splitLine.hidden) {
    const r = rectOf(overlays.splitLine);
    ctx.fillStyle = getComputedStyle(overlays.splitLine).backgroundColor;
    ctx.fillRect(r.x, r.y, Math.max(1, r.w), r.h);
  }
  const legend = overlays.legend.content;
  if (legend && !overlays.legend.element.hidden) drawLegend(ctx, rectOf(overlays.legend.element), legend, scale);
  return new Promise((resolve, reject) =>
    out.toBlob((blob) => (blob ? resolve(blob) : reject(new Error('the snapshot could not be encoded as PNG'))), 'image/png'),
  );
}

function drawLegend(ctx: CanvasRenderingContext2D, r: { x: number; y: number; w: number; h: number }, legend: LegendContent, scale: number): void {
  const pad = 6 * scale;
  ctx.fillStyle = 'rgb(29 33 39 / 85%)';
  ctx.fillRect(r.x, r.y, r.w, r.h);
  ctx.strokeStyle = '#3a404a';
  ctx.lineWidth = scale;
  ctx.strokeRect(r.x + 0.5 * scale, r.y + 0.5 * scale, r.w - scale, r.h - scale);
  const fontSize = 12 * scale;
  ctx.font = `${fontSize}px system-ui, sans-serif`;
  ctx.textBaseline = 'top';
  ctx.fillStyle = '#e6e8eb';
  ctx.fillText(legend.title, r.x + pad, r.y + pad, r.w - 2 * pad);
  const rampY = r.y + pad + fontSize * 1.4;
  const rampH = 10 * scale;
  const gradient = ctx.createLinearGradient(r.x + pad, 0, r.x + r.w - pad, 0);
  legend.ramp.forEach(([red, green, blue], i) =>
    gradient.addColorStop(i / (legend.ramp.length - 1), `rgb(${Math.round(red * 255)} ${Math.round(green * 255)} ${Math.round(blue * 255)})`),
  );
  ctx.fillStyle = gradient;
  ctx.fillRect(r.x + pad, rampY, r.w - 2 * pad, rampH);
  ctx.fillStyle = '#a4abb5';
  const endsY = rampY + rampH + 3 * scale;
  ctx.textAlign = 'left';
  ctx.fillText(legend.low, r.x + pad, endsY);
  ctx.textAlign = 'right';
  ctx.fillText(legend.high, r.x + r.w - pad, endsY);
  ctx.textAlign = 'left';
}

/** "dragon.off" -> "dragon-view.png". */
export function snapshotName(fileName: string): string {
  const dot = fileName.lastIndexOf('.');
  return `${dot > 0 ? fileName.slice(0, dot) : fileName || 'geoshift'}-view.png`;
}
