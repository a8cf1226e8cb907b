// Orbit, pan and zoom of a scene camera ({eye, target, up, fov_deg}), as the
// mouse drives them. The camera's own frame also places the light gizmos.
import { add, cross, dot, length, normalize, rotate, scale, sub } from './vector.js';

// right, up and toward-viewer unit vectors of the view.
export function cameraFrame(camera) {
  const forward = normalize(sub(camera.target, camera.eye));
  let right = cross(forward, camera.up);
  if (length(right) < 1e-6) right = cross(forward, [1, 0, 0]);
  right = normalize(right);
  return { right, up: cross(right, forward), toViewer: scale(forward, -1), forward };
}

// Turns the eye about the target: dx around the camera's up axis, dy over the
// top, stopping short of the poles so the view stays defined.
export function orbit(camera, dxPixels, dyPixels) {
  const up = normalize(camera.up);
  let offset = sub(camera.eye, camera.target);
  offset = rotate(offset, up, -dxPixels * 0.008);
  const right = normalize(cross(up, offset));
  const polar = Math.acos(Math.max(-1, Math.min(1, dot(normalize(offset), up))));
  const turn = Math.max(0.02 - polar, Math.min(Math.PI - 0.02 - polar, -dyPixels * 0.008));
  offset = rotate(offset, right, turn);  // a positive angle about right = cross(up, offset) tilts away from up
  return { ...camera, eye: add(camera.target, offset) };
}

// Moves eye and target together so the point under the mouse follows it.
export function pan(camera, dxPixels, dyPixels, viewHeightPixels) {
  const frame = cameraFrame(camera);
  const distance = length(sub(camera.eye, camera.target));
  const worldPerPixel = (2 * distance * Math.tan((camera.fov_deg || 30) * Math.PI / 360)) / viewHeightPixels;
  const move = add(scale(frame.right, -dxPixels * worldPerPixel), scale(frame.up, dyPixels * worldPerPixel));
  return { ...camera, eye: add(camera.eye, move), target: add(camera.target, move) };
}

// Dolly toward the target (wheel delta in pixels; positive moves away).
export function zoom(camera, wheelDelta) {
  const offset = sub(camera.eye, camera.target);
  const factor = Math.exp(Math.max(-1, Math.min(1, wheelDelta * 0.0015)));
  const next = scale(offset, factor);
  if (length(next) < 1e-3) return camera;
  return { ...camera, eye: add(camera.target, next) };
}
