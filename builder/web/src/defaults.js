// What the page takes from its server instead of restating it (GET /api/defaults,
// builder/API.md): a project file's defaults (the project's, a ground's, each layout's
// block's), the organ label colours and the export formats, all made by the server from
// plantarch's C++ declarations. main.js loads them once, before anything uses them.

let served = null;

/** Sets the server's defaults (the JSON value of GET /api/defaults). */
export function setDefaults(value) {
  served = value;
}

/** The server's defaults; an Error before setDefaults. */
export function defaults() {
  if (!served) throw new Error("the server's defaults are not loaded (GET /api/defaults)");
  return served;
}
