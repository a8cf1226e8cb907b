// Transfer-function editor: control points [value, r, g, b, alpha] over the
// histogram of the volume (log counts, binned over the TF range, so x is the
// normalised TF value). Drag a point to move it (value between its
// neighbours, alpha up and down); click empty space to add one with the
// colour the TF has there; double-click a point to remove it; the colour
// picker edits the selected point.
import { hexToLinear, linearToCss, linearToHex } from './color.js';

const RADIUS = 6;
const STRIP = 14;  // colour strip under the plot, pixels

export class TransferFunctionEditor {
  // onChange(points, final): final is false while dragging.
  constructor(canvas, colorInput, readout, onChange) {
    this.canvas = canvas;
    this.colorInput = colorInput;
    this.readout = readout;
    this.onChange = onChange;
    this.points = [[0, 0, 0, 0, 0], [1, 1, 1, 1, 1]];
    this.counts = [];
    this.selected = -1;
    this.dragging = -1;
    canvas.addEventListener('pointerdown', (e) => this.pointerDown(e));
    canvas.addEventListener('pointermove', (e) => this.pointerMove(e));
    canvas.addEventListener('pointerup', (e) => this.pointerUp(e));
    canvas.addEventListener('dblclick', (e) => this.doubleClick(e));
    colorInput.addEventListener('input', () => this.setSelectedColor(false));
    colorInput.addEventListener('change', () => this.setSelectedColor(true));
  }

  setPoints(points) {
    this.points = points.map((p) => p.slice()).sort((a, b) => a[0] - b[0]);
    this.selected = Math.min(this.selected, this.points.length - 1);
    this.draw();
  }

  setHistogram(counts) {
    this.counts = counts || [];
    this.draw();
  }

  // Plot coordinates: x in [0, 1] over the width, alpha in [0, 1] over the
  // height above the colour strip.
  plotHeight() { return this.canvas.height - STRIP; }
  toCanvas(p) { return [p[0] * this.canvas.width, (1 - p[4]) * (this.plotHeight() - 2 * RADIUS) + RADIUS]; }
  fromEvent(e) {
    const rect = this.canvas.getBoundingClientRect();
    const x = ((e.clientX - rect.left) / rect.width) * this.canvas.width;
    const y = ((e.clientY - rect.top) / rect.height) * this.canvas.height;
    const value = Math.min(1, Math.max(0, x / this.canvas.width));
    const alpha = Math.min(1, Math.max(0, 1 - (y - RADIUS) / (this.plotHeight() - 2 * RADIUS)));
    return { x, y, value, alpha };
  }

  pointAt(x, y) {
    let best = -1, bestDistance = 2 * RADIUS;
    this.points.forEach((p, i) => {
      const [px, py] = this.toCanvas(p);
      const d = Math.hypot(px - x, py - y);
      if (d < bestDistance) { best = i; bestDistance = d; }
    });
    return best;
  }

  // The TF's colour at a value (piecewise linear, clamped at the ends).
  colorAt(value) {
    const pts = this.points;
    if (value <= pts[0][0]) return pts[0].slice(1, 4);
    for (let i = 1; i < pts.length; i++) {
      if (value <= pts[i][0]) {
        const t = (value - pts[i - 1][0]) / Math.max(1e-9, pts[i][0] - pts[i - 1][0]);
        return [1, 2, 3].map((c) => pts[i - 1][c] * (1 - t) + pts[i][c] * t);
      }
    }
    return pts[pts.length - 1].slice(1, 4);
  }

  pointerDown(e) {
    if (e.button !== 0) return;
    const { x, y, value, alpha } = this.fromEvent(e);
    let index = this.pointAt(x, y);
    if (index < 0) {
      this.points.push([value, ...this.colorAt(value), alpha]);
      this.points.sort((a, b) => a[0] - b[0]);
      index = this.points.findIndex((p) => p[0] === value && p[4] === alpha);
    }
    this.selected = index;
    this.dragging = index;
    this.canvas.setPointerCapture(e.pointerId);
    this.draw();
    this.onChange(this.points, false);
  }

  pointerMove(e) {
    if (this.dragging < 0) return;
    const { value, alpha } = this.fromEvent(e);
    const i = this.dragging;
    const lo = i > 0 ? this.points[i - 1][0] : 0;
    const hi = i < this.points.length - 1 ? this.points[i + 1][0] : 1;
    this.points[i][0] = Math.min(hi, Math.max(lo, value));
    this.points[i][4] = alpha;
    this.draw();
    this.onChange(this.points, false);
  }

  pointerUp(e) {
    if (this.dragging < 0) return;
    this.dragging = -1;
    this.canvas.releasePointerCapture(e.pointerId);
    this.onChange(this.points, true);
  }

  doubleClick(e) {
    const { x, y } = this.fromEvent(e);
    const index = this.pointAt(x, y);
    if (index < 0 || this.points.length <= 2) return;
    this.points.splice(index, 1);
    this.selected = -1;
    this.draw();
    this.onChange(this.points, true);
  }

  setSelectedColor(final) {
    if (this.selected < 0) return;
    const rgb = hexToLinear(this.colorInput.value);
    this.points[this.selected].splice(1, 3, ...rgb);
    this.draw();
    this.onChange(this.points, final);
  }

  draw() {
    const ctx = this.canvas.getContext('2d');
    const w = this.canvas.width, h = this.plotHeight();
    ctx.clearRect(0, 0, w, this.canvas.height);
    // Histogram, log(1 + count) so that small features show next to the peak.
    if (this.counts.length) {
      const logs = this.counts.map((c) => Math.log1p(c));
      const top = Math.max(...logs) || 1;
      ctx.fillStyle = '#3a4050';
      const bw = w / logs.length;
      logs.forEach((l, i) => {
        const bh = (l / top) * h;
        ctx.fillRect(i * bw, h - bh, Math.ceil(bw), bh);
      });
    }
    // Colour strip.
    for (let x = 0; x < w; x++) {
      ctx.fillStyle = linearToCss(this.colorAt(x / w));
      ctx.fillRect(x, h, 1, STRIP);
    }
    // Opacity polyline and points.
    ctx.strokeStyle = '#e0e4ee';
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    this.points.forEach((p, i) => {
      const [x, y] = this.toCanvas(p);
      if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
    });
    ctx.stroke();
    this.points.forEach((p, i) => {
      const [x, y] = this.toCanvas(p);
      ctx.beginPath();
      ctx.arc(x, y, RADIUS, 0, 2 * Math.PI);
      ctx.fillStyle = linearToCss(p.slice(1, 4));
      ctx.fill();
      ctx.strokeStyle = i === this.selected ? '#e0a050' : '#000';
      ctx.lineWidth = i === this.selected ? 2.5 : 1;
      ctx.stroke();
    });
    if (this.selected >= 0) {
      const p = this.points[this.selected];
      this.colorInput.value = linearToHex(p.slice(1, 4));
      this.readout.textContent = `value ${p[0].toFixed(3)} · alpha ${p[4].toFixed(3)}`;
    } else {
      this.readout.textContent = '';
    }
  }
}
