// Scene colours are linear; colour pickers speak sRGB hex. The exact
// IEC 61966-2-1 curve, as the server's PNG/JPEG encoding uses.

export function srgbEncode(linear) {
  const c = Math.min(1, Math.max(0, linear));
  return c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055;
}

export function srgbDecode(encoded) {
  const c = Math.min(1, Math.max(0, encoded));
  return c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4);
}

export function linearToHex(rgb) {
  return '#' + rgb.map((c) => Math.round(srgbEncode(c) * 255).toString(16).padStart(2, '0')).join('');
}

export function hexToLinear(hex) {
  const n = parseInt(hex.slice(1), 16);
  return [(n >> 16) & 255, (n >> 8) & 255, n & 255].map((v) => srgbDecode(v / 255));
}

export function linearToCss(rgb) {
  return `rgb(${rgb.map((c) => Math.round(srgbEncode(c) * 255)).join(',')})`;
}
