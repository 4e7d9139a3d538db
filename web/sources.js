// web/sources.js - the sources by name. The daemon's reports (well-posedness checks, theorems, records) cite
// them by the project's working labels (the word "seed" and a number, 000 to 004), which tell a reader
// nothing; everything the page shows from an answer goes through named() first, so the page says
// "Höschl 1983 section 15" where the report has the label of 003. Where the name already stands before the
// label (the right-hand framework: "Matrosov & Finogenko 1995" and the label of 004) the label is dropped.

export const SOURCES = {
  '000': 'Babov\u00e1kov\u00e1 2012',
  '001': 'Pra\u017e\u00e1k & Rajagopal 2016',
  '002': 'Cibulka 2014',
  '003': 'H\u00f6schl 1983',
  '004': 'Matrosov & Finogenko 1995',
};

const LABEL = /\b[Ss]eed (00[0-4])\b/g;
const REPEATED = Object.entries(SOURCES).map(([n, name]) =>
  [new RegExp(`${name.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')},?\\s*[Ss]eed ${n}\\b`, 'g'), name]);

// A text with each label replaced by its source's name.
export function namedText(s) {
  if (typeof s !== 'string' || !/[Ss]eed 00/.test(s)) return s;
  for (const [re, name] of REPEATED) s = s.replace(re, name);
  return s.replace(LABEL, (_, n) => SOURCES[n]);
}

// A copy of a JSON value with every string named (the meta line's report, an error line, a problem document).
export function named(v) {
  if (typeof v === 'string') return namedText(v);
  if (Array.isArray(v)) return v.map(named);
  if (v && typeof v === 'object') return Object.fromEntries(Object.entries(v).map(([k, x]) => [k, named(x)]));
  return v;
}
