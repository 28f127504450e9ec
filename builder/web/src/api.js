// The builder's JSON API (builder/API.md): one function per endpoint. A failed request throws
// an Error whose message is the server's one-line error.

export class ApiError extends Error {
  constructor(message, status, data) {
    super(message);
    this.status = status;
    this.data = data; // the error's JSON ({error, ...}), when the server sent one
  }
}

async function request(method, url, body) {
  const init = { method, headers: {} };
  if (body !== undefined) {
    init.headers['Content-Type'] = 'application/json';
    init.body = JSON.stringify(body);
  }
  let response;
  try {
    response = await fetch(url, init);
  } catch (e) {
    throw new ApiError(
      `the builder's server does not answer (${e.message}): is plantarch builder still running?`,
      0,
    );
  }
  const type = response.headers.get('Content-Type') ?? '';
  const data = type.includes('application/json') ? await response.json() : await response.text();
  if (!response.ok) {
    const message =
      typeof data === 'object' && data?.error
        ? data.error
        : `${method} ${url}: HTTP ${response.status}`;
    const json = typeof data === 'object' ? data : undefined;
    throw new ApiError(message, response.status, json);
  }
  return data;
}

const enc = encodeURIComponent;

export const api = {
  species: () => request('GET', '/api/species'),
  speciesDetail: (name) => request('GET', `/api/species/${enc(name)}`),
  thumbnailUrl: (name) => `/api/species/${enc(name)}/thumbnail.png`,
  checkSpecies: (body) => request('POST', '/api/species/check', body),
  saveSpecies: (body) => request('POST', '/api/species/save', body),
  startBuild: (project, from) =>
    request('POST', '/api/builds', from ? { project, from } : { project }),
  build: (id) => request('GET', `/api/builds/${enc(id)}`),
  cancelBuild: (id) => request('DELETE', `/api/builds/${enc(id)}`),
  /** The scene for the view, with flat or textured materials (look: {materials, textureSize}). */
  sceneUrl: (id, look) =>
    look?.materials === 'textured'
      ? `/api/builds/${enc(id)}/scene.glb?materials=textured&texture_size=${enc(look.textureSize)}`
      : `/api/builds/${enc(id)}/scene.glb`,
  renderUrl: (id, w, h) => `/api/builds/${enc(id)}/render.png?w=${w}&h=${h}`,
  exportFiles: (body) => request('POST', '/api/export', body),
  /** The download of an export; `variant` holds its variant's fields (materials, nodes ...). */
  downloadUrl: ({ build, format, per_plant, name }, variant = {}) =>
    `/api/export/download?build=${enc(build)}&format=${enc(format)}&per_plant=${per_plant ? 'true' : 'false'}&name=${enc(name || 'scene')}` +
    Object.entries(variant)
      .map(([k, v]) => `&${enc(k)}=${enc(v)}`)
      .join(''),
  config: () => request('GET', '/api/config'),
  defaults: () => request('GET', '/api/defaults'),
  saveProject: (name, project) => request('POST', '/api/projects/save', { name, project }),
  projects: () => request('GET', '/api/projects'),
  project: (name) => request('GET', `/api/projects/${enc(name)}`),
  datasetSpecs: () => request('GET', '/api/dataset/specs'),
  datasetSpec: (path) => request('GET', `/api/dataset/spec?path=${enc(path)}`),
  checkDataset: (body) => request('POST', '/api/dataset/check', body),
  previewDataset: (body) => request('POST', '/api/dataset/preview', body),
  startDatasetRun: (body) => request('POST', '/api/dataset/runs', body),
  datasetRun: (id) => request('GET', `/api/dataset/runs/${enc(id)}`),
  cancelDatasetRun: (id) => request('DELETE', `/api/dataset/runs/${enc(id)}`),
};
