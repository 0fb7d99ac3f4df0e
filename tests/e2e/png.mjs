// Minimal PNG decoder for Playwright screenshots (8-bit RGB/RGBA, not interlaced), so tests can
// look at pixels without an image package. Also small image statistics used by the tests.
import { inflateSync } from 'node:zlib';

/** Decodes a PNG buffer into { width, height, data } with data as RGBA bytes. */
export function decodePng(buffer) {
  if (buffer.readUInt32BE(0) !== 0x89504e47) throw new Error('not a PNG');
  let offset = 8;
  let width = 0, height = 0, colorType = 0;
  const idat = [];
  while (offset < buffer.length) {
    const length = buffer.readUInt32BE(offset);
    const type = buffer.toString('ascii', offset + 4, offset + 8);
    const body = buffer.subarray(offset + 8, offset + 8 + length);
    if (type === 'IHDR') {
      width = body.readUInt32BE(0);
      height = body.readUInt32BE(4);
      const bitDepth = body[8];
      colorType = body[9];
      if (bitDepth !== 8 || (colorType !== 2 && colorType !== 6) || body[12] !== 0) {
        throw new Error(`unsupported PNG (bit depth ${bitDepth}, color type ${colorType}, interlace ${body[12]})`);
      }
    } else if (type === 'IDAT') idat.push(body);
    else if (type === 'IEND') break;
    offset += 12 + length;
  }
  const channels = colorType === 6 ? 4 : 3;
  const raw = inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const pixels = Buffer.alloc(stride * height);
  for (let y = 0; y < height; y++) {
    const filter = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; x++) {
      const a = x >= channels ? pixels[y * stride + x - channels] : 0;
      const b = y > 0 ? pixels[(y - 1) * stride + x] : 0;
      const c = x >= channels && y > 0 ? pixels[(y - 1) * stride + x - channels] : 0;
      let v = line[x];
      if (filter === 1) v += a;
      else if (filter === 2) v += b;
      else if (filter === 3) v += (a + b) >> 1;
      else if (filter === 4) {
        const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
        v += pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      pixels[y * stride + x] = v & 0xff;
    }
  }
  const data = Buffer.alloc(width * height * 4);
  for (let i = 0; i < width * height; i++) {
    data[4 * i] = pixels[channels * i];
    data[4 * i + 1] = pixels[channels * i + 1];
    data[4 * i + 2] = pixels[channels * i + 2];
    data[4 * i + 3] = channels === 4 ? pixels[channels * i + 3] : 255;
  }
  return { width, height, data };
}

function pixel(image, x, y) {
  const i = 4 * (y * image.width + x);
  return [image.data[i], image.data[i + 1], image.data[i + 2]];
}

function differs(p, q, threshold) {
  return Math.abs(p[0] - q[0]) + Math.abs(p[1] - q[1]) + Math.abs(p[2] - q[2]) > threshold;
}

/**
 * What a screenshot of the 3D view shows: the background (top-left pixel), how many distinct colours
 * (4 bits per channel), the box around pixels that differ from the background, and how colourful
 * the differing pixels are.
 */
export function analyze(image) {
  const background = pixel(image, 0, 0);
  const colours = new Set();
  let minX = image.width, minY = image.height, maxX = -1, maxY = -1, covered = 0, saturated = 0;
  for (let y = 0; y < image.height; y++) {
    for (let x = 0; x < image.width; x++) {
      const p = pixel(image, x, y);
      colours.add(((p[0] >> 4) << 8) | ((p[1] >> 4) << 4) | (p[2] >> 4));
      if (!differs(p, background, 24)) continue;
      covered++;
      if (Math.max(...p) - Math.min(...p) > 80) saturated++;
      minX = Math.min(minX, x); maxX = Math.max(maxX, x);
      minY = Math.min(minY, y); maxY = Math.max(maxY, y);
    }
  }
  const box = maxX < 0 ? null : {
    centreX: (minX + maxX) / 2 / image.width,
    centreY: (minY + maxY) / 2 / image.height,
    width: (maxX - minX + 1) / image.width,
    height: (maxY - minY + 1) / image.height,
  };
  return {
    background,
    distinctColours: colours.size,
    coverage: covered / (image.width * image.height),
    saturatedFraction: covered ? saturated / covered : 0,
    box,
  };
}

/** Fraction of the non-background pixels whose channels spread by more than `spread` (0..255). */
export function colourfulFraction(image, spread = 40) {
  const background = pixel(image, 0, 0);
  let covered = 0, colourful = 0;
  for (let y = 0; y < image.height; y++) {
    for (let x = 0; x < image.width; x++) {
      const p = pixel(image, x, y);
      if (!differs(p, background, 24)) continue;
      covered++;
      if (Math.max(...p) - Math.min(...p) > spread) colourful++;
    }
  }
  return covered ? colourful / covered : 0;
}

/** Fraction of pixels that differ noticeably between two same-sized images. */
export function differenceFraction(a, b) {
  if (a.width !== b.width || a.height !== b.height) return 1;
  let changed = 0;
  for (let y = 0; y < a.height; y++) {
    for (let x = 0; x < a.width; x++) if (differs(pixel(a, x, y), pixel(b, x, y), 30)) changed++;
  }
  return changed / (a.width * a.height);
}
