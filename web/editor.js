// web/editor.js - the JSON editor: a <textarea> over a backdrop <pre> that mirrors its text, so that the
// member a problem+json error points at (errors[].pointer, RFC 6901) can be highlighted in place with the
// message written after its line. Also a compact pretty-printer for the presets.

// One line when it fits in `width` (with its indent and key), else one member per line.
export function pretty(v, ind = '', lead = 0, width = 44) {
  const flat = oneLine(v);
  if (ind.length + lead + flat.length <= width || v === null || typeof v !== 'object') return flat;
  const ni = ind + '  ';
  if (Array.isArray(v)) return '[\n' + v.map((x) => ni + pretty(x, ni, 0, width)).join(',\n') + '\n' + ind + ']';
  return '{\n' + Object.entries(v).map(([k, x]) => ni + JSON.stringify(k) + ': ' +
    pretty(x, ni, JSON.stringify(k).length + 2, width)).join(',\n') +
    '\n' + ind + '}';
}

function oneLine(v) {
  if (Array.isArray(v)) return '[' + v.map(oneLine).join(', ') + ']';
  if (v && typeof v === 'object')
    return '{' + Object.entries(v).map(([k, x]) => JSON.stringify(k) + ': ' + oneLine(x)).join(', ') + '}';
  return JSON.stringify(v);
}

// Where each JSON Pointer of the document lies: pointer -> {key: [start, end] | null, value: [start, end]}
// (character offsets). Parses as far as the text is valid JSON.
export function locate(text) {
  const map = new Map();
  let i = 0;
  const ws = () => { while (i < text.length && ' \t\r\n'.includes(text[i])) i++; };
  const fail = () => { throw new SyntaxError('at ' + i); };
  const str = () => {
    const s = i++;
    while (i < text.length && text[i] !== '"') i += text[i] === '\\' ? 2 : 1;
    if (i++ >= text.length) fail();
    return [s, i];
  };
  const esc = (k) => k.replace(/~/g, '~0').replace(/\//g, '~1');
  const value = (ptr, key) => {
    ws();
    const s = i;
    if (text[i] === '{' || text[i] === '[') {
      const obj = text[i++] === '{';
      ws();
      if (text[i] === (obj ? '}' : ']')) i++;
      else for (let k = 0; ; k++) {
        ws();
        if (obj) {
          if (text[i] !== '"') fail();
          const kr = str();
          ws();
          if (text[i++] !== ':') fail();
          value(ptr + '/' + esc(JSON.parse(text.slice(kr[0], kr[1]))), kr);
        } else {
          value(ptr + '/' + k, null);
        }
        ws();
        if (text[i] === ',') { i++; continue; }
        if (text[i++] !== (obj ? '}' : ']')) fail();
        break;
      }
    } else if (text[i] === '"') {
      str();
    } else {
      while (i < text.length && /[-+.\w]/.test(text[i])) i++;
      if (i === s) fail();
    }
    map.set(ptr, { key, value: [s, i] });
  };
  try { value('', null); } catch { /* valid up to here */ }
  return map;
}

// The character index of a UTF-8 byte offset.
function charIndex(text, byte) {
  let b = 0, i = 0;
  while (i < text.length && b < byte) {
    const cp = text.codePointAt(i);
    b += cp < 0x80 ? 1 : cp < 0x800 ? 2 : cp < 0x10000 ? 3 : 4;
    i += cp > 0xffff ? 2 : 1;
  }
  return i;
}

const html = (s) => s.replace(/[&<>]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;' })[c]);

export class Editor {
  constructor(root, onRun) {
    this.root = root;
    this.area = root.querySelector('textarea');
    this.back = root.querySelector('pre');
    this.marks = [];
    this.area.addEventListener('input', () => this.clearMarks());
    this.area.addEventListener('scroll', () => this.sync());
    this.area.addEventListener('keydown', (e) => {
      if (e.key === 'Enter' && (e.ctrlKey || e.metaKey)) { e.preventDefault(); onRun(); }
      if (e.key === 'Tab' && !e.shiftKey && !e.ctrlKey && !e.altKey) {
        e.preventDefault();
        this.area.setRangeText('  ', this.area.selectionStart, this.area.selectionEnd, 'end');
        this.clearMarks();
      }
    });
  }

  get text() { return this.area.value; }

  set text(t) {
    this.area.value = t;
    this.area.scrollTop = this.area.scrollLeft = 0;
    this.clearMarks();
  }

  sync() {
    this.back.scrollTop = this.area.scrollTop;
    this.back.scrollLeft = this.area.scrollLeft;
  }

  clearMarks() {
    this.marks = [];
    this.render();
  }

  // errors: [{pointer, detail}] from a problem document. Each gets a range in the text: the member named
  // (key through value on its first line), else its nearest existing ancestor; "" with "near byte N" is
  // that byte. Returns the marks [{start, end, line, pointer, detail}].
  mark(errors) {
    const text = this.text, where = locate(text);
    this.marks = errors.map((e) => {
      let start = 0, end = 0;
      const near = /near byte (\d+)/.exec(e.detail || '');
      if (e.pointer === '' && near) {
        start = Math.min(charIndex(text, +near[1]), text.length); // "near": back to the last thing read
        while (start > 0 && (start === text.length || /\s/.test(text[start]))) start--;
        end = start + 1;
      } else {
        let p = e.pointer || '';
        while (!where.has(p) && p !== '') p = p.slice(0, p.lastIndexOf('/'));
        const loc = where.get(p);
        if (loc) [start, end] = [loc.key ? loc.key[0] : loc.value[0], loc.value[1]];
      }
      const eol = text.indexOf('\n', start);
      if (eol >= 0 && end > eol) end = Math.max(eol, start + 1);
      return { start, end, line: text.slice(0, start).split('\n').length, pointer: e.pointer, detail: e.detail };
    });
    this.render();
    const first = this.marks[0];
    if (first) { // scroll the first one into view
      const lh = parseFloat(getComputedStyle(this.area).lineHeight) || 18;
      this.area.scrollTop = Math.max(0, (first.line - 3) * lh);
      this.sync();
    }
    return this.marks;
  }

  select(mk) {
    this.area.focus();
    this.area.setSelectionRange(mk.start, mk.end);
  }

  // The backdrop: the same text (transparent), the marked ranges, each line's messages after it.
  render() {
    const text = this.text;
    const ms = [...this.marks].sort((a, b) => a.start - b.start);
    let out = '', at = 0;
    const msgs = new Map();
    for (const mk of ms) {
      const eol = text.indexOf('\n', mk.start) < 0 ? text.length : text.indexOf('\n', mk.start);
      if (!msgs.has(eol)) msgs.set(eol, []);
      msgs.get(eol).push(mk.detail);
    }
    const stops = [...new Set([...ms.flatMap((m) => [m.start, m.end]), ...msgs.keys()])].sort((a, b) => a - b);
    let open = 0;
    for (const s of stops) {
      out += html(text.slice(at, s)) + (open > 0 ? '</mark>' : '');
      at = s;
      if (msgs.has(s)) out += '<span class="msg">  \u25c0 ' + html(msgs.get(s).join(' \u00b7 ')) + '</span>';
      open = ms.filter((m) => m.start <= s && s < m.end).length;
      if (open > 0) out += '<mark>';
    }
    out += html(text.slice(at)) + (open > 0 ? '</mark>' : '') + '\n';
    this.back.innerHTML = out;
    this.root.dataset.errorLines = ms.map((m) => m.line).join(',');
    this.sync();
  }
}
