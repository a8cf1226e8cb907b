// End-to-end test of the web viewer: `penumbra serve` on a free port, the
// viewer in headless Chromium, and the interactions of the issue: the engine
// CT is shown, the technique is switched (its controls come from the
// parameter table), a light is dragged on its gizmo and a TF point is moved,
// a light's size is set, pathtrace converges progressively, and the
// reference is shown beside the technique.
// After each, the canvas must have changed, and no console error may occur.
// A screenshot goes to OUTPUT_DIR/viewer.png.
// Usage: node e2e.mjs PENUMBRA_BINARY DATA_DIR OUTPUT_DIR (see run_e2e.sh)
import { spawn } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

const [penumbra, dataDir, outDir] = process.argv.slice(2);
const SIZE = 192;           // render size: small, for CI time
const STEP_TIMEOUT = 30000; // ms for the viewer to settle after an action
const started = Date.now();
const log = (message) => console.log(`[${((Date.now() - started) / 1000).toFixed(1)} s] ${message}`);

let failures = 0;
function check(condition, message) {
  if (condition) { log(`ok: ${message}`); return; }
  failures++;
  log(`FAIL: ${message}`);
}

// ---------------------------------------------------------------- server

function startServer() {
  const child = spawn(penumbra, ['--threads', '2', 'serve', '--port', '0', '--data', dataDir],
                      { stdio: ['ignore', 'pipe', 'inherit'] });
  return new Promise((resolve, reject) => {
    let text = '';
    const timer = setTimeout(() => reject(new Error(`no address from penumbra serve: ${text}`)), 20000);
    child.stdout.on('data', (chunk) => {
      text += chunk;
      const match = text.match(/http:\/\/[\d.]+:(\d+)\//);
      if (match) { clearTimeout(timer); resolve({ child, url: match[0] }); }
    });
    child.on('exit', (code) => reject(new Error(`penumbra serve exited (${code}): ${text}`)));
  });
}

// ---------------------------------------------------------------- page helpers

async function settled(page, what) {
  await page.waitForFunction(() => window.penumbraViewer && window.penumbraViewer.fullFrames > 0 &&
                                   window.penumbraViewer.idle(), null, { timeout: STEP_TIMEOUT, polling: 50 });
  log(`settled: ${what}`);
}

// The canvas shrunk to 64x64 in the page (enough to see any change, and fast
// to hand over), as 8-bit RGBA.
const canvasPixels = (page) => page.evaluate(() => {
  const small = document.createElement('canvas');
  small.width = small.height = 64;
  const ctx = small.getContext('2d');
  ctx.drawImage(document.getElementById('view'), 0, 0, 64, 64);
  return Array.from(ctx.getImageData(0, 0, 64, 64).data);
});

// Mean absolute difference per colour channel, in 8-bit codes. A change below
// half a code on average would be invisible; every step here changes much more.
function difference(a, b) {
  let sum = 0;
  for (let i = 0; i < a.length; i++) if (i % 4 !== 3) sum += Math.abs(a[i] - b[i]);
  return sum / (a.length * 0.75);
}

const meanLevel = (pixels) => difference(pixels, new Array(pixels.length).fill(0));

async function drag(page, from, to, steps = 8) {
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let i = 1; i <= steps; i++) {
    await page.mouse.move(from.x + (to.x - from.x) * i / steps, from.y + (to.y - from.y) * i / steps);
    await page.waitForTimeout(30);
  }
  await page.mouse.up();
}

// ---------------------------------------------------------------- the test

async function run() {
  const { child, url } = await startServer();
  log(`server at ${url}`);
  const profile = mkdtempSync(join(tmpdir(), 'penumbra-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    viewport: { width: 1100, height: 800 },
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
           '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const consoleErrors = [];
  try {
    const page = context.pages()[0] || await context.newPage();
    page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
    page.on('pageerror', (e) => consoleErrors.push(String(e)));

    await page.goto(`${url}?size=${SIZE}`);
    await settled(page, 'first frame');

    // 1. The engine CT, as the server's initial scene.
    check(await page.inputValue('#volume-select') === 'engine_256x256x128_uint8.nhdr', 'the engine CT is selected');
    check((await page.textContent('#volume-info')).includes('256×256×128'), 'the volume info shows 256×256×128');
    let before = await canvasPixels(page);
    check(meanLevel(before) > 5, `the first frame is not black (mean level ${meanLevel(before).toFixed(1)})`);

    // 2. Switch the technique; its controls come from the parameter table.
    // filtered-sat (Ament et al.) with its softness slider when the engine
    // has it, else the first other technique with parameters.
    const table = await (await page.request.get(`${url}api/techniques`)).json();
    const next = table.techniques.find((t) => t.name === 'filtered-sat') ||
                 table.techniques.find((t) => t.name !== 'shadow-rays' && t.parameters.length > 0);
    await page.selectOption('#technique-select', next.name);
    await settled(page, `technique ${next.name}`);
    let after = await canvasPixels(page);
    check(difference(before, after) > 0.5, `switching to ${next.name} changed the canvas (by ${difference(before, after).toFixed(2)})`);
    check(await page.locator('#technique-params .param').count() === next.parameters.length,
          `${next.parameters.length} controls for ${next.name}'s parameters`);
    check((await page.evaluate(() => window.penumbraViewer.scene().render.technique)) === next.name, 'the scene names the technique');
    const slider = next.parameters.find((p) => p.name === 'filter_voxels') ||
                   next.parameters.find((p) => p.type === 'float');
    if (slider) {
      before = after;
      const value = slider.min + (slider.max - slider.min) * 0.1;
      await page.locator(`#technique-params .param[data-name="${slider.name}"] input`).evaluate((input, v) => {
        input.value = v;
        input.dispatchEvent(new Event('input', { bubbles: true }));
        input.dispatchEvent(new Event('change', { bubbles: true }));
      }, value);
      await settled(page, `${slider.name} = ${value}`);
      after = await canvasPixels(page);
      const sent = await page.evaluate((name) => window.penumbraViewer.scene().render.params[name], slider.name);
      check(Math.abs(sent - value) < 1e-6 * Math.max(1, value), `the scene carries ${slider.name} = ${sent}`);
      check(difference(before, after) > 0.5, `moving ${slider.name} changed the canvas (by ${difference(before, after).toFixed(2)})`);
    }

    // 3. Drag the first light on its sphere gizmo.
    const directionBefore = await page.evaluate(() => JSON.stringify(window.penumbraViewer.scene().lights[0]));
    const gizmo = await page.locator('.light-gizmo').first().boundingBox();
    before = after;
    await drag(page, { x: gizmo.x + gizmo.width * 0.5, y: gizmo.y + gizmo.height * 0.5 },
                     { x: gizmo.x + gizmo.width * 0.85, y: gizmo.y + gizmo.height * 0.2 });
    await settled(page, 'light drag');
    after = await canvasPixels(page);
    const directionAfter = await page.evaluate(() => JSON.stringify(window.penumbraViewer.scene().lights[0]));
    check(directionAfter !== directionBefore, 'the light moved');
    check(difference(before, after) > 0.5, `dragging the light changed the canvas (by ${difference(before, after).toFixed(2)})`);

    // 4. Move a TF point down to a quarter of its alpha.
    const tf = await page.evaluate(() => {
      const canvas = document.getElementById('tf-canvas');
      const rect = canvas.getBoundingClientRect();
      const points = window.penumbraViewer.scene().transfer_function.points;
      // The most opaque point away from the ends (those sit on the canvas edges).
      let k = 1;
      for (let i = 1; i < points.length - 1; i++) if (points[i][4] > points[k][4]) k = i;
      // The editor's mapping (tf_editor.js): radius 6, a 14-pixel colour strip.
      const plot = canvas.height - 14;
      const toPage = (value, alpha) => ({
        x: rect.left + value * rect.width,
        y: rect.top + ((1 - alpha) * (plot - 12) + 6) * rect.height / canvas.height,
      });
      return { k, before: points[k].slice(), from: toPage(points[k][0], points[k][4]), to: toPage(points[k][0], points[k][4] * 0.25) };
    });
    before = after;
    await drag(page, tf.from, tf.to);
    await settled(page, 'TF point move');
    after = await canvasPixels(page);
    const moved = await page.evaluate((k) => window.penumbraViewer.scene().transfer_function.points[k], tf.k);
    check(moved[4] < tf.before[4] * 0.5, `TF point ${tf.k} alpha ${tf.before[4]} -> ${moved[4].toFixed(3)}`);
    check(difference(before, after) > 0.5, `moving the TF point changed the canvas (by ${difference(before, after).toFixed(2)})`);

    // 5. Orbit the camera with the mouse.
    const viewBox = await page.locator('#view').boundingBox();
    before = after;
    await drag(page, { x: viewBox.x + viewBox.width / 2, y: viewBox.y + viewBox.height / 2 },
                     { x: viewBox.x + viewBox.width / 2 + 60, y: viewBox.y + viewBox.height / 2 + 10 });
    await settled(page, 'orbit');
    after = await canvasPixels(page);
    check(difference(before, after) > 0.5, `orbiting changed the canvas (by ${difference(before, after).toFixed(2)})`);

    // 6. The first light's size: 15 degrees makes the directional light a
    // distant one, and cone-shadows (whose cone follows the light, 5 degrees
    // for a directional one) changes.
    await page.selectOption('#technique-select', 'cone-shadows');
    await settled(page, 'technique cone-shadows');
    before = await canvasPixels(page);
    await page.locator('.light-size-value').first().fill('15');
    await page.locator('.light-size-value').first().dispatchEvent('change');
    await settled(page, 'light size 15 degrees');
    after = await canvasPixels(page);
    const sized = await page.evaluate(() => window.penumbraViewer.scene().lights[0]);
    check(sized.type === 'distant' && sized.angle_deg === 15, `the light is distant with angle_deg 15 (${JSON.stringify(sized)})`);
    check(difference(before, after) > 0.5, `the light's size changed the canvas (by ${difference(before, after).toFixed(2)})`);

    // The size's conversions (light_panel.js setLightSize), without frames.
    const conversions = await page.evaluate(async () => {
      const { setLightSize } = await import('./light_panel.js');
      const steps = (light, sizes) => sizes.map((size) => { setLightSize(light, size); return JSON.stringify(light); });
      return [
        ...steps({ type: 'directional', direction: [0, 0, -1] }, [3, 0]),
        ...steps({ type: 'point', position: [0, 0, 9] }, [2, 0]),
        ...steps({ type: 'distant', direction: [0, 0, -1], profile: 'gaussian', angle_deg: 4 }, [0]),
        ...steps({ type: 'disk', position: [0, 0, 9], direction: [0, 0, -1], radius: 1 }, [0]),
      ];
    });
    check(JSON.stringify(conversions) === JSON.stringify([
      '{"type":"distant","direction":[0,0,-1],"angle_deg":3}', '{"type":"directional","direction":[0,0,-1]}',
      '{"type":"sphere","position":[0,0,9],"radius":2}', '{"type":"point","position":[0,0,9]}',
      '{"type":"distant","direction":[0,0,-1],"profile":"gaussian","angle_deg":0}',
      '{"type":"disk","position":[0,0,9],"direction":[0,0,-1],"radius":0}',
    ]), `sizes convert directional <-> distant and point <-> sphere only (${conversions.join(' ')})`);

    // 7. pathtrace, progressive: a scene loaded with 1 path per pixel a frame
    // and at most 3; the viewer asks for frames until the server says done.
    const traced = await page.evaluate(() => {
      const scene = JSON.parse(JSON.stringify(window.penumbraViewer.scene()));
      scene.render.technique = 'pathtrace';
      scene.render.params = { spp: 1, min_spp: 2, max_total_spp: 3 };
      return JSON.stringify(scene);
    });
    const framesBefore = await page.evaluate(() => window.penumbraViewer.fullFrames);
    await page.setInputFiles('#load-scene', { name: 'scene.json', mimeType: 'application/json', buffer: Buffer.from(traced) });
    await settled(page, 'pathtrace converged');
    const progress = await page.evaluate(() => ({ spp: window.penumbraViewer.spp, converged: window.penumbraViewer.converged,
                                                  frames: window.penumbraViewer.fullFrames }));
    check(progress.spp === 3 && progress.converged, `pathtrace reached 3 spp and stopped (${JSON.stringify(progress)})`);
    check(progress.frames - framesBefore === 3, `3 frames of 1 spp each (${progress.frames - framesBefore})`);
    check((await page.textContent('#spp')).startsWith('3 spp'), `the spp read-out: ${await page.textContent('#spp')}`);

    // 8. The reference beside the technique: cone-shadows in the view,
    // pathtrace (the panel's pathtrace parameters of step 7) beside it.
    await page.selectOption('#technique-select', 'cone-shadows');
    await page.check('#reference-toggle');
    await settled(page, 'reference beside cone-shadows');
    const referencePixels = await page.evaluate(() => {
      const small = document.createElement('canvas');
      small.width = small.height = 64;
      const ctx = small.getContext('2d');
      ctx.drawImage(document.getElementById('reference'), 0, 0, 64, 64);
      return Array.from(ctx.getImageData(0, 0, 64, 64).data);
    });
    const shown = await page.evaluate(() => window.penumbraViewer.reference);
    check(shown.spp === 3 && shown.converged && shown.frames === 3, `the reference converged beside the view (${JSON.stringify(shown)})`);
    check(meanLevel(referencePixels) > 5, `the reference is not black (mean level ${meanLevel(referencePixels).toFixed(1)})`);
    check(await page.evaluate(() => window.penumbraViewer.scene().render.technique) === 'cone-shadows', 'the view stays cone-shadows');
    check(await page.isVisible('#reference'), 'the reference canvas is shown');

    // 9. Animated mesh detail: a scene of one mesh whose detail has a time.
    // The row shows; while it is on the time advances and each step is drawn.
    await page.uncheck('#reference-toggle');
    const animated = JSON.stringify({
      volume: { builtin: 'empty', size: [32, 32, 32] },
      camera: { eye: [0, -80, 30], target: [0, 0, 0], up: [0, 0, 1], fov_deg: 30 },
      lights: [{ type: 'directional', direction: [0.3, 0.5, -0.8] }],
      material: { ambient: 0.2 },
      meshes: [{ builtin: 'sphere', scale: 12, material: { detail: { type: 'fbm', frequency: 2, time: 0 },
        transfer_function: { points: [[-1, 0.1, 0.1, 0.1, 0.0], [0.2, 0.5, 0.3, 0.2, 0.05], [1, 1, 1, 1, 0.9]],
                             range: 'data' } } }],
      render: { technique: 'convolution' },
    });
    await page.setInputFiles('#load-scene', { name: 'mesh.json', mimeType: 'application/json', buffer: Buffer.from(animated) });
    await settled(page, 'animated mesh scene');
    check(await page.isVisible('#detail-time-row'), 'the animate-detail row shows for a scene with animated detail');
    const still = await canvasPixels(page);
    const animationStart = await page.evaluate(() => window.penumbraViewer.fullFrames);
    await page.check('#animate-detail');
    await page.waitForFunction(() => window.penumbraViewer.scene().meshes[0].material.detail.time >= 0.199, null,
                               { timeout: 30000 });
    await page.uncheck('#animate-detail');
    await settled(page, 'animation stopped');
    const animation = await page.evaluate(() => ({ time: window.penumbraViewer.scene().meshes[0].material.detail.time,
                                                   frames: window.penumbraViewer.fullFrames }));
    check(animation.frames - animationStart >= 5, `a frame per detail step (${animation.frames - animationStart} frames to t = ${animation.time.toFixed(2)})`);
    check((await page.textContent('#detail-time-value')) === `t = ${animation.time.toFixed(2)}`, 'the time read-out follows');
    const animatedPixels = await canvasPixels(page);
    check(difference(still, animatedPixels) > 0.3,
          `the detail moved in the view (mean change ${difference(still, animatedPixels).toFixed(2)} codes)`);

    const frameTime = await page.textContent('#frame-time');
    check(/render [\d.]+ ms/.test(frameTime), `frame-time read-out: ${frameTime}`);
    check(await page.evaluate(() => window.penumbraViewer.errors) === 0, 'no error banner');
    await page.screenshot({ path: join(outDir, 'viewer.png') });
    log(`screenshot: ${join(outDir, 'viewer.png')}`);
  } finally {
    await context.close();
    rmSync(profile, { recursive: true, force: true });
    child.kill('SIGTERM');
  }
  check(consoleErrors.length === 0, `no console errors${consoleErrors.length ? ': ' + consoleErrors.join(' | ') : ''}`);
}

const watchdog = setTimeout(() => { log('FAIL: the test took over 100 s'); process.exit(1); }, 100000);
try {
  await run();
} catch (e) {
  failures++;
  log(`FAIL: ${e.stack || e}`);
}
clearTimeout(watchdog);
log(failures ? `${failures} check(s) failed` : 'all checks passed');
process.exit(failures ? 1 : 0);
