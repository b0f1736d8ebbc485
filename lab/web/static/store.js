// What the page keeps in this browser, so that a reload (or the same address later) finds
// the student's work again: the model files opened in the page (IndexedDB: a MERL table is
// 33 MB of binary data) and the editor's text of each model or exercise (localStorage,
// written synchronously on every change, so a reload right after typing loses nothing).
const DB_NAME = "brdf-lab";
const FILES = "files"; // model name -> { name, fileName, data: string | ArrayBuffer, saved }
const DRAFT_PREFIX = "brdf-lab.draft."; // + model or exercise name -> the editor's text

/** Why the browser keeps nothing (a private window, storage turned off), or "". */
export let storeProblem = "";

const request = (req) => new Promise((resolve, reject) => {
  req.onsuccess = () => resolve(req.result);
  req.onerror = () => reject(req.error);
});

let opening = null;
function database() {
  opening ??= new Promise((resolve, reject) => {
    if (!globalThis.indexedDB) throw new Error("this browser has no IndexedDB");
    const req = indexedDB.open(DB_NAME, 1);
    req.onupgradeneeded = () => req.result.createObjectStore(FILES, { keyPath: "name" });
    req.onsuccess = () => resolve(req.result);
    req.onerror = () => reject(req.error);
    req.onblocked = () => reject(new Error("another tab of the lab holds an older store open"));
  });
  return opening;
}

async function files(mode) {
  const db = await database();
  return db.transaction(FILES, mode).objectStore(FILES);
}

const remember = (err) => {
  storeProblem = `this browser keeps no files for the page (${err?.message || err}): ` +
    "after a reload, open your files again";
  return null;
};

/** Keeps an opened file under its model's name (replacing an earlier one of that name). */
export async function keepFile(name, file) {
  try {
    const binary = /\.binary$/i.test(file.name);
    const data = binary ? await file.arrayBuffer() : await file.text();
    const store = await files("readwrite");
    await request(store.put({ name, fileName: file.name, data, saved: Date.now() }));
    return true;
  } catch (err) {
    remember(err);
    return false;
  }
}

/** The files kept earlier, as File objects with their model names: [{name, file}]. */
export async function keptFiles() {
  try {
    // Nothing kept yet: the store is made by the first file kept, not by every visit (making
    // it delays the first picture by about 10 ms). Browsers that cannot list stores open it.
    const stores = await globalThis.indexedDB?.databases?.();
    if (stores && !stores.some((s) => s.name === DB_NAME)) return [];
    const records = await request((await files("readonly")).getAll());
    return records.map((r) => ({ name: r.name, file: new File([r.data], r.fileName) }));
  } catch (err) {
    remember(err);
    return [];
  }
}

/** Forgets the kept file of a model. */
export async function forgetFile(name) {
  try {
    await request((await files("readwrite")).delete(name));
  } catch (err) {
    remember(err);
  }
}

/** The editor's text for `name`, or null. */
export function draft(name) {
  try {
    return localStorage.getItem(DRAFT_PREFIX + name);
  } catch {
    return null;
  }
}

/** Keeps the editor's text for `name`; `null` (the text is the original again) forgets it. */
export function keepDraft(name, text) {
  try {
    if (text === null) localStorage.removeItem(DRAFT_PREFIX + name);
    else localStorage.setItem(DRAFT_PREFIX + name, text);
  } catch (err) {
    storeProblem = `this browser does not keep your edits (${err.message}): download them with "save"`;
  }
}

/** The names with a kept editor text. */
export function draftNames() {
  try {
    return Object.keys(localStorage).filter((k) => k.startsWith(DRAFT_PREFIX)).map((k) => k.slice(DRAFT_PREFIX.length));
  } catch {
    return [];
  }
}
