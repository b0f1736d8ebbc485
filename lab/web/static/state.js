// The page's state: one LabState holds what the page shows (models, panels, lights, the
// registry's settings) and is handed to every module that reads or changes it. The views,
// their settings (defaults, ranges, kinds) and the constants come from the manifest that
// lab/web/site.py writes from the Python registry (lab/views, lab/constants.py).

export const MAX_PANELS = 6;
export const DEFAULT_SIZE = 384; // render size of a sphere (the address's size=)
// One colour per panel, in every view that overlays models (the desktop's first colours).
export const PALETTE = ["#56b4e9", "#e69f00", "#009e73", "#f0e442", "#cc79a7", "#d55e00"]; // Okabe-Ito: apart under colour blindness (tests/test_a11y_colour.py)
// The page's first light (theta 0: at the eye); the desktop's default light is its own.
const DEFAULT_LIGHT = { theta: 45, phi: 0, rgb: [1, 1, 1] };
// The views every panel draws itself (panel.js, polar.js); the others are page modules.
export const CORE_VIEWS = ["sphere", "polar"];

/** Four significant digits: what a slider's value is shown and kept with. */
export const round = (x) => Number(x.toPrecision(4));

export class LabState {
  constructor() {
    this.files = {}; // path under shaders/ -> text
    this.models = {}; // name -> parsed model
    this.modelErrors = {}; // name -> header error text
    this.order = []; // model names as the pickers list them
    this.panels = [];
    this.constants = {}; // lab/constants.py, from the manifest
    this.registry = []; // the manifest's views (lab/views), in their order
    this.specs = {}; // setting name -> {default, min, max, step, label, choices, kind, view}
    this.modules = {}; // view name -> its page module's VIEW (views/NAME.js)
    this.settings = {}; // setting name -> value: one name in Python, here and in the address
    // Directional lights in camera space; the polar plot shows the plane of incidence of
    // the first. Ambient is radiance added everywhere on the sphere.
    this.lights = [{ ...DEFAULT_LIGHT, rgb: [...DEFAULT_LIGHT.rgb] }];
    this.ambient = [0, 0, 0];
    this.active = 0; // the light that dragging on a sphere moves
    this.size = DEFAULT_SIZE;
    this.embed = false;
    // Slides: only these controls (null: all), the lobe against θo, each plot on its own scale.
    this.show = null;
    this.plot = "polar";
    this.scaleEach = false;
    this.notes = [];
    this.views = []; // page modules shown besides the sphere and the polar plot, in order
    this.fast = false; // a slider is moving: the costly views draw a coarse version
    this.presets = []; // the desktop lab's presets (lab/app/presets/*.toml)
    this.exerciseList = [];
    this.environments = null; // the IBL view's maps: names and size
    this.measuredCode = ""; // lab/measured/measured.glsl
    this.measuredTable = null; // how lab/measured/merl.py reads a table (the manifest's)
    this.builtMs = null; // the page built, nothing drawn yet (ms since navigation)
    this.firstRenderMs = null; // the sphere and polar plot of every panel drawn (ms since navigation)
    this.viewsRenderMs = null; // every view in sight drawn, the costly ones coarse
    this.fullRenderMs = null; // every view at full quality
    this.idleDrawnMs = null; // the views out of sight drawn too (while the page was idle)
    this.renderListener = () => {};
  }

  get light() {
    return { theta: this.lights[0].theta, phi: this.lights[0].phi };
  }

  /** Takes the registry's views and settings from the manifest; every setting at its default. */
  readRegistry(views) {
    this.registry = views;
    this.specs = {};
    for (const view of views) {
      for (const [name, spec] of Object.entries(view.settings)) this.specs[name] = { ...spec, view: view.name };
    }
    this.defaultSettings();
  }

  /** The constants view `name`'s Python module sends its page module (ViewSpec.page_data). */
  viewData(name) {
    return this.registry.find((v) => v.name === name)?.data ?? {};
  }

  /** The page modules' views in the registry's order (the views the page can show). */
  get pageViews() {
    return this.registry.filter((v) => this.modules[v.name]).map((v) => v.name);
  }

  defaultSettings() {
    this.settings = Object.fromEntries(Object.entries(this.specs).map(([name, s]) => [name, s.default]));
  }

  /** The lights and every setting back to their defaults (the models are the panels'). */
  resetLook() {
    this.defaultSettings();
    this.lights = [{ ...DEFAULT_LIGHT, rgb: [...DEFAULT_LIGHT.rgb] }];
    this.ambient = [0, 0, 0];
    this.active = 0;
  }

  /** Sets a registry setting, as its kind and clamped to its range; throws on a name that is
   * no setting or a value that is not a number (the caller words the note). */
  set(name, value) {
    const spec = this.specs[name];
    if (!spec) throw new Error(`no setting ${name}`);
    if (spec.kind === "bool") {
      this.settings[name] = Boolean(value);
      return this.settings[name];
    }
    let number = Number(value);
    if (!Number.isFinite(number)) throw new Error(`${name}: not a number`);
    if (spec.kind === "int") number = Math.round(number);
    if (spec.min !== null) number = Math.max(number, spec.min);
    if (spec.max !== null) number = Math.min(number, spec.max);
    this.settings[name] = number;
    return number;
  }

  /** Something the pictures depend on changed: draw again (soon; scheduler.js listens). */
  requestRender() {
    this.renderListener();
  }
}
