// penumbra's web viewer. The server owns rendering; the viewer owns the scene
// (scene JSON v1, the same format `penumbra render` reads) and sends it with
// every frame, so the server renders exactly what the controls show. See
// frame_scheduler.js for the preview / full-quality refinement.
import { api, ApiError } from './api.js';
import { orbit, pan, zoom } from './camera.js';
import { FrameScheduler } from './frame_scheduler.js';
import { LightPanel } from './light_panel.js';
import { TechniquePanel } from './technique_panel.js';
import { TransferFunctionEditor } from './tf_editor.js';
import { length, sub } from './vector.js';

const $ = (id) => document.getElementById(id);

const state = {
  session: null,
  scene: null,
  volume: null,     // dims, frames, histogram, ... of the session's volume
  size: Number(new URLSearchParams(location.search).get('size')) || 512,
  histogramStale: false,
};

// Read by the end-to-end test (tests/web): frames drawn, and whether the
// viewer has settled (no frame in flight or scheduled).
// spp / converged: the path-traced estimate last shown (0 for other
// techniques); reference: the same for the reference view.
const status = {
  frames: 0, fullFrames: 0, errors: 0, spp: 0, converged: false,
  reference: { frames: 0, spp: 0, converged: false },
  idle: () => scheduler.idle() && referenceScheduler.idle() && !busy,
  scene: () => state.scene,
};
window.penumbraViewer = status;
let busy = 0;  // requests other than frames in progress

const view = $('view');
const scheduler = new FrameScheduler(renderFrame);
const referenceScheduler = new FrameScheduler(renderReference);

function showError(error) {
  const box = $('error');
  if (!error) { box.hidden = true; return; }
  status.errors++;
  box.hidden = false;
  box.textContent = error.key ? `${error.key}: ${error.message}` : error.message;
}

async function withBusy(work) {
  busy++;
  try { return await work(); } catch (e) { showError(e); return null; } finally { busy--; }
}

// ---------------------------------------------------------------- frames

async function renderFrame(kind) {
  const preview = kind === 'preview';
  const width = preview ? Math.max(32, Math.round(state.size / 2)) : state.size;
  const request = { scene: state.scene, width, height: width, format: 'jpeg', quality: preview ? 70 : 90, preview };
  const started = performance.now();
  let frame;
  try {
    frame = await api.frame(state.session, request);
  } catch (e) {
    if (e instanceof ApiError && e.status === 409) return;  // superseded by a newer frame
    if (e instanceof ApiError && e.status === 404 && e.key === 'session') {
      await startSession(state.scene);  // expired: start again where we were
      scheduler.full();
      return;
    }
    showError(e);
    return;
  }
  const image = await createImageBitmap(frame.blob);
  const ctx = view.getContext('2d');
  ctx.imageSmoothingEnabled = true;
  ctx.drawImage(image, 0, 0, view.width, view.height);
  image.close();
  showError(null);
  status.frames++;
  if (!preview) status.fullFrames++;
  const total = performance.now() - started;
  status.spp = frame.spp;
  status.converged = frame.converged;
  const spp = frame.spp > 0 ? ` · ${frame.spp} spp${frame.converged ? ' (done)' : ''}` : '';
  $('frame-time').textContent =
    `${preview ? 'preview' : 'full'} ${width}² · ${frame.technique}${spp} · prepare ${frame.prepareMs.toFixed(1)} ms · ` +
    `render ${frame.renderMs.toFixed(1)} ms · encode ${frame.encodeMs.toFixed(1)} ms · round trip ${total.toFixed(0)} ms`;
  $('spp').textContent = frame.spp > 0 ? `${frame.spp} spp${frame.converged ? ' ✓' : ''}` : '';
  // A progressive estimate (pathtrace) keeps growing while nothing changes:
  // ask for the next frame until the server says it has converged (every
  // pixel met target_error, or max_total_spp).
  if (!preview && frame.spp > 0 && !frame.converged) scheduler.refine();
  if (!preview && state.histogramStale) {
    state.histogramStale = false;
    const info = await withBusy(() => api.volumeInfo(state.session));
    if (info) setVolumeInfo(info);
  }
}

// ---------------------------------------------------------------- the reference view
// "Reference" shows pathtrace of the same scene beside the technique, so the
// converging soft-shadow reference and the technique can be looked at side
// by side. It renders in a session of its own: a session keeps one scene,
// and the technique's frames would otherwise start pathtrace's estimate
// again each time. Its parameters are the technique panel's for pathtrace.
const reference = { on: false, session: null };

function referenceScene() {
  const scene = JSON.parse(JSON.stringify(state.scene));
  scene.render.technique = 'pathtrace';
  scene.render.params = techniques.paramsFor('pathtrace');
  return scene;
}

async function renderReference(kind) {
  if (!reference.on || !state.scene) return;
  const preview = kind === 'preview';
  const width = preview ? Math.max(32, Math.round(state.size / 2)) : state.size;
  const scene = referenceScene();
  let frame;
  try {
    if (!reference.session) reference.session = (await api.createSession(scene)).id;
    frame = await api.frame(reference.session, { scene, width, height: width, format: 'jpeg', quality: preview ? 70 : 90, preview });
  } catch (e) {
    if (e instanceof ApiError && e.status === 409) return;
    if (e instanceof ApiError && e.status === 404 && e.key === 'session') {
      reference.session = null;  // expired: the next frame starts another
      referenceScheduler.full();
      return;
    }
    showError(e);
    return;
  }
  const image = await createImageBitmap(frame.blob);
  const canvas = $('reference');
  canvas.getContext('2d').drawImage(image, 0, 0, canvas.width, canvas.height);
  image.close();
  status.reference = { frames: status.reference.frames + 1, spp: frame.spp, converged: frame.converged };
  $('reference-spp').textContent = `pathtrace · ${frame.spp} spp${frame.converged ? ' ✓' : ''}`;
  if (!preview && reference.on && !frame.converged) referenceScheduler.refine();
}

$('reference-toggle').addEventListener('change', () => {
  reference.on = $('reference-toggle').checked;
  $('reference-box').hidden = !reference.on;
  if (reference.on) referenceScheduler.full();
});

// Any edit: preview frames while it goes on, a full frame when it ends.
function changed(final) {
  if (final) {
    fullFrames();
  } else {
    scheduler.preview();
    if (reference.on) referenceScheduler.preview();
  }
}

// A full frame of the view and, when shown, of the reference.
function fullFrames() {
  scheduler.full();
  if (reference.on) referenceScheduler.full();
}

// ---------------------------------------------------------------- scene -> controls

function adopt(scene, volume) {
  state.scene = scene;
  if (volume) setVolumeInfo(volume);
  scene.render.width = scene.render.height = state.size;
  tfEditor.setPoints(scene.transfer_function.points);
  $('density-scale').value = Math.log10(scene.transfer_function.density_scale || 1);
  lights.setLights(scene.lights || []);
  techniques.setFromScene(scene.render);
  $('shading').value = scene.material.shading;
  $('ambient').value = scene.material.ambient;
  $('phase-g').value = scene.material.phase_g;
  $('step').value = scene.render.step;
  const source = scene.volume.file !== undefined ? scene.volume.file : `builtin:${scene.volume.builtin}`;
  $('volume-select').value = source;
  $('detail-time-row').hidden = animatedMeshes().length === 0;
  if (animatedMeshes().length === 0) $('animate-detail').checked = false;
  showDetailTime();
}

function setVolumeInfo(info) {
  state.volume = info;
  tfEditor.setHistogram(info.histogram ? info.histogram.counts : []);
  const frames = info.frames || 1;
  $('time-step-row').hidden = frames <= 1;
  $('time-step').max = frames - 1;
  $('time-step').value = info.time_step || 0;
  $('time-step-value').textContent = `${info.time_step || 0} / ${frames - 1}`;
  $('volume-info').textContent =
    `${info.dims.join('×')} ${info.voxel_type}, values ${info.value_range.map((v) => +v.toPrecision(4)).join('…')}`;
}

function viewInfo() {
  const box = state.volume ? state.volume.box : { min: [-1, -1, -1], max: [1, 1, 1] };
  return { camera: state.scene.camera, boxSize: length(sub(box.max, box.min)) };
}

// ---------------------------------------------------------------- controls

const tfEditor = new TransferFunctionEditor($('tf-canvas'), $('tf-color'), $('tf-point-value'), (points, final) => {
  state.scene.transfer_function.points = points.map((p) => p.slice());
  delete state.scene.transfer_function.preset;
  changed(final);
});

const lights = new LightPanel($('lights'), viewInfo, (list, final) => {
  state.scene.lights = JSON.parse(JSON.stringify(list));
  changed(final);
});
$('add-directional').addEventListener('click', () => lights.addLight('directional'));
$('add-point').addEventListener('click', () => lights.addLight('point'));

// pathtrace adds spp paths per pixel each frame while nothing changes, and a
// change waits for the frame in flight: 4 a frame instead of the CLI's 64
// keeps that wait short (apps/web/README.md has the times).
const VIEWER_DEFAULTS = { pathtrace: { spp: 4 } };

const techniques = new TechniquePanel($('technique-select'), $('technique-summary'), $('technique-params'),
  (name, params, final) => {
    state.scene.render.technique = name;
    state.scene.render.params = params;
    changed(final);
  });

function bindRange(id, apply) {
  const input = $(id);
  input.addEventListener('input', () => { apply(Number(input.value)); changed(false); });
  input.addEventListener('change', () => { apply(Number(input.value)); changed(true); });
}
bindRange('density-scale', (v) => { state.scene.transfer_function.density_scale = Math.pow(10, v); });
bindRange('ambient', (v) => { state.scene.material.ambient = v; });
bindRange('phase-g', (v) => { state.scene.material.phase_g = v; });
bindRange('step', (v) => { state.scene.render.step = v; });
bindRange('time-step', (v) => {
  state.scene.volume.time_step = v;
  $('time-step-value').textContent = `${v} / ${$('time-step').max}`;
  state.histogramStale = true;
});
$('shading').addEventListener('change', () => { state.scene.material.shading = $('shading').value; changed(true); });

// Animated mesh detail (Patel et al. 2013): while "Animate mesh detail" is
// on, every mesh whose detail has a time advances by DETAIL_TIME_STEP each
// time the last full frame is shown, the step `penumbra render --frames`
// takes by default.
const DETAIL_TIME_STEP = 0.04;
function animatedMeshes() {
  return ((state.scene && state.scene.meshes) || []).filter((m) => m.material && m.material.detail &&
                                                                   m.material.detail.time !== undefined);
}
function showDetailTime() {
  const meshes = animatedMeshes();
  $('detail-time-value').textContent = meshes.length ? `t = ${meshes[0].material.detail.time.toFixed(2)}` : '';
}
let animationTimer = null;
function animateDetail() {
  animationTimer = null;
  if (!$('animate-detail').checked || animatedMeshes().length === 0) return;
  if (scheduler.idle() && !busy) {
    for (const m of animatedMeshes()) m.material.detail.time += DETAIL_TIME_STEP;
    showDetailTime();
    fullFrames();
  }
  animationTimer = setTimeout(animateDetail, 20);
}
$('animate-detail').addEventListener('change', () => {
  if ($('animate-detail').checked && animationTimer === null) animateDetail();
});

if (![...$('size-select').options].some((o) => o.value === String(state.size))) {
  $('size-select').append(Object.assign(document.createElement('option'), { textContent: String(state.size) }));
}
$('size-select').value = String(state.size);
function applySize() {
  view.width = view.height = state.size;
  $('reference').width = $('reference').height = state.size;
  if (state.scene) state.scene.render.width = state.scene.render.height = state.size;
}
applySize();
$('size-select').addEventListener('change', () => {
  state.size = Number($('size-select').value);
  applySize();
  changed(true);
});

$('volume-select').addEventListener('change', () => withBusy(async () => {
  const value = $('volume-select').value;
  const volume = value.startsWith('builtin:') ? { builtin: value.slice(8), size: [96, 96, 96] } : { file: value };
  const reply = await api.loadVolume(state.session, volume);
  adopt(reply.scene, reply.volume);
  fullFrames();
}));

// ParaView presets: the server converts them (io/paraview_preset.h) so the
// viewer and `penumbra render` agree on what a preset means.
let presetText = '';
async function applyPreset(name) {
  const reply = await api.convertPreset(presetText, name);
  state.scene.transfer_function.points = reply.transfer_function.points;
  state.scene.transfer_function.range = 'data';
  tfEditor.setPoints(reply.transfer_function.points);
  state.histogramStale = true;
  changed(true);
}
$('preset-file').addEventListener('change', () => withBusy(async () => {
  const file = $('preset-file').files[0];
  if (!file) return;
  presetText = await file.text();
  let names = [];
  try {
    const parsed = JSON.parse(presetText);
    names = (Array.isArray(parsed) ? parsed : [parsed]).filter((p) => p && p.RGBPoints).map((p) => p.Name || '');
  } catch (e) { /* the server reports what is wrong with it */ }
  const select = $('preset-name');
  select.replaceChildren(...names.map((n) => Object.assign(document.createElement('option'), { value: n, textContent: n })));
  select.hidden = names.length < 2;
  await applyPreset(names[0] || '');
}));
$('preset-name').addEventListener('change', () => withBusy(() => applyPreset($('preset-name').value)));

function download(name, blob) {
  const link = document.createElement('a');
  link.href = URL.createObjectURL(blob);
  link.download = name;
  link.click();
  setTimeout(() => URL.revokeObjectURL(link.href), 1000);
}
$('save-image').addEventListener('click', () => withBusy(async () => {
  const frame = await api.frame(state.session, { scene: state.scene, width: state.size, height: state.size, format: 'png' });
  download('penumbra.png', frame.blob);
}));
$('save-scene').addEventListener('click', () => {
  download('scene.json', new Blob([JSON.stringify(state.scene, null, 2)], { type: 'application/json' }));
});
$('load-scene').addEventListener('change', () => withBusy(async () => {
  const file = $('load-scene').files[0];
  if (!file) return;
  const reply = await api.putScene(state.session, JSON.parse(await file.text()));
  adopt(reply.scene, reply.volume);
  fullFrames();
}));

// ---------------------------------------------------------------- mouse on the view

let drag = null;
view.addEventListener('contextmenu', (e) => e.preventDefault());
view.addEventListener('pointerdown', (e) => {
  drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
  view.setPointerCapture(e.pointerId);
});
view.addEventListener('pointermove', (e) => {
  if (!drag || !state.scene) return;
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  drag.x = e.clientX;
  drag.y = e.clientY;
  // The image is square and fitted into the canvas box (object-fit: contain).
  const rect = view.getBoundingClientRect();
  state.scene.camera = drag.pan ? pan(state.scene.camera, dx, dy, Math.min(rect.width, rect.height))
                                : orbit(state.scene.camera, dx, dy);
  lights.refresh();
  changed(false);
});
view.addEventListener('pointerup', (e) => {
  if (!drag) return;
  drag = null;
  view.releasePointerCapture(e.pointerId);
  changed(true);
});
view.addEventListener('wheel', (e) => {
  e.preventDefault();
  if (!state.scene) return;
  state.scene.camera = zoom(state.scene.camera, e.deltaY);
  changed(false);
}, { passive: false });

// ---------------------------------------------------------------- start

async function startSession(scene) {
  const reply = await api.createSession(scene);
  state.session = reply.id;
  $('session-label').textContent = `session ${reply.id.slice(0, 8)}`;
  adopt(reply.scene, reply.volume);
}

async function start() {
  const [techniqueList, volumes] = await Promise.all([api.techniques(), api.volumes()]);
  techniques.setTechniques(techniqueList.techniques, VIEWER_DEFAULTS);
  const select = $('volume-select');
  for (const f of volumes.files) {
    select.append(Object.assign(document.createElement('option'), { value: f.path, textContent: f.path }));
  }
  for (const b of volumes.builtins) {
    select.append(Object.assign(document.createElement('option'),
      { value: `builtin:${b.name}`, textContent: `builtin: ${b.name}`, title: b.doc }));
  }
  await startSession(null);
  fullFrames();
}

withBusy(start);
