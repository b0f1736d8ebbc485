// On a phone (a screen narrower than 640 px) a panel with extra views shows one view at a
// time, picked from a menu above its pictures: "sphere and polar plot" first, then each view
// the page added (its `.view` boxes, by their data-view names). Wider screens show every
// view. This module owns only that menu and the `switched-off` class; it reads the panels'
// markup as lab.js builds it and follows it as views come and go.

const PHONE = "(max-width: 640px)";
const CORE = "sphere and polar plot";

/** The extra views of a panel (its second `.views` box), in the page's order. */
const extraViews = (panel) => [...panel.querySelectorAll(":scope > .views + .views > .view")];

/** Keep one panel's menu and views in step with the screen and the views it holds. */
function sync(panel, phone) {
  const core = panel.querySelector(":scope > .views");
  const extra = extraViews(panel);
  let menu = panel.querySelector(":scope > label.view-switch");
  const show = (chosen) => {
    core?.classList.toggle("switched-off", chosen !== CORE);
    for (const view of extra) view.classList.toggle("switched-off", view.dataset.view !== chosen);
  };
  if (!phone || !core || extra.length === 0) {
    if (menu) menu.hidden = true;
    core?.classList.remove("switched-off");
    for (const view of extra) view.classList.remove("switched-off");
    return;
  }
  if (!menu) {
    const select = document.createElement("select");
    select.addEventListener("change", () => show(select.value));
    menu = document.createElement("label");
    menu.className = "view-switch";
    menu.append("view ", select);
    menu.title = "one view at a time on a small screen: pick which";
    core.before(menu);
  }
  menu.hidden = false;
  const select = menu.querySelector("select");
  const names = [CORE, ...extra.map((v) => v.dataset.view)];
  const known = [...select.options].map((o) => o.value);
  if (names.join("\n") !== known.join("\n")) {
    // New options only when the views changed: this observer sees its own changes too.
    const keep = names.includes(select.value) ? select.value : CORE;
    select.replaceChildren(...names.map((name) => new Option(name, name)));
    select.value = keep;
  }
  show(select.value);
}

/** Watch the panels (and the screen's width) from now on. */
export function initViewSwitch() {
  const panels = document.getElementById("panels");
  if (!panels) return;
  const media = matchMedia(PHONE);
  const update = () => {
    const phone = media.matches && !document.body.classList.contains("embed"); // not in slides
    for (const panel of panels.querySelectorAll(":scope > .panel")) sync(panel, phone);
  };
  media.addEventListener("change", update);
  // Panels and their views are added and replaced by lab.js; class changes are not watched.
  new MutationObserver(update).observe(panels, { childList: true, subtree: true });
  update();
}

initViewSwitch();
