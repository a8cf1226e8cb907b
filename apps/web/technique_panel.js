// The technique picker and its controls, generated from the parameter tables
// that GET /api/techniques returns (the engine's registry): a slider for
// float and int, a checkbox for bool, a list for choice. A technique added to
// the engine later gets its controls here with no change to this file.
// Values are kept per technique, so switching back restores them.

export class TechniquePanel {
  // onChange(technique, params, final)
  constructor(select, summary, container, onChange) {
    this.select = select;
    this.summary = summary;
    this.container = container;
    this.onChange = onChange;
    this.techniques = [];
    this.values = {};  // technique name -> {param: value} (only those set)
    select.addEventListener('change', () => {
      this.show(select.value);
      this.onChange(this.current(), this.params(), true);
    });
  }

  // `defaults`: technique name -> {param: value} the viewer starts with
  // instead of the table's default (a scene's own params still win).
  setTechniques(list, defaults = {}) {
    this.techniques = list;
    for (const [name, values] of Object.entries(defaults)) {
      if (!this.values[name]) this.values[name] = { ...values };
    }
    this.select.replaceChildren(...list.map((t) => {
      const option = document.createElement('option');
      option.value = t.name;
      option.textContent = t.name;
      option.title = t.summary;
      return option;
    }));
  }

  // Adopts a scene's technique and its parameters.
  setFromScene(render) {
    const name = render.technique;
    this.values[name] = { ...(render.params || {}) };
    this.select.value = name;
    this.show(name);
  }

  current() { return this.select.value; }
  params() { return this.paramsFor(this.current()); }
  paramsFor(name) { return { ...(this.values[name] || {}) }; }
  info(name) { return this.techniques.find((t) => t.name === name); }

  show(name) {
    const info = this.info(name);
    this.container.replaceChildren();
    this.summary.textContent = info ? info.summary : '';
    if (!info) return;
    const values = this.values[name] || (this.values[name] = {});
    for (const spec of info.parameters) this.container.append(this.control(name, spec, values));
  }

  control(technique, spec, values) {
    const row = document.createElement('div');
    row.className = 'param';
    row.dataset.name = spec.name;
    row.title = spec.doc;
    const head = document.createElement('div');
    head.className = 'name';
    const label = document.createElement('span');
    label.textContent = spec.name.replaceAll('_', ' ');
    const readout = document.createElement('output');
    readout.className = 'muted';
    head.append(label, readout);
    row.append(head);
    const value = spec.name in values ? values[spec.name] : spec.default;
    const set = (v, final) => {
      values[spec.name] = v;
      this.onChange(technique, this.params(), final);
    };
    let input;
    if (spec.type === 'float' || spec.type === 'int') {
      input = document.createElement('input');
      input.type = 'range';
      input.min = spec.min;
      input.max = spec.max;
      input.step = spec.type === 'int' ? 1 : (spec.max - spec.min) / 1000;
      input.value = value;
      const show = () => { readout.textContent = spec.type === 'int' ? input.value : Number(input.value).toPrecision(3); };
      show();
      input.addEventListener('input', () => { show(); set(Number(input.value), false); });
      input.addEventListener('change', () => set(Number(input.value), true));
    } else if (spec.type === 'bool') {
      input = document.createElement('input');
      input.type = 'checkbox';
      input.checked = Boolean(value);
      input.addEventListener('change', () => set(input.checked, true));
    } else {
      input = document.createElement('select');
      for (const choice of spec.choices || []) {
        const option = document.createElement('option');
        option.value = option.textContent = choice;
        input.append(option);
      }
      input.value = value;
      input.addEventListener('change', () => set(input.value, true));
    }
    input.name = spec.name;
    row.append(input);
    const doc = document.createElement('div');
    doc.className = 'muted';
    doc.textContent = spec.doc;
    row.append(doc);
    return row;
  }
}
