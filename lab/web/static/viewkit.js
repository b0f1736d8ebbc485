// What the views that draw images share: float renders shown as sRGB pictures and read
// back top row first (views/*.js, exercise.js).

/** Linear RGB(A) floats (rows from the bottom) -> an sRGB ImageData (rows from the top),
 * times 2^exposure and clamped, as the spheres are shown. */
export function toImage(floats, width, height, exposure) {
  const image = new ImageData(width, height);
  const scale = Math.pow(2, exposure);
  const srgb = (c) => {
    c = Math.min(Math.max(c * scale, 0), 1) || 0;
    return 255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055);
  };
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const i = 4 * ((height - 1 - y) * width + x);
      const o = 4 * (y * width + x);
      const alpha = floats[i + 3];
      for (let c = 0; c < 3; c++) image.data[o + c] = Math.round(srgb(floats[i + c]) * alpha);
      image.data[o + 3] = Math.round(255 * alpha);
    }
  }
  return image;
}

/** Rows flipped so that row 0 is the top (what a test compares with the desktop). */
export function topFirst(floats, width, height) {
  const out = new Float32Array(floats.length);
  const row = 4 * width;
  for (let y = 0; y < height; y++) out.set(floats.subarray(y * row, (y + 1) * row), (height - 1 - y) * row);
  return out;
}
