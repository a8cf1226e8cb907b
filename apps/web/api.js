// The server's HTTP API (apps/server/http_server.h lists the endpoints).
// Errors come back as JSON {error, key, status}; they are thrown as ApiError.

export class ApiError extends Error {
  constructor(status, body) {
    super(body && body.error ? body.error : `HTTP ${status}`);
    this.status = status;
    this.key = body && body.key ? body.key : '';
  }
}

async function check(response) {
  if (response.ok) return response;
  let body = null;
  try { body = await response.json(); } catch (e) { /* not JSON: keep the status */ }
  throw new ApiError(response.status, body);
}

async function json(url, options = {}) {
  const response = await check(await fetch(url, options));
  return response.json();
}

function send(method, body) {
  return { method, headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) };
}

export const api = {
  techniques: () => json('/api/techniques'),
  volumes: () => json('/api/volumes'),
  createSession: (scene) => json('/api/sessions', send('POST', scene ? { scene } : {})),
  putScene: (id, scene) => json(`/api/sessions/${id}/scene`, send('PUT', scene)),
  getScene: (id) => json(`/api/sessions/${id}/scene`),
  volumeInfo: (id) => json(`/api/sessions/${id}/volume`),
  loadVolume: (id, volume) => json(`/api/sessions/${id}/volume`, send('POST', volume)),
  convertPreset: (text, name) =>
    json('/api/presets' + (name ? `?name=${encodeURIComponent(name)}` : ''),
         { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: text }),

  // A frame: the image blob and the server's timings (response headers).
  async frame(id, request) {
    const response = await check(await fetch(`/api/sessions/${id}/frame`, send('POST', request)));
    const header = (name) => Number(response.headers.get(name) || 0);
    return {
      blob: await response.blob(),
      prepareMs: header('X-Prepare-Ms'),
      renderMs: header('X-Render-Ms'),
      encodeMs: header('X-Encode-Ms'),
      samples: header('X-Samples'),
      // pathtrace: paths per pixel of the estimate shown, and whether it has
      // stopped growing (apps/server/http_server.h).
      spp: header('X-Spp'),
      converged: response.headers.get('X-Converged') === '1',
      technique: response.headers.get('X-Technique'),
    };
  },
};
