// The light list: add and remove directional and point lights, set colour
// and intensity, and drag where a light comes from on a sphere gizmo. The
// gizmo shows the sphere of directions as the camera sees it: the dot is the
// direction toward the light (a filled dot on the front hemisphere, a ring
// behind). Dragging puts the light in front; with shift held, behind.
// A point light keeps its distance from the camera target while it moves.
// Each light has a size, which every technique's softness follows: the
// angle of a light at infinity (a distant light's angle_deg, in degrees) or
// the radius of a light at a position (world units). A size above 0 turns a
// directional light into a distant one and a point light into a sphere, and
// back at 0 (the limits of those lights as the size goes to 0:
// src/penumbra/scene/light.h).
import { hexToLinear, linearToHex } from './color.js';
import { add, dot, length, normalize, scale, sub } from './vector.js';
import { cameraFrame } from './camera.js';

const GIZMO = 96;

// Sets a light's size in place (see the top of the file): angle_deg of a
// light at infinity, radius of one at a position; directional <-> distant
// and point <-> sphere as the size leaves or reaches 0. A gaussian or
// anisotropic distant light stays distant.
export function setLightSize(light, size) {
  if (light.type === 'directional' || light.type === 'distant') {
    const plain = !light.profile || light.profile === 'uniform';
    if (size > 0 || !plain) {
      light.type = 'distant';
      light.angle_deg = size;
    } else {
      light.type = 'directional';
      delete light.angle_deg;
      delete light.profile;
    }
  } else if (light.type === 'point' || light.type === 'sphere') {
    if (size > 0) {
      light.type = 'sphere';
      light.radius = size;
    } else {
      light.type = 'point';
      delete light.radius;
    }
  } else if (light.type === 'disk') {
    light.radius = size;
  }
}

export class LightPanel {
  // getView() -> {camera, boxSize}; onChange(lights, final).
  constructor(container, getView, onChange) {
    this.container = container;
    this.getView = getView;
    this.onChange = onChange;
    this.lights = [];
  }

  setLights(lights) {
    this.lights = lights.map((l) => JSON.parse(JSON.stringify(l)));
    this.build();
  }

  // The direction toward light i, as a unit vector.
  towardLight(light) {
    const { camera } = this.getView();
    if (light.type === 'point' || light.type === 'sphere' || light.type === 'disk') {
      return normalize(sub(light.position, camera.target));
    }
    return normalize(scale(light.direction || [0, 0, -1], -1));
  }

  addLight(type) {
    const { camera, boxSize } = this.getView();
    const f = cameraFrame(camera);
    const toward = normalize(add(add(scale(f.right, -0.5), scale(f.up, 0.6)), scale(f.toViewer, 0.6)));
    if (type === 'point') {
      const distance = boxSize;
      const position = add(camera.target, scale(toward, distance));
      // Units (docs/scene-format.md): intensity d^2 matches a directional light of 1.
      this.lights.push({ type: 'point', position, color: [1, 1, 1], intensity: distance * distance });
    } else {
      this.lights.push({ type: 'directional', direction: scale(toward, -1), color: [1, 1, 1], intensity: 1 });
    }
    this.build();
    this.onChange(this.lights, true);
  }

  build() {
    this.container.replaceChildren();
    this.lights.forEach((light, index) => this.container.append(this.lightElement(light, index)));
  }

  lightElement(light, index) {
    const box = document.createElement('div');
    box.className = 'light';
    box.dataset.index = index;
    const gizmo = document.createElement('canvas');
    gizmo.width = GIZMO;
    gizmo.height = GIZMO;
    gizmo.className = 'light-gizmo';
    gizmo.title = 'drag to move the light (shift: behind)';
    box.append(gizmo);

    const title = document.createElement('div');
    title.className = 'title';
    title.innerHTML = `<span class="light-type">${light.type} light</span>`;
    const remove = document.createElement('button');
    remove.type = 'button';
    remove.textContent = '×';
    remove.title = 'remove this light';
    remove.addEventListener('click', () => {
      this.lights.splice(index, 1);
      this.build();
      this.onChange(this.lights, true);
    });
    title.append(remove);
    box.append(title);

    const color = document.createElement('input');
    color.type = 'color';
    color.value = linearToHex(light.color || [1, 1, 1]);
    const setColor = (final) => { light.color = hexToLinear(color.value); this.onChange(this.lights, final); };
    color.addEventListener('input', () => setColor(false));
    color.addEventListener('change', () => setColor(true));
    const colorLabel = document.createElement('label');
    colorLabel.append('Colour ', color);
    box.append(colorLabel);

    // Intensity on a slider up to 4x the level that lights the volume like a
    // unit directional light (d^2 for a point light at distance d).
    const base = light.type === 'directional' || light.type === 'distant' ? 1
      : Math.max(1e-6, Math.pow(length(sub(light.position, this.getView().camera.target)), 2));
    const intensity = document.createElement('input');
    intensity.type = 'range';
    intensity.min = 0;
    intensity.max = 4;
    intensity.step = 0.01;
    intensity.value = (light.intensity ?? 1) / base;
    intensity.className = 'light-intensity';
    const intensityLabel = document.createElement('label');
    const readout = document.createElement('span');
    readout.className = 'muted';
    readout.textContent = ` ${(light.intensity ?? 1).toPrecision(3)}`;
    const setIntensity = (final) => {
      light.intensity = Number(intensity.value) * base;
      readout.textContent = ` ${light.intensity.toPrecision(3)}`;
      this.onChange(this.lights, final);
    };
    intensity.addEventListener('input', () => setIntensity(false));
    intensity.addEventListener('change', () => setIntensity(true));
    intensityLabel.append('Intensity', readout, intensity);
    box.append(intensityLabel);
    const size = this.sizeElement(light, title.querySelector('.light-type'));
    if (size) box.append(size);

    this.attachGizmo(gizmo, light);
    this.drawGizmo(gizmo, light);
    return box;
  }

  // The size slider and number, or null for a light without one (environment).
  sizeElement(light, typeLabel) {
    const atInfinity = ['directional', 'distant'].includes(light.type);
    if (!atInfinity && !['point', 'sphere', 'disk'].includes(light.type)) return null;
    // Degrees up to 20 (a 40-degree-wide cone); radii up to a quarter of the
    // volume's diagonal. The number field takes any value the server accepts.
    const max = atInfinity ? 20 : Math.max(1e-3, this.getView().boxSize / 4);
    const current = () => (atInfinity ? light.angle_deg : light.radius) || 0;
    const slider = document.createElement('input');
    slider.type = 'range';
    slider.min = 0;
    slider.max = max;
    slider.step = atInfinity ? 0.1 : max / 200;
    slider.className = 'light-size';
    const number = document.createElement('input');
    number.type = 'number';
    number.min = 0;
    number.step = 'any';
    number.className = 'light-size-value';
    const show = () => {
      slider.value = Math.min(max, current());
      number.value = +current().toPrecision(4);
    };
    show();
    const apply = (value, final) => {
      if (!Number.isFinite(value) || value < 0) return;  // the field shows what is wrong until fixed
      setLightSize(light, value);
      typeLabel.textContent = `${light.type} light`;
      this.onChange(this.lights, final);
    };
    slider.addEventListener('input', () => { apply(Number(slider.value), false); number.value = +current().toPrecision(4); });
    slider.addEventListener('change', () => apply(Number(slider.value), true));
    number.addEventListener('change', () => { apply(Number(number.value), true); show(); });
    const label = document.createElement('label');
    label.title = atInfinity ? 'the angular radius of the light (a cone half-angle, or the standard deviation of a gaussian light)'
      : 'the radius of the light, in world units';
    label.append(atInfinity ? 'Size (degrees) ' : 'Size (radius) ', number, slider);
    return label;
  }

  attachGizmo(gizmo, light) {
    if (!['directional', 'distant', 'point', 'sphere', 'disk'].includes(light.type)) return;
    let dragging = false;
    const update = (e, final) => {
      const rect = gizmo.getBoundingClientRect();
      let x = ((e.clientX - rect.left) / rect.width) * 2 - 1;
      let y = 1 - ((e.clientY - rect.top) / rect.height) * 2;
      const r = Math.hypot(x, y);
      if (r > 1) { x /= r; y /= r; }
      const z = Math.sqrt(Math.max(0, 1 - x * x - y * y)) * (e.shiftKey ? -1 : 1);
      const { camera } = this.getView();
      const f = cameraFrame(camera);
      const toward = normalize(add(add(scale(f.right, x), scale(f.up, y)), scale(f.toViewer, z)));
      if (light.type === 'point' || light.type === 'sphere' || light.type === 'disk') {
        const distance = length(sub(light.position, camera.target));
        light.position = add(camera.target, scale(toward, distance));
      } else {
        light.direction = scale(toward, -1);
      }
      this.drawGizmo(gizmo, light);
      this.onChange(this.lights, final);
    };
    gizmo.addEventListener('pointerdown', (e) => {
      dragging = true;
      gizmo.setPointerCapture(e.pointerId);
      update(e, false);
    });
    gizmo.addEventListener('pointermove', (e) => { if (dragging) update(e, false); });
    gizmo.addEventListener('pointerup', (e) => {
      if (!dragging) return;
      dragging = false;
      gizmo.releasePointerCapture(e.pointerId);
      update(e, true);
    });
  }

  drawGizmo(gizmo, light) {
    const ctx = gizmo.getContext('2d');
    const c = GIZMO / 2, r = GIZMO / 2 - 4;
    ctx.clearRect(0, 0, GIZMO, GIZMO);
    const shade = ctx.createRadialGradient(c - r / 3, c - r / 3, r / 8, c, c, r);
    shade.addColorStop(0, '#5b6275');
    shade.addColorStop(1, '#22252d');
    ctx.fillStyle = shade;
    ctx.beginPath();
    ctx.arc(c, c, r, 0, 2 * Math.PI);
    ctx.fill();
    const f = cameraFrame(this.getView().camera);
    const toward = this.towardLight(light);
    const x = c + dot(toward, f.right) * r, y = c - dot(toward, f.up) * r;
    const front = dot(toward, f.toViewer) >= 0;
    ctx.beginPath();
    ctx.arc(x, y, 6, 0, 2 * Math.PI);
    ctx.strokeStyle = '#ffd070';
    ctx.lineWidth = 2;
    if (front) { ctx.fillStyle = '#ffd070'; ctx.fill(); }
    ctx.stroke();
  }

  // Redraws the gizmos after the camera moved (directions are shown in view space).
  refresh() {
    this.container.querySelectorAll('.light').forEach((box) => {
      const light = this.lights[Number(box.dataset.index)];
      if (light) this.drawGizmo(box.querySelector('canvas'), light);
    });
  }
}
